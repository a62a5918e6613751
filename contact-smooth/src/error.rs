//! Errors of the surface smoothing.
use fv_mesh::Real;

/// Everything that can go wrong when building or using a smoothed surface.
///
/// Degenerate faces are not an error: they are kept as
/// [`crate::PatchKind::Degenerate`] and skipped by the projection.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SmoothError {
    /// A smoothing or projection parameter is out of range.
    #[error("surface smoothing parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: Real,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// A point-normal weighting name that does not exist.
    #[error("unknown point-normal weighting '{name}'; valid weightings: {valid}")]
    UnknownWeighting {
        /// The rejected name.
        name: String,
        /// The valid names, comma separated.
        valid: String,
    },
    /// Inconsistent input: indices out of range, array lengths that do not
    /// match, non-finite coordinates.
    #[error("invalid surface: {0}")]
    InvalidSurface(String),
}
