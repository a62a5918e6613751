//! Contact forces between two boundary surfaces by the penalty method
//! (thesis chapter 4: §4.1 penalty laws and explicit Neumann–Neumann
//! coupling, §4.3 pointwise algorithm, §4.4 segment-to-segment algorithm,
//! §4.6 both against a Nagata-smoothed master surface from `contact-smooth`).
//!
//! # Use in the outer loop
//!
//! Once per problem: a [`ContactLaw`] from [`PenaltyParams::contact_law`]
//! (eqs. 4.4a/4.4b) or [`ContactLaw::new`]; an algorithm from
//! [`ContactAlgorithmKind::from_name`]`(..)?.build()`; an
//! [`ExplicitRelaxation`] (eq. 4.13). Then, every outer iteration:
//!
//! 1. move both [`Surface`](fv_mesh::Surface)s to the current positions
//!    ([`fv_mesh::Surface::update_points`]);
//! 2. detect candidate pairs (`contact-detect`; any [`FacePairs`]);
//! 3. [`ContactAlgorithm::compute`] → [`ContactTractions`] (new tractions,
//!    pressure, gap, contact fraction β, slip, GGI weights) and
//!    [`ContactStats`];
//! 4. [`Coupling::apply`] → the tractions to apply as the traction boundary
//!    condition of each contact patch.
//!
//! At the end of a converged increment: [`ContactAlgorithm::commit_increment`]
//! with the converged surfaces (the slip of the next increment is measured
//! from them).
//!
//! # Signs (DESIGN.md)
//!
//! Tractions are forces per area acting on the body whose surface it is: a
//! compressive normal traction points against the outward face normal.
//! Pressure is positive in compression. Gap < 0 is penetration.
#![warn(missing_docs)]

mod auxiliary_plane;
mod barycentric;
mod contact_algorithm;
mod contact_tractions;
mod coulomb_friction;
mod error;
mod explicit_coupling;
mod face_pairs;
mod face_shifts;
mod ggi;
mod increment_state;
mod occluded_volume;
mod penalty;
mod pointwise;
mod restart;
mod segment_to_segment;
mod smoothed_master;
mod sutherland_hodgman;

pub use auxiliary_plane::{AuxiliaryPlane, AREA_TOLERANCE, MIN_FACING_COSINE};
pub use barycentric::{barycentric, locate_in_polygon, Located};
pub use contact_algorithm::{ContactAlgorithm, ContactAlgorithmKind};
/// Symmetry plane of a smoothed master ([`ContactAlgorithm::set_symmetry_planes`]).
pub use contact_smooth::SymmetryPlane;
pub use contact_tractions::{ContactStats, ContactTractions, SurfaceContact, NO_GAP};
pub use coulomb_friction::{
    coulomb_return_mapping, face_friction, FaceFriction, FrictionState, SlipHistory,
};
pub use error::ContactError;
pub use explicit_coupling::{AppliedTraction, Coupling, CouplingInfo, ExplicitRelaxation};
pub use face_pairs::{all_pairs, check_pairs, swap_pairs, FacePairs};
pub use face_shifts::FaceShifts;
pub use ggi::{GgiScratch, GgiWeights};
pub use occluded_volume::central_integral;
pub use penalty::{macaulay, normal_pressure, ContactLaw, PenaltyParams, SurfaceMaterial};
pub use pointwise::Pointwise;
pub use segment_to_segment::SegmentToSegment;
pub use sutherland_hodgman::{
    clip_convex, clip_non_positive, signed_area, Affine2, ClipScratch, Point2,
};
