//! How the stress of a body follows from its displacement: the small-strain
//! (total) form or the incremental updated Lagrangian form (thesis §3.2,
//! eqs. 3.4, 3.6 and 3.16).
use fv_materials::{updated_lagrangian_stress, LargeStrainMaterial, Material, MaterialState};
use fv_mesh::{Tensor, Vector};

/// The constitutive side of one body.
#[derive(Debug)]
pub enum StressLaw {
    /// Small strain (eq. 3.17): σ̂ = σ of the total displacement gradient,
    /// on the initial mesh.
    Small(Box<dyn Material>),
    /// Incremental updated Lagrangian (eq. 3.6): the unknown is the
    /// increment Δu on the mesh of the start of the increment, the stress
    /// comes from the relative deformation gradient f = I + (∇Δu)ᵀ applied
    /// to the committed state, and the surface force is σ̂ = jσ·f⁻ᵀ (3.16).
    UpdatedLagrangian {
        /// The constitutive law.
        law: Box<dyn LargeStrainMaterial>,
        /// Committed and trial state of every cell.
        state: MaterialState,
    },
}

impl StressLaw {
    /// Whether the formulation is the updated Lagrangian one.
    #[inline]
    pub fn is_updated_lagrangian(&self) -> bool {
        matches!(self, StressLaw::UpdatedLagrangian { .. })
    }

    /// Model name as in the case file.
    pub fn name(&self) -> &'static str {
        match self {
            StressLaw::Small(m) => m.name(),
            StressLaw::UpdatedLagrangian { law, .. } => law.name(),
        }
    }

    /// Implicit stiffness 2μ + λ (thesis §3.2.2, used for every model).
    pub fn implicit_stiffness(&self) -> f64 {
        match self {
            StressLaw::Small(m) => m.implicit_stiffness(),
            StressLaw::UpdatedLagrangian { law, .. } => law.implicit_stiffness(),
        }
    }

    /// The thickness stretch λ_z of `cell` (its latest evaluated state) by
    /// which a plane-stress body's balance scales the Cauchy stress (it
    /// integrates λ_z σ, force per unit initial thickness,
    /// `fv_materials::PlaneStress`); 1 for every other body.
    #[inline]
    pub fn thickness_stretch(&self, cell: usize) -> f64 {
        match self {
            StressLaw::UpdatedLagrangian { law, state } if law.per_initial_thickness() => {
                let lz = state.trial(cell).f[(2, 2)];
                if lz.is_finite() && lz > 0.0 {
                    lz
                } else {
                    1.0
                }
            }
            _ => 1.0,
        }
    }

    /// Shear modulus μ.
    pub fn shear_modulus(&self) -> f64 {
        match self {
            StressLaw::Small(m) => m.shear_modulus(),
            StressLaw::UpdatedLagrangian { law, .. } => law.shear_modulus(),
        }
    }

    /// Cauchy stress σ and surface-force tensor σ̂ at a point of `cell`
    /// (a boundary face) with gradient `grad` (total for small strain, of
    /// the increment otherwise); the state is not changed. The force through
    /// an area vector Γ of the mesh is σ̂·Γ. `None` when the increment
    /// inverts the point (det f ≤ 0).
    #[inline]
    pub fn point_stress(&self, cell: usize, grad: &Tensor) -> Option<(Tensor, Tensor)> {
        match self {
            StressLaw::Small(m) => {
                let s = m.stress(grad);
                Some((s, s))
            }
            StressLaw::UpdatedLagrangian { state, .. } => self.point_stress_in(state, cell, grad),
        }
    }

    /// [`Self::point_stress`] of point `i` of another state than the
    /// cells' (e.g. the boundary faces'); updated Lagrangian only (`None`
    /// under small strain, whose stress has no state).
    #[inline]
    pub fn point_stress_in(
        &self,
        state: &MaterialState,
        i: usize,
        grad: &Tensor,
    ) -> Option<(Tensor, Tensor)> {
        match self {
            StressLaw::Small(_) => None,
            StressLaw::UpdatedLagrangian { law, .. } => {
                let sigma = law.stress_at(state, i, grad)?;
                let f = Tensor::identity() + grad.transpose();
                Some((sigma, updated_lagrangian_stress(&sigma, &f)?))
            }
        }
    }

    /// Equivalent plastic strain of every cell (the latest evaluated, trial
    /// state; equal to the committed one after a commit), for plastic models
    /// only.
    pub fn plastic_strain(&self) -> Option<&[f64]> {
        match self {
            StressLaw::UpdatedLagrangian { law, state } if law.name() == "neo-hookean-plastic" => {
                Some(state.trial_equivalent_plastic_strain())
            }
            _ => None,
        }
    }
}

/// Area vector in the current configuration, j f⁻ᵀ·Γ (Nanson), of a face
/// with area vector `gamma` on the mesh and increment gradient `grad`
/// (`gamma` itself under small strain or when f is singular).
#[inline]
pub fn current_area_vector(updated_lagrangian: bool, grad: &Tensor, gamma: &Vector) -> Vector {
    if !updated_lagrangian {
        return *gamma;
    }
    let f = Tensor::identity() + grad.transpose();
    let j = f.determinant();
    match f.try_inverse() {
        Some(fi) if j > 0.0 => fi.transpose() * gamma * j,
        _ => *gamma,
    }
}
