//! Finite-volume discretisation of the solid momentum equation (thesis §3.2)
//! and the sparse linear solvers it needs.
//!
//! Conventions: the displacement gradient is `(∇u)_ij = ∂u_j/∂x_i`; the
//! traction on a face with unit normal n is `σ·n` (σ symmetric).
#![warn(missing_docs)]

mod boundary_conditions;
mod cell_halves;
mod least_squares_gradient;
mod solid_momentum;
mod stress_law;

pub mod amg;
pub mod bicgstab_ilu0;
pub mod csr;
pub mod direct;
pub mod linear_solver;
pub mod pcg_ic0;

pub use boundary_conditions::{wedge_rotations, LinearisedContact, PatchCondition};
pub use least_squares_gradient::LeastSquaresGradient;
pub use solid_momentum::{
    Inertia, MomentumParams, RhieChowHistory, RhieChowPlastic, SolidMomentum, StateNode,
    PLASTIC_RC_SHARE_FLOOR,
};
pub use stress_law::{current_area_vector, StressLaw};

pub use amg::PcgAmg;
pub use bicgstab_ilu0::{BicgstabIlu0, BicgstabParams};
pub use csr::{CsrMatrix, FaceSlots, PatternGrowth};
pub use direct::{DirectMethod, DirectSolver};
pub use linear_solver::{FactorisationInfo, LinearSolver, LinearSolverError, SolveInfo};
pub use pcg_ic0::{PcgIc0, PcgParams};

pub use fv_mesh::{Real, Tensor, Vector};
