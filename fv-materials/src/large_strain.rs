//! The incremental updated Lagrangian interface (thesis §2.1.3–2.1.4, §3.2.2):
//! per-cell state, the [`LargeStrainMaterial`] trait and the kinematics of
//! the increment (eqs. 2.23, 3.16).
//!
//! Per outer iteration the solver computes the gradient of the displacement
//! increment ∇Δu of every cell with respect to the configuration at the start
//! of the increment (the last committed one) and calls
//! [`LargeStrainMaterial::update_stress`]; it always starts from the
//! committed state, so iterations never accumulate. At the end of a converged
//! increment it calls [`MaterialState::commit`]; to redo an increment
//! (cut-back) [`MaterialState::discard`].
use crate::{MaterialError, Tensor};

/// Relative deformation gradient f = [∇_u(Δu)]ᵀ + I (eq. 2.23), with this
/// crate's convention (∇Δu)_ij = ∂Δu_j/∂x_i.
#[inline]
pub fn relative_deformation_gradient(grad_du: &Tensor) -> Tensor {
    grad_du.transpose() + Tensor::identity()
}

/// Stress tensor of the updated Lagrangian surface force, σ̂ = j σ·f⁻ᵀ
/// (eq. 3.16), j = det f. The force through a face with area vector Γ_u in
/// the updated (start-of-increment) configuration is `σ̂ * Γ_u` (matrix times
/// column vector) = σ·(j f⁻ᵀ·Γ_u) = σ·Γ (Nanson), as in eq. 2.21; note that
/// the row-vector product Γ_u·σ̂ would be wrong because σ̂ is not symmetric.
/// Returns `None` when f is singular.
#[inline]
pub fn updated_lagrangian_stress(sigma: &Tensor, f: &Tensor) -> Option<Tensor> {
    let j = f.determinant();
    let f_inv = f.try_inverse()?;
    Some(sigma * f_inv.transpose() * j)
}

/// ∇_u(Δu) = F⁻ᵀ·∇_o(Δu): the gradient of the increment with respect to the
/// updated configuration from the one with respect to the reference
/// configuration and the total deformation gradient F at the start of the
/// increment (for a solver that does not move its mesh). Returns `None`
/// when F is singular.
#[inline]
pub fn grad_du_in_updated(grad0_du: &Tensor, f_old: &Tensor) -> Option<Tensor> {
    Some(f_old.try_inverse()?.transpose() * grad0_du)
}

/// One increment of a hyperelastic law whose state is only F: F ← f·F and
/// σ = `cauchy`(F); `None` when f or F is not invertible.
#[inline]
pub(crate) fn hyperelastic_update(
    committed: &PointState,
    grad_du: &Tensor,
    cauchy: impl Fn(&Tensor) -> Option<Tensor>,
) -> Option<(Tensor, PointState)> {
    let f_rel = relative_deformation_gradient(grad_du);
    if !(f_rel.determinant() > 0.0) {
        return None;
    }
    let f = f_rel * committed.f;
    let sigma = cauchy(&f)?;
    Some((sigma, PointState { f, ..*committed }))
}

/// State of one material point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    /// Total deformation gradient F (for [`crate::LinearElastic`]: I + (∇u)ᵀ
    /// of the accumulated small-strain gradient).
    pub f: Tensor,
    /// Isochoric elastic left Cauchy–Green tensor b̄_e (eq. 2.26); identity
    /// for models without plasticity.
    pub be_bar: Tensor,
    /// Equivalent plastic strain ε̄_p (eq. 2.30).
    pub eps_p: f64,
}

impl Default for PointState {
    /// The undeformed, virgin state.
    fn default() -> Self {
        PointState {
            f: Tensor::identity(),
            be_bar: Tensor::identity(),
            eps_p: 0.0,
        }
    }
}

/// Per-cell fields of one state (struct of arrays).
#[derive(Debug, Clone, PartialEq)]
struct Fields {
    f: Vec<Tensor>,
    /// Empty for models without plasticity.
    be_bar: Vec<Tensor>,
    eps_p: Vec<f64>,
}

