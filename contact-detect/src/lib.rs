//! Contact detection between two boundary surfaces: candidate face pairs
//! for the contact-force algorithms (thesis §4.2).
//!
//! # What a pair is
//!
//! Master face `m` and slave face `s` are a **candidate pair** iff
//!
//! 1. both faces are *valid* (see below);
//! 2. **global phase**: their oriented bounding boxes overlap, by the 3-D
//!    separating-axis test over 15 axes ([`obb_overlap`]), after the AABBs
//!    of the two OBBs were found to meet (a necessary condition, tested first);
//! 3. **local phase**: the slave polygon, projected orthogonally onto the
//!    plane of `m`, overlaps polygon `m` by the 2-D separating-axis test
//!    ([`prepared_polygons_overlap`]: the edge normals of both polygons and
//!    the axes of `m`'s rectangle); touching counts as overlap, within
//!    [`DetectParams::touch_tolerance`] × the longest side of `m`'s rectangle.
//!
//! The face OBB (§4.2.1, Fig. 4.10): its normal axis is the face normal; its
//! in-plane axes are those of the minimum-area rectangle enclosing the face
//! points projected on the face plane, found by rotating calipers on their
//! convex hull ([`min_area_rectangle`]); the rectangle is inflated by 5 % and
//! extruded by e⁺ = 0.25 h̄ out of the body and e⁻ = h̄ into it (eq. 4.10),
//! h̄ being the mean cell height at the contact boundary
//! ([`DetectParams::mean_cell_height`]; estimated as the mean face size
//! √|Γ_f| if not given).
//!
//! All detectors return exactly this set: [`BruteForce`] tests every pair
//! in the contact zone, [`BvhDetector`] tests the pairs whose OBB AABBs a
//! BVH traversal reports, [`AdvancingFront`] walks face adjacency from the
//! previous pairs (Algorithm 2; exact under the condition stated on it).
//! [`PairReuse`] wraps any of them: it searches with it only when a face
//! has moved out of a skin since the last search, and otherwise tests the
//! pairs listed then (a Verlet list), returning the same set.
//!
//! # Degenerate faces
//!
//! A face with fewer than three points, a non-finite point, centre or
//! normal, or an area at most [`DEGENERATE_AREA`]` · h̄²` is skipped: it is in
//! no pair and is counted in [`DetectionStats::skipped_faces`]. Inconsistent
//! surface addressing (indices out of range) is an error, never a panic.
//!
//! # Contact zone
//!
//! Only faces inside the intersection of the two surfaces' bounding boxes
//! (Fig. 4.11), taken over the face OBBs and so inflated by the extrusions,
//! are tested ([`ContactZone`]); no pair can lie outside it.
#![warn(missing_docs)]

mod aabb;
mod advancing_front;
mod box_bound;
mod brute_force;
mod bvh;
mod candidate_pairs;
mod contact_zone;
mod convex_hull_2d;
mod detection_method;
mod error;
mod face_boxes;
mod freeze;
mod min_area_rectangle;
mod obb;
mod pair_reuse;
mod params;
mod sat_obb_obb;
mod sat_polygon_polygon;
mod seed_search;
mod surface_check;
mod workspace;

pub use aabb::Aabb;
pub use advancing_front::AdvancingFront;
pub use box_bound::face_box_bound;
pub use brute_force::BruteForce;
pub use bvh::BvhDetector;
pub use candidate_pairs::CandidatePairs;
pub use contact_zone::ContactZone;
pub use convex_hull_2d::{convex_hull, V2};
pub use detection_method::DetectionMethod;
pub use error::DetectError;
pub use face_boxes::{mean_face_size, FaceBoxes, DEGENERATE_AREA};
pub use min_area_rectangle::{min_area_rectangle, Rectangle};
pub use obb::{face_obb, plane_basis, FaceBoxSize, Obb, ObbScratch};
pub use pair_reuse::{PairReuse, DEFAULT_SKIN};
pub use params::DetectParams;
pub use sat_obb_obb::obb_overlap;
pub use sat_polygon_polygon::{
    polygons_overlap, prepare_polygon, prepared_polygons_overlap, PreparedPolygon,
};
pub use seed_search::SeedSearch;
pub use surface_check::check_surface;
pub use workspace::Workspace;

use fv_mesh::{Real, Surface};

/// Counters of one detection call.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DetectionStats {
    /// h̄ used for the boxes (eq. 4.10).
    pub mean_cell_height: Real,
    /// Master faces inside the contact zone.
    pub master_faces_in_zone: usize,
    /// Slave faces inside the contact zone.
    pub slave_faces_in_zone: usize,
    /// Degenerate faces skipped (both surfaces).
    pub skipped_faces: usize,
    /// AABB overlap tests.
    pub aabb_tests: u64,
    /// OBB overlap tests (3-D SAT).
    pub obb_tests: u64,
    /// Local-phase polygon tests (2-D SAT).
    pub polygon_tests: u64,
    /// Front tests (advancing front only, see [`Workspace::front_test`]).
    pub front_tests: u64,
    /// Brute-force seed searches (advancing front only).
    pub seed_searches: usize,
    /// Fronts grown again from a neighbour's front (advancing front only;
    /// see [`AdvancingFront`]).
    pub repairs: usize,
    /// Pairs found.
    pub pairs: usize,
    /// Whether the pairs were reused without search ([`Detector::set_frozen`]).
    pub frozen: bool,
    /// Whether the pairs were found among those listed at the last search
    /// ([`PairReuse`]; exact, unlike `frozen`).
    pub reused: bool,
    /// Pairs listed at the last search ([`PairReuse`] only).
    pub listed_pairs: usize,
}

/// A contact detection algorithm (thesis §4.2): candidate pairs between a
/// master and a slave surface at their current positions.
///
/// A detector keeps state between calls (seeds, buffers, the last result);
/// call [`Detector::reset`] when the surfaces change topology or a new
/// problem starts.
pub trait Detector {
    /// Finds the candidate pairs (see the crate docs for the definition)
    /// and writes them into `out`, one sorted row per master face.
    fn detect(
        &mut self,
        master: &Surface,
        slave: &Surface,
        out: &mut CandidatePairs,
    ) -> Result<DetectionStats, DetectError>;

    /// Forgets seeds and the last result.
    fn reset(&mut self);

    /// Freezes (or thaws) the pairs: while frozen, [`Detector::detect`]
    /// returns the last pairs without searching (§4.2.2: once the outer
    /// residual is below a threshold such as 5·10⁻⁶). The caller decides
    /// when; a change in face counts forces a new search.
    fn set_frozen(&mut self, frozen: bool);

    /// Whether the pairs are frozen.
    fn is_frozen(&self) -> bool;

    /// Which algorithm this is.
    fn method(&self) -> DetectionMethod;
}
