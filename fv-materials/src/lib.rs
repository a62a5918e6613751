//! Constitutive models behind one trait ([`Material`]).
//!
//! Tensor convention (as OpenFOAM and the thesis): the displacement gradient
//! is `(∇u)_ij = ∂u_j/∂x_i`; stresses are symmetric Cauchy tensors, tension
//! positive.
#![warn(missing_docs)]

mod linear_elastic;

pub use linear_elastic::LinearElastic;

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
