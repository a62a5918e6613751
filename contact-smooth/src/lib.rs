//! Nagata surface smoothing (thesis §4.6.1, eqs. 4.76–4.84, Tables 4.8–4.11).
//!
//! A faceted surface (points and face polygons) is replaced by one
//! quadratic Nagata patch per face, interpolating the points and the point
//! normals; the patches of neighbouring faces share their edge curves, so
//! the smoothed surface has no gaps. Contact algorithms project points onto
//! it.
//!
//! * [`curvature_parameter`], [`EdgeCurve`]: the edge curve (eqs. 4.76–4.77) with
//!   a documented treatment of nearly parallel end normals;
//! * [`TrianglePatch`], [`QuadPatch`]: the patches (eqs. 4.78–4.79,
//!   Tables 4.8–4.9); other polygons are fanned around a lifted centre
//!   ([`fan_centre`]);
//! * [`PointNormals`]: point normals with the weightings of Table 4.10
//!   ([`NormalWeighting`], selectable by name) and the corrections at
//!   symmetry planes and flat/curved transitions (Fig. 4.40);
//! * [`project_onto_patch`]: orthogonal projection by Newton–Raphson
//!   (eqs. 4.81–4.84) with Weingarten normal derivatives
//!   ([`normal_derivatives`]);
//! * [`NagataSurface`]: the whole surface, built once, refreshed in place by
//!   [`NagataSurface::update_points`], and
//!   [`NagataSurface::closest_projection`] among candidate faces.
//!
//! ```
//! use contact_smooth::{NagataSurface, NormalWeighting, SmoothingOptions};
//! use fv_mesh::Vector;
//! let mut options = SmoothingOptions::default();
//! options.normals.weighting = NormalWeighting::from_name("angle")?;
//! let points = vec![Vector::x(), Vector::y(), Vector::z()];
//! let surface = NagataSurface::new(&points, &[[0, 1, 2]], &[], options)?;
//! let foot = surface.closest_projection(&Vector::new(1.0, 1.0, 1.0), &[0])?;
//! assert!(foot.is_some_and(|p| p.inside));
//! # Ok::<(), contact_smooth::SmoothError>(())
//! ```
#![warn(missing_docs)]

mod edge_curve;
mod error;
mod face_geometry;
mod face_table;
mod normal_fit;
mod patch;
mod point_normals;
mod polygon_fan;
mod projection;
mod quad_patch;
mod surface;
mod triangle_patch;
mod weingarten;

pub use edge_curve::{curvature_parameter, EdgeCurve, EdgeCurveParams};
pub use error::SmoothError;
pub use face_geometry::polygon_centre_area;
pub use face_table::{Corner, FaceTable};
pub use normal_fit::{FitWorkspace, NormalFit, MIN_FIRST_RING};
pub use patch::{DomainEdge, NagataPatch, PatchDerivatives, PatchDomain};
pub use point_normals::{
    NormalWeighting, PointNormalParams, PointNormals, SymmetryPlane, TransitionCorrection,
    MAX_SYMMETRY_PLANES,
};
pub use polygon_fan::fan_centre;
pub use projection::{project_onto_patch, PatchProjection, ProjectionParams};
pub use quad_patch::QuadPatch;
pub use surface::{
    LocalCoords, NagataSurface, PatchKind, PatchRef, SmoothingOptions, SurfaceProjection,
    DEGENERATE_AREA, QUAD_MIN_CORNER_SINE,
};
pub use triangle_patch::TrianglePatch;
pub use weingarten::{normal_derivatives, NormalDerivatives};