impl Fields {
    fn new(n: usize, plastic: bool) -> Self {
        Fields {
            f: vec![Tensor::identity(); n],
            be_bar: if plastic {
                vec![Tensor::identity(); n]
            } else {
                Vec::new()
            },
            eps_p: vec![0.0; n],
        }
    }

    fn copy_from(&mut self, other: &Fields) {
        self.f.copy_from_slice(&other.f);
        self.be_bar.copy_from_slice(&other.be_bar);
        self.eps_p.copy_from_slice(&other.eps_p);
    }

    #[inline]
    fn get(&self, i: usize) -> PointState {
        PointState {
            f: self.f[i],
            be_bar: self.be_bar.get(i).copied().unwrap_or_else(Tensor::identity),
            eps_p: self.eps_p[i],
        }
    }

    #[inline]
    fn set(&mut self, i: usize, p: &PointState) {
        self.f[i] = p.f;
        if let Some(b) = self.be_bar.get_mut(i) {
            *b = p.be_bar;
        }
        self.eps_p[i] = p.eps_p;
    }
}

/// Committed (end of the last converged increment) and trial (current outer
/// iteration) state of every cell, created by
/// [`LargeStrainMaterial::new_state`]. Memory: 2 × (9 or 18 + 1) f64 per cell.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialState {
    committed: Fields,
    trial: Fields,
}

impl MaterialState {
    /// Virgin state of `n_cells` cells; `plastic` stores b̄_e as well.
    pub fn new(n_cells: usize, plastic: bool) -> Self {
        let committed = Fields::new(n_cells, plastic);
        MaterialState {
            trial: committed.clone(),
            committed,
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.committed.f.len()
    }

    /// True when there are no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Committed state of cell `i`.
    #[inline]
    pub fn committed(&self, i: usize) -> PointState {
        self.committed.get(i)
    }

    /// Trial state of cell `i` (last [`LargeStrainMaterial::update_stress`]).
    #[inline]
    pub fn trial(&self, i: usize) -> PointState {
        self.trial.get(i)
    }

    /// Sets the trial state of cell `i`.
    #[inline]
    pub fn set_trial(&mut self, i: usize, p: &PointState) {
        self.trial.set(i, p);
    }

    /// End of a converged increment: trial becomes committed. No allocation.
    pub fn commit(&mut self) {
        self.committed.copy_from(&self.trial);
    }

    /// Drops the trial state (trial = committed), e.g. to redo an increment.
    pub fn discard(&mut self) {
        self.trial.copy_from(&self.committed);
    }

    /// Committed equivalent plastic strain ε̄_p of every cell (eq. 2.30; zero
    /// for elastic models): the `plastic_strain` output field.
    pub fn equivalent_plastic_strain(&self) -> &[f64] {
        &self.committed.eps_p
    }

    /// Trial equivalent plastic strain of every cell.
    pub fn trial_equivalent_plastic_strain(&self) -> &[f64] {
        &self.trial.eps_p
    }

    /// Committed total deformation gradient F of every cell.
    pub fn deformation_gradient(&self) -> &[Tensor] {
        &self.committed.f
    }

    /// Trial total deformation gradient F of every cell.
    pub fn trial_deformation_gradient(&self) -> &[Tensor] {
        &self.trial.f
    }

    /// Restart: the committed F, b̄_e (empty for elastic models) and ε̄_p
    /// of every cell, to be given back to [`Self::restore_committed`].
    pub fn committed_parts(&self) -> (&[Tensor], &[Tensor], &[f64]) {
        let c = &self.committed;
        (&c.f, &c.be_bar, &c.eps_p)
    }

    /// Restart: sets the committed state (each slice as long as
    /// [`Self::committed_parts`] gives it, else an error naming the part)
    /// and the trial state equal to it.
    pub fn restore_committed(
        &mut self,
        f: &[Tensor],
        be_bar: &[Tensor],
        eps_p: &[f64],
    ) -> Result<(), String> {
        let c = &mut self.committed;
        for (name, got, expected) in [
            ("f", f.len(), c.f.len()),
            ("be_bar", be_bar.len(), c.be_bar.len()),
            ("eps_p", eps_p.len(), c.eps_p.len()),
        ] {
            if got != expected {
                return Err(format!(
                    "material state '{name}': {got} values, expected {expected}"
                ));
            }
        }
        c.f.copy_from_slice(f);
        c.be_bar.copy_from_slice(be_bar);
        c.eps_p.copy_from_slice(eps_p);
        self.discard();
        Ok(())
    }
}

/// A constitutive law in the incremental updated Lagrangian form
/// (eqs. 2.22–2.31): stress from the relative deformation gradient of the
/// increment applied to a committed per-cell state.
pub trait LargeStrainMaterial: Send + Sync + std::fmt::Debug {
    /// Model name as written in the case file.
    fn name(&self) -> &'static str;

