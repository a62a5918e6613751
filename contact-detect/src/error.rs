//! Errors of contact detection.

/// Everything that can go wrong in contact detection.
///
/// Degenerate faces are not an error: they are skipped (see the crate
/// documentation for the rule).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DetectError {
    /// A detection parameter is out of range.
    #[error("contact detection parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// A `detection = ...` name that no detector has.
    #[error("unknown contact detection method '{name}'; valid methods: {valid}")]
    UnknownMethod {
        /// The rejected name.
        name: String,
        /// The valid names, comma separated.
        valid: String,
    },
    /// A surface whose addressing is inconsistent (array lengths or indices out of range).
    #[error("invalid {side} surface: {message}")]
    InvalidSurface {
        /// `"master"` or `"slave"`.
        side: &'static str,
        /// What is inconsistent.
        message: String,
    },
}
