//! Hooke's law in the finite-strain setting: the St Venant–Kirchhoff solid,
//! the meaning of `model = "linear-elastic"` with `strain = "large"`.
use crate::{
    large_strain::hyperelastic_update, LargeStrainMaterial, LinearElastic, MaterialError,
    PointState, Tensor,
};

/// S = λ tr(E) I + 2μ E with the Green–Lagrange strain E = ½(FᵀF − I) and
/// σ = J⁻¹ F·S·Fᵀ: the same constants as [`LinearElastic`] (λ* under plane
/// stress), identical to it for small strains, and objective, so large
/// rotations produce no spurious stress. The state carries F (F ← f·F each
/// increment).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StVenantKirchhoff {
    /// Shear modulus μ.
    pub mu: f64,
    /// First Lamé parameter λ (λ* under plane stress).
    pub lambda: f64,
}

impl StVenantKirchhoff {
    /// From Young's modulus and Poisson's ratio (see [`LinearElastic::new`]).
    pub fn new(e: f64, nu: f64, plane_stress: bool) -> Result<Self, MaterialError> {
        let h = LinearElastic::new(e, nu, plane_stress)?;
        Ok(StVenantKirchhoff {
            mu: h.mu,
            lambda: h.lambda,
        })
    }

    /// Cauchy stress of total deformation gradient `f`; `None` when det F ≤ 0.
    #[inline]
    pub fn cauchy_stress(&self, f: &Tensor) -> Option<Tensor> {
        let j = f.determinant();
        if !(j > 0.0) {
            return None;
        }
        let e = (f.transpose() * f - Tensor::identity()) * 0.5;
        let s = e * (2.0 * self.mu) + Tensor::identity() * (self.lambda * e.trace());
        let sigma = f * s * f.transpose() / j;
        Some((sigma + sigma.transpose()) * 0.5)
    }
}

impl LargeStrainMaterial for StVenantKirchhoff {
    fn name(&self) -> &'static str {
        "linear-elastic"
    }
    fn implicit_stiffness(&self) -> f64 {
        2.0 * self.mu + self.lambda
    }
    fn shear_modulus(&self) -> f64 {
        self.mu
    }
    #[inline]
    fn update_point(
        &self,
        committed: &PointState,
        grad_du: &Tensor,
    ) -> Option<(Tensor, PointState)> {
        hyperelastic_update(committed, grad_du, |f| self.cauchy_stress(f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;

    #[test]
    fn small_strain_limit_is_hooke() {
        let m = StVenantKirchhoff::new(200e9, 0.3, false).unwrap();
        let h = LinearElastic::new(200e9, 0.3, false).unwrap();
        let g = Tensor::new(1.0, 0.3, -0.2, 0.5, -0.4, 0.1, 0.2, 0.7, 0.6) * 1e-7;
        let s = m
            .cauchy_stress(&(Tensor::identity() + g.transpose()))
            .unwrap();
        let r = h.stress(&g);
        assert!((s - r).norm() < 1e-5 * r.norm());
    }

    #[test]
    fn rigid_rotation_is_stress_free() {
        let m = StVenantKirchhoff::new(1.0, 0.3, false).unwrap();
        let rot = *nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::z_axis(), 1.2).matrix();
        let s = m.cauchy_stress(&rot).unwrap();
        assert!(s.norm() < 1e-14);
        // stretched then rotated: the stress rotates with the body
        let stretch = Tensor::from_diagonal(&nalgebra::Vector3::new(1.1, 1.0, 1.0));
        let s0 = m.cauchy_stress(&stretch).unwrap();
        let s1 = m.cauchy_stress(&(rot * stretch)).unwrap();
        assert!((s1 - rot * s0 * rot.transpose()).norm() < 1e-12);
        // uniaxial strain along x: S_xx = (λ + 2μ) E_xx, σ_xx = λ_x² S_xx / J
        let exx = 0.5 * (1.1f64 * 1.1 - 1.0);
        let sxx = (m.lambda + 2.0 * m.mu) * exx * 1.1 * 1.1 / 1.1;
        assert!((s0[(0, 0)] - sxx).abs() < 1e-14);
    }
}