    /// Implicit stiffness 2μ + λ = K + 4μ/3 of the segregated Laplacian,
    /// used for every model (thesis §3.2.2, eqs. 3.2, 3.6).
    fn implicit_stiffness(&self) -> f64;

    /// Shear modulus μ.
    fn shear_modulus(&self) -> f64;

    /// Whether the stress this model returns is λ_z σ, the force per unit
    /// *initial* thickness of a plane-stress body ([`crate::PlaneStress`]);
    /// false for the three-dimensional models.
    fn per_initial_thickness(&self) -> bool {
        false
    }

    /// The hardening modulus H' = dσ_y/dε̄p at equivalent plastic strain
    /// `eps_p`, for plastic models (`None` for the others).
    fn hardening_slope(&self, _eps_p: f64) -> Option<f64> {
        None
    }

    /// Virgin state of `n_cells` cells for this model.
    fn new_state(&self, n_cells: usize) -> MaterialState {
        MaterialState::new(n_cells, false)
    }

    /// One material point: Cauchy stress and trial state after applying the
    /// increment with displacement-increment gradient `grad_du` (∇_u Δu,
    /// eq. 2.23) to `committed`. Pure; no allocation. `None` when det f ≤ 0.
    fn update_point(
        &self,
        committed: &PointState,
        grad_du: &Tensor,
    ) -> Option<(Tensor, PointState)>;

    /// Every cell: writes the Cauchy stress to `sigma` and the trial state,
    /// always starting from the committed state (call once per outer
    /// iteration). No allocation. Stops at the first cell whose increment is
    /// not invertible and reports it; cells before it are updated.
    ///
    /// # Panics
    /// When `grad_du`, `sigma` and `state` differ in length.
    fn update_stress(
        &self,
        grad_du: &[Tensor],
        state: &mut MaterialState,
        sigma: &mut [Tensor],
    ) -> Result<(), MaterialError> {
        assert_eq!(grad_du.len(), state.len(), "grad_du and state lengths");
        assert_eq!(sigma.len(), state.len(), "sigma and state lengths");
        for (i, (g, s)) in grad_du.iter().zip(sigma.iter_mut()).enumerate() {
            let (sig, trial) = self.update_point(&state.committed(i), g).ok_or(
                MaterialError::NonPositiveJacobian {
                    cell: i,
                    jacobian: relative_deformation_gradient(g).determinant(),
                },
            )?;
            *s = sig;
            state.set_trial(i, &trial);
        }
        Ok(())
    }

    /// Stress at a point other than a cell centre (e.g. a boundary face) from
    /// the committed state of `cell` and the increment gradient there; the
    /// state is not changed. `None` when det f ≤ 0.
    fn stress_at(&self, state: &MaterialState, cell: usize, grad_du: &Tensor) -> Option<Tensor> {
        self.update_point(&state.committed(cell), grad_du)
            .map(|(s, _)| s)
    }
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Homogeneous uniaxial-stress driver shared by the model tests.
    use super::*;

    /// Relative-gradient of f = diag(a, r, r): ∇Δu = (f − I)ᵀ.
    pub fn diag_grad(a: f64, r: f64) -> Tensor {
        Tensor::from_diagonal(&nalgebra::Vector3::new(a - 1.0, r - 1.0, r - 1.0))
    }

