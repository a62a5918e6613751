//! Nagata surface smoothing (thesis §4.6.1, eqs. 4.76–4.84, Tables 4.8–4.11).
#![warn(missing_docs)]

mod edge_curve;
mod error;
mod patch;
mod projection;
mod quad_patch;
mod triangle_patch;
mod weingarten;

pub use edge_curve::{curvature_parameter, EdgeCurve, EdgeCurveParams};
pub use error::SmoothError;
pub use patch::{DomainEdge, NagataPatch, PatchDerivatives, PatchDomain};
pub use projection::{project_onto_patch, PatchProjection, ProjectionParams};
pub use quad_patch::QuadPatch;
pub use triangle_patch::TrianglePatch;
pub use weingarten::{normal_derivatives, NormalDerivatives};
