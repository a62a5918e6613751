//! Compressible neo-Hookean hyperelasticity with the thesis's uncoupled
//! volumetric term (eq. 2.25).
use crate::large_strain::hyperelastic_update;
use crate::{
    lame_from_young_poisson, LargeStrainMaterial, MaterialError, MaterialState, PointState, Tensor,
};

/// Deviatoric part dev(A) = A − tr(A)/3 I.
#[inline]
pub(crate) fn dev(a: &Tensor) -> Tensor {
    let p = a.trace() / 3.0;
    let mut d = *a;
    d[(0, 0)] -= p;
    d[(1, 1)] -= p;
    d[(2, 2)] -= p;
    d
}

/// Symmetric part (A + Aᵀ)/2, to keep b̄ symmetric under rounding.
#[inline]
pub(crate) fn sym(a: &Tensor) -> Tensor {
    (a + a.transpose()) * 0.5
}

/// Cauchy stress σ = τ/J with τ = (K/2)(J² − 1) I + s (eq. 2.25, s = μ dev b̄_e).
#[inline]
pub(crate) fn cauchy(bulk: f64, j: f64, s: &Tensor) -> Tensor {
    let p = 0.5 * bulk * (j * j - 1.0);
    let mut tau = *s;
    tau[(0, 0)] += p;
    tau[(1, 1)] += p;
    tau[(2, 2)] += p;
    tau / j
}

/// Shear and bulk moduli (μ, K) from E and ν (eq. 2.27). Under
/// `plane_stress`, λ is replaced by λ* = 2μλ/(λ + 2μ) as in
/// [`crate::LinearElastic`], i.e. K = λ* + 2μ/3 (exact for small strains
/// only).
pub(crate) fn moduli(e: f64, nu: f64, plane_stress: bool) -> Result<(f64, f64), MaterialError> {
    let (mu, lambda) = lame_from_young_poisson(e, nu)?;
    let lambda = if plane_stress {
        2.0 * mu * lambda / (lambda + 2.0 * mu)
    } else {
        lambda
    };
    Ok((mu, lambda + 2.0 * mu / 3.0))
}

/// Compressible neo-Hookean solid (eq. 2.25 without plasticity, F^e = F):
///
/// τ = J σ = (K/2)(J² − 1) I + μ dev(b̄),  b̄ = J^(−2/3) F·Fᵀ (eq. 2.26).
///
/// Hyperelastic, so the stress depends only on the total F, which the state
/// carries (F ← f·F each increment).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeoHookean {
    /// Shear modulus μ (eq. 2.27).
    pub mu: f64,
    /// Bulk modulus K (eq. 2.27).
    pub bulk: f64,
}

impl NeoHookean {
    /// From Young's modulus and Poisson's ratio (eq. 2.27); see
    /// [`crate::LinearElastic::new`] for `plane_stress`.
    pub fn new(e: f64, nu: f64, plane_stress: bool) -> Result<Self, MaterialError> {
        let (mu, bulk) = moduli(e, nu, plane_stress)?;
        Ok(NeoHookean { mu, bulk })
    }

    /// Cauchy stress of total deformation gradient `f` (eqs. 2.25–2.26);
    /// `None` when det F ≤ 0.
    #[inline]
    pub fn cauchy_stress(&self, f: &Tensor) -> Option<Tensor> {
        let j = f.determinant();
        if !(j > 0.0) {
            return None;
        }
        let b_bar = sym(&(f * f.transpose())) * j.powf(-2.0 / 3.0);
        Some(cauchy(self.bulk, j, &(dev(&b_bar) * self.mu)))
    }
}