    /// One increment of uniaxial stress: axial relative stretch `a`, lateral
    /// relative stretch r found by Newton (numerical derivative) such that
    /// σ_22 = σ_33 = 0. Returns (σ, trial state).
    pub fn uniaxial_increment(
        m: &dyn LargeStrainMaterial,
        committed: &PointState,
        a: f64,
        scale: f64,
    ) -> (Tensor, PointState) {
        let s22 = |r: f64| m.update_point(committed, &diag_grad(a, r)).unwrap().0[(1, 1)];
        let mut r = 1.0 - 0.4 * (a - 1.0);
        for _ in 0..50 {
            let s = s22(r);
            if s.abs() < 1e-13 * scale {
                break;
            }
            let h = 1e-7;
            let ds = (s22(r + h) - s22(r - h)) / (2.0 * h);
            r -= s / ds;
        }
        let out = m.update_point(committed, &diag_grad(a, r)).unwrap();
        assert!(
            out.0[(1, 1)].abs() < 1e-9 * scale,
            "lateral stress {}",
            out.0[(1, 1)]
        );
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Hardening, LinearElastic, NeoHookean, NeoHookeanPlastic};

    fn rot(axis: nalgebra::Vector3<f64>, angle: f64) -> Tensor {
        *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix()
    }

    #[test]
    fn kinematics_of_the_increment() {
        let g = Tensor::new(0.1, 0.02, -0.03, 0.05, -0.04, 0.01, 0.0, 0.03, 0.07);
        let f = relative_deformation_gradient(&g);
        // f_ij = δ_ij + ∂Δu_i/∂x_j = δ_ij + g_ji
        assert_eq!(f[(0, 1)], 1.0 * g[(1, 0)]);
        assert_eq!(f[(1, 1)], 1.0 + g[(1, 1)]);
        // σ̂ Γ_u equals σ times the current area vector j f⁻ᵀ Γ_u (Nanson)
        let sigma = Tensor::new(3.0, 1.0, 0.5, 1.0, -2.0, 0.2, 0.5, 0.2, 1.0);
        let gamma_u = nalgebra::Vector3::new(0.3, -0.5, 0.8);
        let s_hat = updated_lagrangian_stress(&sigma, &f).unwrap();
        let gamma = f.try_inverse().unwrap().transpose() * gamma_u * f.determinant();
        assert!((s_hat * gamma_u - sigma * gamma).norm() < 1e-14);
        // updated-configuration gradient from the reference one:
        // F_new = F_old + (∇_oΔu)ᵀ and f = F_new F_old⁻¹
        let f_old = Tensor::new(1.2, 0.1, 0.0, -0.05, 0.9, 0.02, 0.0, 0.1, 1.05);
        let g0 = Tensor::new(0.01, -0.02, 0.0, 0.03, 0.01, 0.0, -0.01, 0.0, 0.02);
        let f_new = f_old + g0.transpose();
        let gu = grad_du_in_updated(&g0, &f_old).unwrap();
        let f_rel = relative_deformation_gradient(&gu);
        assert!((f_rel - f_new * f_old.try_inverse().unwrap()).norm() < 1e-15);
    }

