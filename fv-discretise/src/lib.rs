//! Finite-volume discretisation of the solid momentum equation (thesis §3.2)
//! and the sparse linear solvers it needs.
//!
//! Conventions: the displacement gradient is `(∇u)_ij = ∂u_j/∂x_i`; the
//! traction on a face with unit normal n is `σ·n` (σ symmetric).
#![warn(missing_docs)]

mod boundary_conditions;
mod least_squares_gradient;
mod solid_momentum;

pub use boundary_conditions::{wedge_rotations, PatchCondition};
pub use least_squares_gradient::LeastSquaresGradient;
pub use solid_momentum::{MomentumParams, SolidMomentum};

pub use fv_mesh::{Real, Tensor, Vector};
