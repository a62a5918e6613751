//! Constitutive models.
//!
//! - [`Material`]: stateless small-strain stress from the total displacement
//!   gradient (Hooke, eq. 3.17).
//! - [`LargeStrainMaterial`]: the incremental updated Lagrangian form
//!   (eqs. 2.22–2.31): Cauchy stress of every cell from the relative
//!   deformation gradient f = I + (∇Δu)ᵀ of the current increment applied to
//!   a committed per-cell [`MaterialState`]; neo-Hookean ([`NeoHookean`],
//!   eq. 2.25) and neo-Hookean J2 plasticity ([`NeoHookeanPlastic`],
//!   eqs. 2.28–2.31) with [`Hardening`]; [`StVenantKirchhoff`] is Hooke's
//!   law for finite strain. [`LinearElastic`] implements both (additively).
//!
//! Tensor convention (as OpenFOAM and the thesis): the displacement gradient
//! is `(∇u)_ij = ∂u_j/∂x_i`, so the deformation gradient is F = I + (∇u)ᵀ;
//! stresses are symmetric Cauchy tensors, tension positive.
#![warn(missing_docs)]

mod hardening;
mod large_strain;
mod linear_elastic;
mod neo_hookean;
mod neo_hookean_plastic;
mod plane_stress;
mod st_venant_kirchhoff;

pub use hardening::Hardening;
pub use large_strain::{
    grad_du_in_updated, relative_deformation_gradient, updated_lagrangian_stress,
    LargeStrainMaterial, MaterialState, PointState,
};
pub use linear_elastic::LinearElastic;
pub use neo_hookean::NeoHookean;
pub use neo_hookean_plastic::NeoHookeanPlastic;
pub use plane_stress::PlaneStress;
pub use st_venant_kirchhoff::StVenantKirchhoff;

/// 3×3 tensor.
pub type Tensor = nalgebra::Matrix3<f64>;

/// Invalid material parameters.
#[derive(Debug, thiserror::Error)]
pub enum MaterialError {
    /// A parameter is out of its admissible range.
    #[error("{name} = {value}: {requirement}")]
    OutOfRange {
        /// Parameter name as in the case file.
        name: &'static str,
        /// Given value.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// A table parameter has no rows.
    #[error("{name} is empty: give at least one row")]
    EmptyTable {
        /// Parameter name as in the case file.
        name: &'static str,
    },
    /// One entry of a table parameter is out of its admissible range.
    #[error("{name}[{row}][{column}] = {value}: {requirement}")]
    InvalidTableEntry {
        /// Parameter name as in the case file.
        name: &'static str,
        /// Row index (from 0).
        row: usize,
        /// Column index (from 0).
        column: usize,
        /// Given value.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// The deformation of a cell is not invertible (det f ≤ 0, eq. 2.23).
    #[error("cell {cell}: relative Jacobian det f = {jacobian} is not positive (the increment inverts the cell)")]
    NonPositiveJacobian {
        /// Cell index.
        cell: usize,
        /// det f of the increment.
        jacobian: f64,
    },
}

/// A constitutive law: stress from kinematics (seam of `../DESIGN.md`).
pub trait Material: Send + Sync + std::fmt::Debug {
    /// Model name as written in the case file.
    fn name(&self) -> &'static str;
    /// Implicit stiffness 2μ + λ of the segregated Laplacian (thesis §3.2.2, eq. 3.2).
    fn implicit_stiffness(&self) -> f64;
    /// Shear modulus μ.
    fn shear_modulus(&self) -> f64;
    /// Cauchy stress for a small-strain displacement gradient (eq. 3.17).
    fn stress(&self, grad_u: &Tensor) -> Tensor;
}

/// Lamé parameters (μ, λ) from Young's modulus and Poisson's ratio.
pub fn lame_from_young_poisson(e: f64, nu: f64) -> Result<(f64, f64), MaterialError> {
    if !(e > 0.0 && e.is_finite()) {
        return Err(MaterialError::OutOfRange {
            name: "E",
            value: e,
            requirement: "must be positive and finite",
        });
    }
    if !(nu > -1.0 && nu < 0.5) {
        return Err(MaterialError::OutOfRange {
            name: "nu",
            value: nu,
            requirement: "must satisfy -1 < nu < 0.5",
        });
    }
    let mu = e / (2.0 * (1.0 + nu));
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    Ok((mu, lambda))
}