impl LargeStrainMaterial for NeoHookean {
    fn name(&self) -> &'static str {
        "neo-hookean"
    }
    fn implicit_stiffness(&self) -> f64 {
        self.bulk + 4.0 * self.mu / 3.0
    }
    fn shear_modulus(&self) -> f64 {
        self.mu
    }
    fn new_state(&self, n_cells: usize) -> MaterialState {
        MaterialState::new(n_cells, false)
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
    use crate::large_strain::test_support::uniaxial_increment;
    use crate::{LinearElastic, Material};
    use nalgebra::Vector3;

    fn grad_of(f: &Tensor) -> Tensor {
        (f - Tensor::identity()).transpose()
    }

    /// Uniaxial stress, F = diag(λ, λ_t, λ_t), J = λλ_t²:
    /// b̄ = J^(−2/3) diag(λ², λ_t², λ_t²), dev b̄ = J^(−2/3)(λ² − λ_t²) diag(2/3, −1/3, −1/3),
    /// τ_22 = 0 ⇔ (K/2)(J² − 1) = (μ/3) J^(−2/3)(λ² − λ_t²),
    /// τ_11 = μ J^(−2/3)(λ² − λ_t²), σ_11 = τ_11/J, nominal stress
    /// (reaction per undeformed area) P = σ_11 λ_t².
    #[test]
    fn uniaxial_stretch_matches_closed_form() {
        let m = NeoHookean::new(10e6, 0.3, false).unwrap();
        let (mu, k) = (m.mu, m.bulk);
        let lam = 1.5;
        let g = |lt: f64| {
            let j = lam * lt * lt;
            0.5 * k * (j * j - 1.0) - mu / 3.0 * j.powf(-2.0 / 3.0) * (lam * lam - lt * lt)
        };
        let mut lt = 1.0;
        for _ in 0..50 {
            let h = 1e-7;
            lt -= g(lt) / ((g(lt + h) - g(lt - h)) / (2.0 * h));
        }
        assert!(
            g(lt).abs() < 1e-6,
            "closed-form lateral stretch not converged"
        );
        let j = lam * lt * lt;
        let sigma_cf = mu * j.powf(-2.0 / 3.0) * (lam * lam - lt * lt) / j;
        let p_cf = sigma_cf * lt * lt;

        // one shot from the undeformed state
        let f = Tensor::from_diagonal(&Vector3::new(lam, lt, lt));
        let (s, _) = m
            .update_point(&PointState::default(), &grad_of(&f))
            .unwrap();
        assert!((s[(0, 0)] - sigma_cf).abs() < 1e-12 * sigma_cf);
        assert!(s[(1, 1)].abs() < 1e-9 * sigma_cf && s[(2, 2)].abs() < 1e-9 * sigma_cf);
        assert!(s.norm() - s.diagonal().norm() < 1e-12 * sigma_cf);

        // 50 increments, lateral stretch found from the material's σ_22 = 0
        let mut p = PointState::default();
        let mut sig = Tensor::zeros();
        let n = 50;
        for i in 0..n {
            let (l0, l1) = (
                1.0 + 0.5 * i as f64 / n as f64,
                1.0 + 0.5 * (i + 1) as f64 / n as f64,
            );
            (sig, p) = uniaxial_increment(&m, &p, l1 / l0, mu);
        }
        assert!((p.f[(0, 0)] - lam).abs() < 1e-12);
        assert!((p.f[(1, 1)] - lt).abs() < 1e-9, "{} vs {lt}", p.f[(1, 1)]);
        let p_nominal = sig[(0, 0)] * p.f[(1, 1)] * p.f[(2, 2)];
        let err = (p_nominal - p_cf).abs() / p_cf;
        assert!(err < 1e-8, "nominal stress error {err:e}");
    }

    /// Simple shear F = I + γ e_1⊗e_2 (u = (γy, 0, 0)): J = 1, b̄ = b =
    /// [[1+γ², γ, 0], [γ, 1, 0], [0, 0, 1]], so σ = μ dev b:
    /// σ_12 = μγ, σ_11 = 2μγ²/3, σ_22 = σ_33 = −μγ²/3, other shear zero.
    #[test]
    fn simple_shear_matches_closed_form() {
        let m = NeoHookean::new(10e6, 0.3, false).unwrap();
        let mu = m.mu;
        let gamma = 1.0;
        // (∇u)_21 = ∂u_1/∂x_2 = γ
        let mut g = Tensor::zeros();
        g[(1, 0)] = gamma;
        let (s, p) = m.update_point(&PointState::default(), &g).unwrap();
        assert_eq!(p.f[(0, 1)], gamma);
        let expect = Tensor::new(
            2.0 * mu * gamma * gamma / 3.0,
            mu * gamma,
            0.0,
            mu * gamma,
            -mu * gamma * gamma / 3.0,
            0.0,
            0.0,
            0.0,
            -mu * gamma * gamma / 3.0,
        );
        assert!((s - expect).norm() < 1e-12 * mu, "{s} vs {expect}");
    }

    /// Path independence: stretch then shear in 400 committed relative
    /// increments (f_k = F_k F_(k−1)⁻¹) gives the stress of the single step.
    #[test]
    fn many_small_increments_equal_one_large() {
        let m = NeoHookean::new(10e6, 0.3, false).unwrap();
        let path = |t: f64| {
            let a = (2.0 * t).min(1.0);
            let b = (2.0 * t - 1.0).max(0.0);
            let mut f = Tensor::from_diagonal(&Vector3::new(1.0 + 0.5 * a, 1.0 - 0.15 * a, 1.0));
            f[(0, 1)] = 0.8 * b;
            f[(2, 0)] = -0.3 * b;
            f
        };
        let n = 400;
        let mut st = m.new_state(1);
        let mut sigma = [Tensor::zeros()];
        for i in 0..n {
            let f_rel =
                path((i + 1) as f64 / n as f64) * path(i as f64 / n as f64).try_inverse().unwrap();
            m.update_stress(&[grad_of(&f_rel)], &mut st, &mut sigma)
                .unwrap();
            st.commit();
        }
        let (one, _) = m
            .update_point(&PointState::default(), &grad_of(&path(1.0)))
            .unwrap();
        let err = (sigma[0] - one).norm() / one.norm();
        assert!(err < 1e-12, "path error {err:e}");
        assert!((st.deformation_gradient()[0] - path(1.0)).norm() < 1e-13);
    }

    /// Small strains: eq. 2.25 reduces to Hooke's law with λ = K − 2μ/3.
    #[test]
    fn small_strain_limit_is_hooke() {
        let (e, nu) = (200e9, 0.3);
        let m = NeoHookean::new(e, nu, false).unwrap();
        let le = LinearElastic::new(e, nu, false).unwrap();
        assert!(
            (LargeStrainMaterial::implicit_stiffness(&m) - Material::implicit_stiffness(&le)).abs()
                < 1e-3
        );
        let g = Tensor::new(1.0, 0.3, -0.2, 0.5, -0.4, 0.1, 0.2, 0.7, 0.6) * 1e-7;
        let (s, _) = m.update_point(&PointState::default(), &g).unwrap();
        let s_lin = le.stress(&g);
        assert!((s - s_lin).norm() < 1e-5 * s_lin.norm());
        // plane stress uses the same λ*
        let m = NeoHookean::new(e, nu, true).unwrap();
        let le = LinearElastic::new(e, nu, true).unwrap();
        assert!((m.bulk - le.lambda - 2.0 * le.mu / 3.0).abs() < 1e-3);
    }

    #[test]
    fn rejects_bad_parameters() {
        let e = NeoHookean::new(-1.0, 0.3, false).unwrap_err().to_string();
        assert!(e.starts_with("E = -1"), "{e}");
        let e = NeoHookean::new(1.0, 0.5, false).unwrap_err().to_string();
        assert!(e.starts_with("nu = 0.5"), "{e}");
    }
}
