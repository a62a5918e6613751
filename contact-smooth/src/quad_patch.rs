//! Quadrilateral Nagata patch (thesis eq. 4.79, Tables 4.8, 4.9 and 4.11).
//!
//! Corners `x₀₀, x₁₀, x₁₁, x₀₁` (in the face's vertex order) over
//! `0 ≤ η, ζ ≤ 1`:
//!
//! ```text
//! x(η, ζ) = c₀₀ + c₁₀ η + c₀₁ ζ + c₁₁ ηζ + c₂₀ η² + c₀₂ ζ² + c₂₁ η²ζ + c₁₂ ηζ²
//! ```
//!
//! (eq. 4.79 as printed omits the `c₀₂ ζ²` term that Tables 4.8 and 4.11
//! contain). Each side is the edge curve of eq. 4.76.
use crate::edge_curve::{curvature_parameter, EdgeCurveParams};
use crate::patch::{solve_2x2_least_squares, NagataPatch, PatchDerivatives, PatchDomain};
use fv_mesh::{Real, Vector};

/// Coefficients of a quadrilateral Nagata patch (Table 4.8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadPatch {
    /// `c₀₀ = x₀₀`.
    pub c00: Vector,
    /// `c₁₀ = x₁₀ − x₀₀ − c₁`.
    pub c10: Vector,
    /// `c₀₁ = x₀₁ − x₀₀ − c₄`.
    pub c01: Vector,
    /// `c₁₁ = x₁₁ − x₁₀ − x₀₁ + x₀₀ + c₁ − c₂ − c₃ + c₄`.
    pub c11: Vector,
    /// `c₂₀ = c₁`.
    pub c20: Vector,
    /// `c₀₂ = c₄`.
    pub c02: Vector,
    /// `c₂₁ = c₃ − c₁`.
    pub c21: Vector,
    /// `c₁₂ = c₂ − c₄`.
    pub c12: Vector,
    /// Corners `x₀₀, x₁₀, x₁₁, x₀₁`.
    pub corners: [Vector; 4],
}

impl Default for QuadPatch {
    fn default() -> Self {
        let z = Vector::zeros();
        QuadPatch {
            c00: z,
            c10: z,
            c01: z,
            c11: z,
            c20: z,
            c02: z,
            c21: z,
            c12: z,
            corners: [z; 4],
        }
    }
}

impl QuadPatch {
    /// The patch through corners `x = [x₀₀, x₁₀, x₁₁, x₀₁]` (the face's
    /// vertex order) with unit normals `n`.
    ///
    /// Curvature parameters (Table 4.9): `c₁` on `x₀₀x₁₀`, `c₂` on
    /// `x₁₀x₁₁`, `c₃` on `x₀₁x₁₁`, `c₄` on `x₀₀x₀₁`.
    pub fn new(x: [Vector; 4], n: [Vector; 4], params: &EdgeCurveParams) -> Self {
        let [x00, x10, x11, x01] = x;
        let [n00, n10, n11, n01] = n;
        let c1 = curvature_parameter(&(x10 - x00), &n00, &n10, params);
        let c2 = curvature_parameter(&(x11 - x10), &n10, &n11, params);
        let c3 = curvature_parameter(&(x11 - x01), &n01, &n11, params);
        let c4 = curvature_parameter(&(x01 - x00), &n00, &n01, params);
        QuadPatch {
            c00: x00,
            c10: x10 - x00 - c1,
            c01: x01 - x00 - c4,
            c11: x11 - x10 - x01 + x00 + c1 - c2 - c3 + c4,
            c20: c1,
            c02: c4,
            c21: c3 - c1,
            c12: c2 - c4,
            corners: x,
        }
    }

    /// The bilinear quadrilateral through the corners (curvature parameters zero).
    pub fn flat(x: [Vector; 4]) -> Self {
        let z = Vector::zeros();
        Self::new(x, [z; 4], &EdgeCurveParams::default())
    }
}

impl NagataPatch for QuadPatch {
    fn domain(&self) -> PatchDomain {
        PatchDomain::Square
    }

    fn point(&self, eta: Real, zeta: Real) -> Vector {
        let (ee, zz, ez) = (eta * eta, zeta * zeta, eta * zeta);
        self.c00
            + self.c10 * eta
            + self.c01 * zeta
            + self.c11 * ez
            + self.c20 * ee
            + self.c02 * zz
            + self.c21 * (ee * zeta)
            + self.c12 * (eta * zz)
    }

    fn derivatives(&self, eta: Real, zeta: Real) -> PatchDerivatives {
        PatchDerivatives {
            x: self.point(eta, zeta),
            s1: self.c10
                + self.c11 * zeta
                + self.c20 * (2.0 * eta)
                + self.c21 * (2.0 * eta * zeta)
                + self.c12 * (zeta * zeta),
            s2: self.c01
                + self.c11 * eta
                + self.c02 * (2.0 * zeta)
                + self.c21 * (eta * eta)
                + self.c12 * (2.0 * eta * zeta),
            x_ee: 2.0 * (self.c20 + self.c21 * zeta),
            x_ez: self.c11 + self.c21 * (2.0 * eta) + self.c12 * (2.0 * zeta),
            x_zz: 2.0 * (self.c02 + self.c12 * eta),
        }
    }

