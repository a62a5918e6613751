//! Errors of the contact-force computation.

/// Everything that can go wrong in a contact-force call.
///
/// Degenerate geometry is not an error: zero-area or non-finite faces,
/// pairs whose projections do not overlap and faces that do not face each
/// other are skipped (they carry no traction).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// A penalty or relaxation parameter is out of range.
    #[error("contact parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// An input array does not have one entry per face.
    #[error("{what}: expected {expected} entries, got {got}")]
    SizeMismatch {
        /// Which array.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        got: usize,
    },
    /// Candidate pairs inconsistent with the surfaces.
    #[error("candidate pairs: {0}")]
    InvalidPairs(String),
    /// Material data from which no penalty can be estimated.
    #[error("penalty estimate (4.4a/4.4b): {0}")]
    InvalidMaterial(String),
    /// A `contact_algorithm = ...` name that no algorithm has.
    #[error("unknown contact algorithm '{name}'; valid names: {valid}")]
    UnknownAlgorithm {
        /// The rejected name.
        name: String,
        /// The valid names, comma separated.
        valid: String,
    },
    /// A known algorithm that is not implemented (no algorithm is in this
    /// state at present; kept for variants to come).
    #[error("contact algorithm '{name}' is not available yet ({reason}); valid names: {valid}")]
    NotAvailable {
        /// The requested name.
        name: String,
        /// Why / where it will come from.
        reason: &'static str,
        /// The names that work today, comma separated.
        valid: String,
    },
}
