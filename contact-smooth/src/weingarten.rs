//! Unit normal (eq. 4.82) and its derivatives with respect to the local
//! coordinates by the Weingarten equations, as the Jacobian of eq. 4.84
//! needs them.
//!
//! With the first fundamental form `E = s₁·s₁`, `F = s₁·s₂`, `G = s₂·s₂`
//! and the second `L = x,ηη·n`, `M = x,ηζ·n`, `N = x,ζζ·n`:
//!
//! ```text
//! ∂n/∂η = [(MF − LG) s₁ + (LF − ME) s₂] / (EG − F²)
//! ∂n/∂ζ = [(NF − MG) s₁ + (MF − NE) s₂] / (EG − F²)
//! ```
use crate::patch::PatchDerivatives;
use fv_mesh::{Real, Vector};

/// Unit normal and its derivatives at one point of a patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalDerivatives {
    /// `n = s₁ × s₂ / |s₁ × s₂|` (eq. 4.82).
    pub n: Vector,
    /// `∂n/∂η`.
    pub n_eta: Vector,
    /// `∂n/∂ζ`.
    pub n_zeta: Vector,
    /// `|s₁ × s₂|`, the area Jacobian of the parametrisation.
    pub jacobian: Real,
}

/// Normal and Weingarten derivatives from the patch derivatives; `None`
/// where the parametrisation is singular (`|s₁ × s₂|` zero or not finite).
pub fn normal_derivatives(d: &PatchDerivatives) -> Option<NormalDerivatives> {
    let a = d.s1.cross(&d.s2);
    let j2 = a.norm_squared(); // = EG − F²
    let j = j2.sqrt();
    if !(j > 0.0 && j.is_finite()) {
        return None;
    }
    let n = a / j;
    let (e, f, g) = (d.s1.dot(&d.s1), d.s1.dot(&d.s2), d.s2.dot(&d.s2));
    let (l, m, nn) = (d.x_ee.dot(&n), d.x_ez.dot(&n), d.x_zz.dot(&n));
    let n_eta = ((m * f - l * g) * d.s1 + (l * f - m * e) * d.s2) / j2;
    let n_zeta = ((nn * f - m * g) * d.s1 + (m * f - nn * e) * d.s2) / j2;
    Some(NormalDerivatives {
        n,
        n_eta,
        n_zeta,
        jacobian: j,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edge_curve::EdgeCurveParams;
    use crate::patch::NagataPatch;
    use crate::quad_patch::QuadPatch;
    use crate::triangle_patch::TrianglePatch;

    fn check<P: NagataPatch>(p: &P, e: Real, z: Real) {
        let h = 1e-6;
        let w = normal_derivatives(&p.derivatives(e, z)).unwrap();
        let n = |e, z| p.normal(e, z).unwrap();
        let fe = (n(e + h, z) - n(e - h, z)) / (2.0 * h);
        let fz = (n(e, z + h) - n(e, z - h)) / (2.0 * h);
        assert!((fe - w.n_eta).norm() < 1e-8, "{fe:?} vs {:?}", w.n_eta);
        assert!((fz - w.n_zeta).norm() < 1e-8, "{fz:?} vs {:?}", w.n_zeta);
        assert!((w.n.norm() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn matches_finite_differences_of_the_normal() {
        let p = EdgeCurveParams::default();
        let x = [
            Vector::new(1.0, 0.1, 0.2).normalize(),
            Vector::new(0.8, 0.6, 0.1).normalize(),
            Vector::new(0.7, 0.3, 0.6).normalize(),
        ];
        // deliberately tilted normals: a general (non-spherical) patch
        let n = [
            (x[0] + Vector::new(0.1, 0.0, 0.0)).normalize(),
            x[1],
            (x[2] + Vector::new(0.0, -0.2, 0.1)).normalize(),
        ];
        check(&TrianglePatch::new(x, n, &p), 0.7, 0.2);
        let y = [
            Vector::new(1.0, -0.2, -0.2).normalize(),
            Vector::new(1.0, 0.25, -0.2).normalize(),
            Vector::new(1.0, 0.2, 0.3).normalize(),
            Vector::new(1.0, -0.2, 0.2).normalize(),
        ];
        let m = [
            y[0],
            (y[1] + Vector::new(0.0, 0.1, 0.1)).normalize(),
            y[2],
            y[3],
        ];
        check(&QuadPatch::new(y, m, &p), 0.4, 0.6);
    }

    #[test]
    fn singular_parametrisation_is_none() {
        let z = Vector::zeros();
        let d = PatchDerivatives {
            x: z,
            s1: Vector::x(),
            s2: 2.0 * Vector::x(),
            x_ee: z,
            x_ez: z,
            x_zz: z,
        };
        assert!(normal_derivatives(&d).is_none());
    }
}
