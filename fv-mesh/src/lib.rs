//! Polyhedral finite-volume meshes with OpenFOAM addressing.
//!
//! A [`PolyMesh`] stores points, faces (as point lists), the owner and
//! neighbour cell of every face and the boundary patches, in the order
//! OpenFOAM uses: internal faces first (sorted by owner, then neighbour),
//! then the boundary faces grouped by patch. [`MeshGeometry`] holds the
//! derived geometric quantities of thesis §3.2 (cell centres and volumes,
//! face centres and area vectors, d-vectors, interpolation weights).
#![warn(missing_docs)]

mod cell_shapes;
mod cell_to_point;
mod error;
mod extrude_plane;
mod geometry;
mod gmsh;
mod openfoam;
mod poly_mesh;
mod quality;
mod state_arrays;
mod surface;
mod wedge_point_constraint;

pub mod generators;
pub mod spherical_shell;

pub use cell_shapes::{CellNodes, CellShape, CellType, MAX_CELL_NODES};
pub use cell_to_point::{CellToPoint, PointFit, EIGEN_TOLERANCE, MAX_WEIGHT_SUM};
pub use error::MeshError;
pub use extrude_plane::{FRONT_AND_BACK, PLANE_THICKNESS};
pub use geometry::MeshGeometry;
pub use gmsh::{read_gmsh, read_gmsh_bytes};
pub use openfoam::{face_connected_regions, read_polymesh, read_polymesh_files, select_body};
pub use poly_mesh::{polygon_area_vector, CellZone, FaceZone, Patch, PolyMesh};
pub use quality::{coincident_boundary_faces, MeshQuality};
pub use state_arrays::{StateArray, StateArrays};
pub use surface::{PointNormalWeighting, Surface, NO_FACE};
pub use wedge_point_constraint::{is_planar_patch, PointConstraint, WedgePointConstraint};

/// Scalar type used everywhere.
pub type Real = f64;
/// 3-vector (positions, displacements, area vectors).
pub type Vector = nalgebra::Vector3<Real>;
/// 3×3 tensor (gradients, stresses).
pub type Tensor = nalgebra::Matrix3<Real>;
