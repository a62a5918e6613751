//! Errors of mesh construction, import and validation.
use std::path::PathBuf;

/// Everything that can go wrong when a mesh is read, built or checked.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// A file could not be opened or read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A file's content could not be parsed.
    #[error("{path}{}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Parse {
        /// The file.
        path: PathBuf,
        /// Line (1-based), where known.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
    /// The mesh is structurally invalid (bad indices, open cells, …).
    #[error("invalid mesh: {0}")]
    Invalid(String),
    /// The request is not supported (element type, format variant, …).
    #[error("unsupported: {0}")]
    Unsupported(String),
}

impl MeshError {
    /// Shorthand for [`MeshError::Invalid`].
    pub fn invalid(msg: impl Into<String>) -> Self {
        MeshError::Invalid(msg.into())
    }
}
