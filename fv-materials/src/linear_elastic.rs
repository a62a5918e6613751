//! Hooke's law for small strains, with an optional plane-stress variant.
use crate::{
    lame_from_young_poisson, LargeStrainMaterial, Material, MaterialError, PointState, Tensor,
};

/// Isotropic linear elasticity, σ = μ(∇u + ∇uᵀ) + λ tr(∇u) I (eq. 3.17).
///
/// With `plane_stress`, λ is replaced by λ* = 2μλ/(λ + 2μ) so that a
/// one-cell-thick model with σ_zz-free behaviour in the plane is obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearElastic {
    /// Shear modulus μ.
    pub mu: f64,
    /// First Lamé parameter λ (λ* under plane stress).
    pub lambda: f64,
}

impl LinearElastic {
    /// From Young's modulus and Poisson's ratio.
    pub fn new(e: f64, nu: f64, plane_stress: bool) -> Result<Self, MaterialError> {
        let (mu, lambda) = lame_from_young_poisson(e, nu)?;
        let lambda = if plane_stress {
            2.0 * mu * lambda / (lambda + 2.0 * mu)
        } else {
            lambda
        };
        Ok(LinearElastic { mu, lambda })
    }
}

impl Material for LinearElastic {
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
    fn stress(&self, g: &Tensor) -> Tensor {
        let tr = g.trace();
        let mut s = (g + g.transpose()) * self.mu;
        s[(0, 0)] += self.lambda * tr;
        s[(1, 1)] += self.lambda * tr;
        s[(2, 2)] += self.lambda * tr;
        s
    }
}

/// The small-strain model in the incremental interface: the increments add,
/// ∇u = ∇u_n + ∇Δu (the state keeps F = I + (∇u)ᵀ), and σ is eq. 3.17 of the
/// total gradient. Not objective: meant for small strains and rotations.
impl LargeStrainMaterial for LinearElastic {
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
        let f = committed.f + grad_du.transpose();
        let grad_u = (f - Tensor::identity()).transpose();
        Some((self.stress(&grad_u), PointState { f, ..*committed }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniaxial_stress_recovers_young_modulus() {
        let (e, nu) = (210e9, 0.3);
        let m = LinearElastic::new(e, nu, false).unwrap();
        // uniaxial stress state: eps_xx = s/E, eps_yy = eps_zz = -nu s/E
        let s = 1e6;
        let g = Tensor::from_diagonal(&nalgebra::Vector3::new(s / e, -nu * s / e, -nu * s / e));
        let sig = m.stress(&g);
        assert!((sig[(0, 0)] - s).abs() < 1e-6 * s);
        assert!(sig[(1, 1)].abs() < 1e-6 * s && sig[(2, 2)].abs() < 1e-6 * s);
    }

    #[test]
    fn plane_stress_has_no_out_of_plane_stress_effect() {
        let (e, nu) = (200.0, 0.25);
        let m = LinearElastic::new(e, nu, true).unwrap();
        // in-plane uniaxial stress: eps_yy = -nu eps_xx, eps_zz not in the model
        let exx = 1e-3;
        let g = Tensor::from_diagonal(&nalgebra::Vector3::new(exx, -nu * exx, 0.0));
        let sig = m.stress(&g);
        assert!((sig[(0, 0)] - e * exx).abs() < 1e-9);
        assert!(sig[(1, 1)].abs() < 1e-9);
    }

    #[test]
    fn rejects_bad_parameters() {
        assert!(LinearElastic::new(0.0, 0.3, false).is_err());
        assert!(LinearElastic::new(1.0, 0.5, false).is_err());
        assert!(LinearElastic::new(-1.0, 0.3, false).is_err());
    }

    #[test]
    fn increments_add_up_to_the_total_gradient() {
        let m = LinearElastic::new(200e9, 0.3, false).unwrap();
        let g = Tensor::new(1.0, 0.3, -0.2, 0.5, -0.4, 0.1, 0.2, 0.7, 0.6) * 1e-4;
        let mut st = LargeStrainMaterial::new_state(&m, 2);
        let mut sigma = vec![Tensor::zeros(); 2];
        for _ in 0..10 {
            m.update_stress(&[g, -g], &mut st, &mut sigma).unwrap();
            st.commit();
        }
        let total = Material::stress(&m, &(g * 10.0));
        assert!((sigma[0] - total).norm() < 1e-12 * total.norm());
        assert!((sigma[1] + total).norm() < 1e-12 * total.norm());
        assert_eq!(st.equivalent_plastic_strain(), &[0.0, 0.0]);
    }
}