    /// The state machine: update writes only the trial state, commit and
    /// discard copy between the two, and the plastic strain field follows.
    #[test]
    fn commit_and_discard() {
        let m = NeoHookeanPlastic::new(200e9, 0.3, false, Hardening::linear(250e6, 1e9).unwrap())
            .unwrap();
        let mut st = m.new_state(3);
        let mut sigma = vec![Tensor::zeros(); 3];
        // cell 1 far beyond yield, cells 0 and 2 elastic
        let mut g = vec![Tensor::zeros(); 3];
        g[0][(0, 0)] = 1e-4;
        g[1][(0, 1)] = 0.02;
        g[2][(2, 2)] = -1e-4;
        m.update_stress(&g, &mut st, &mut sigma).unwrap();
        assert_eq!(st.equivalent_plastic_strain(), &[0.0; 3]);
        let eps1 = st.trial_equivalent_plastic_strain()[1];
        assert!(eps1 > 0.01);
        assert_eq!(st.trial_equivalent_plastic_strain()[0], 0.0);
        assert_eq!(st.committed(1), PointState::default());
        let trial = st.clone();
        // discard: back to the committed state, also for the next update
        st.discard();
        assert_eq!(st.trial(1), PointState::default());
        assert_eq!(st.trial_equivalent_plastic_strain(), &[0.0; 3]);
        // the same update again gives the same trial (iterations don't accumulate)
        m.update_stress(&g, &mut st, &mut sigma).unwrap();
        m.update_stress(&g, &mut st, &mut sigma).unwrap();
        assert_eq!(st, trial);
        st.commit();
        assert_eq!(st.equivalent_plastic_strain()[1], eps1);
        assert_eq!(st.committed(1), trial.trial(1));
        // after commit, a zero increment keeps the stress and the state
        let sig_committed = sigma.clone();
        m.update_stress(&[Tensor::zeros(); 3], &mut st, &mut sigma)
            .unwrap();
        for (a, b) in sigma.iter().zip(&sig_committed) {
            assert!((a - b).norm() <= 1e-6 * b.norm().max(1.0));
        }
        assert!((st.trial_equivalent_plastic_strain()[1] - eps1).abs() < 1e-15);
        // stress_at uses the committed state and changes nothing
        let before = st.clone();
        let s = m.stress_at(&st, 1, &Tensor::zeros()).unwrap();
        assert!((s - sig_committed[1]).norm() <= 1e-6 * s.norm());
        assert_eq!(st, before);
    }

    #[test]
    fn inverted_cell_is_reported() {
        let m = NeoHookean::new(1e6, 0.3, false).unwrap();
        let mut st = m.new_state(2);
        let mut sigma = vec![Tensor::zeros(); 2];
        let mut g = vec![Tensor::zeros(); 2];
        g[1][(0, 0)] = -1.5; // f_11 = −0.5
        let e = m.update_stress(&g, &mut st, &mut sigma).unwrap_err();
        assert!(matches!(
            e,
            MaterialError::NonPositiveJacobian { cell: 1, .. }
        ));
        assert!(
            e.to_string()
                .starts_with("cell 1: relative Jacobian det f = -0.5"),
            "{e}"
        );
    }

    /// Objectivity: a rigid rotation increment R rotates the stress, σ → R σ Rᵀ,
    /// and leaves ε̄_p unchanged, for every model.
    #[test]
    fn rigid_rotation_increment_rotates_stress() {
        let hard = Hardening::linear(250e6, 1e9).unwrap();
        let models: Vec<Box<dyn LargeStrainMaterial>> = vec![
            Box::new(NeoHookean::new(200e9, 0.3, false).unwrap()),
            Box::new(NeoHookeanPlastic::new(200e9, 0.3, false, hard).unwrap()),
        ];
        let g1 = Tensor::new(0.03, 0.01, 0.0, 0.02, -0.01, 0.005, 0.0, 0.01, 0.004);
        let r = rot(nalgebra::Vector3::new(1.0, 2.0, -0.5), 0.7);
        for m in &models {
            let (s1, p1) = m.update_point(&PointState::default(), &g1).unwrap();
            // f = R ⇒ ∇Δu = (R − I)ᵀ
            let (s2, p2) = m
                .update_point(&p1, &(r - Tensor::identity()).transpose())
                .unwrap();
            let err = (s2 - r * s1 * r.transpose()).norm() / s1.norm();
            assert!(err < 1e-12, "{}: {err:e}", m.name());
            assert_eq!(p2.eps_p, p1.eps_p, "{}", m.name());
        }
        // the small-strain model is not objective: a rotation is a strain to it
        let le = LinearElastic::new(200e9, 0.3, false).unwrap();
        let (s, _) = le
            .update_point(
                &PointState::default(),
                &(r - Tensor::identity()).transpose(),
            )
            .unwrap();
        assert!(s.norm() > 1e9);
    }
}
