//! Nonlinear solution methods for the discretised balance of an increment.
//!
//! - [`NonlinearMethod`]: the methods by case-file name (`[solver]
//!   nonlinear`), the seam between the time loop and the solvers.
//! - [`NewtonKrylov`]: Jacobian-free Newton–Krylov over any
//!   [`NonlinearProblem`] — matrix-free Jacobian products by finite
//!   differences with the problem's frozen data kept ([`Frozen`]),
//!   right-preconditioned restarted [`Gmres`], Eisenstat–Walker
//!   [`Forcing`] terms, a non-monotone backtracking line search and
//!   [`PseudoTransient`] continuation where the line search fails.
//!
//! The segregated method of the thesis lives with the model it iterates
//! (`solver-app`); this crate holds what does not depend on the model.
#![warn(missing_docs)]

mod forcing;
mod gmres;
pub mod line_search;
mod method;
mod newton_krylov;
mod problem;
mod pseudo_transient;
pub mod vector_ops;

pub use forcing::{Forcing, ForcingParams};
pub use gmres::{Gmres, GmresInfo, GmresParams, KrylovSystem};
pub use line_search::LineSearchParams;
pub use method::{NonlinearMethod, UnknownMethod};
pub use newton_krylov::{IterationReport, NewtonError, NewtonInfo, NewtonKrylov, NewtonParams};
pub use problem::{Frozen, Inadmissible, NonlinearProblem};
pub use pseudo_transient::{PseudoTransient, PseudoTransientParams};