    /// Inverse of the bilinear map through the corners by three
    /// Gauss–Newton steps from the centre (exact for a parallelogram after
    /// the first).
    fn flat_start(&self, xs: &Vector) -> (Real, Real) {
        let [x00, x10, x11, x01] = self.corners;
        let (a, b, c) = (x10 - x00, x01 - x00, x11 - x10 - x01 + x00);
        let (mut eta, mut zeta) = self.domain().centre();
        for _ in 0..3 {
            let r = xs - (x00 + a * eta + b * zeta + c * (eta * zeta));
            let (ta, tb) = (a + c * zeta, b + c * eta);
            match solve_2x2_least_squares(&ta, &tb, &r) {
                Some((de, dz)) if de.is_finite() && dz.is_finite() => {
                    eta += de;
                    zeta += dz;
                }
                _ => break,
            }
        }
        (eta, zeta)
    }

    fn size(&self) -> Real {
        let [x00, x10, x11, x01] = self.corners;
        [
            x10 - x00,
            x11 - x10,
            x01 - x11,
            x00 - x01,
            x11 - x00,
            x01 - x10,
        ]
        .iter()
        .map(|e| e.norm())
        .fold(0.0, Real::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edge_curve::EdgeCurve;

    fn sphere_quad() -> ([Vector; 4], [Vector; 4]) {
        let x = [
            Vector::new(1.0, -0.2, -0.2).normalize(),
            Vector::new(1.0, 0.25, -0.2).normalize(),
            Vector::new(1.0, 0.2, 0.3).normalize(),
            Vector::new(1.0, -0.2, 0.2).normalize(),
        ];
        (x, x)
    }

    #[test]
    fn corners_and_sides_are_the_edge_curves() {
        let (x, n) = sphere_quad();
        let p = EdgeCurveParams::default();
        let q = QuadPatch::new(x, n, &p);
        let sides = [
            (
                EdgeCurve::new(x[0], x[1], &n[0], &n[1], &p),
                [0.0, 0.0],
                [1.0, 0.0],
            ),
            (
                EdgeCurve::new(x[1], x[2], &n[1], &n[2], &p),
                [1.0, 0.0],
                [0.0, 1.0],
            ),
            (
                EdgeCurve::new(x[3], x[2], &n[3], &n[2], &p),
                [0.0, 1.0],
                [1.0, 0.0],
            ),
            (
                EdgeCurve::new(x[0], x[3], &n[0], &n[3], &p),
                [0.0, 0.0],
                [0.0, 1.0],
            ),
        ];
        for (e, s, d) in sides {
            for k in 0..=8 {
                let t = k as Real / 8.0;
                let y = q.point(s[0] + t * d[0], s[1] + t * d[1]);
                assert!((y - e.point(t)).norm() < 1e-15);
            }
        }
        for (e, z, k) in [(0.0, 0.0, 0), (1.0, 0.0, 1), (1.0, 1.0, 2), (0.0, 1.0, 3)] {
            let m = q.normal(e, z).unwrap();
            assert!((m - n[k]).norm() < 1e-12, "corner {k}: {m:?}");
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let (x, n) = sphere_quad();
        let q = QuadPatch::new(x, n, &EdgeCurveParams::default());
        let (e, z, h) = (0.3, 0.7, 1e-6);
        let d = q.derivatives(e, z);
        let s1 = (q.point(e + h, z) - q.point(e - h, z)) / (2.0 * h);
        let s2 = (q.point(e, z + h) - q.point(e, z - h)) / (2.0 * h);
        assert!((s1 - d.s1).norm() < 1e-9 && (s2 - d.s2).norm() < 1e-9);
        let (dp, dm) = (q.derivatives(e + h, z), q.derivatives(e - h, z));
        assert!(((dp.s1 - dm.s1) / (2.0 * h) - d.x_ee).norm() < 1e-8);
        assert!(((dp.s2 - dm.s2) / (2.0 * h) - d.x_ez).norm() < 1e-8);
        let (dp, dm) = (q.derivatives(e, z + h), q.derivatives(e, z - h));
        assert!(((dp.s2 - dm.s2) / (2.0 * h) - d.x_zz).norm() < 1e-8);
    }

    #[test]
    fn flat_start_inverts_the_bilinear_map() {
        let (x, _) = sphere_quad();
        let q = QuadPatch::flat(x);
        let p = q.point(0.3, 0.8);
        let (e, z) = q.flat_start(&p);
        assert!((e - 0.3).abs() < 1e-6 && (z - 0.8).abs() < 1e-6, "{e} {z}");
    }
}
