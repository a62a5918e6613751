//! [`InputError`]: a bad-input message naming file, line and key.

use std::fmt;
use std::path::{Path, PathBuf};

/// An error in the user's input, located as precisely as known.
///
/// Displays as `<file>:<line>: <key>: <message>`, leaving out the parts that
/// are absent, e.g.
/// `case.toml:12: body[0].material.nu: must satisfy -1 < nu < 0.5, got 0.5`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputError {
    /// The file the error is in (as given by the caller).
    pub file: PathBuf,
    /// 1-based line number, when known.
    pub line: Option<usize>,
    /// Key path such as `body[1].boundary.top` or `solver.linear.method`.
    pub key: Option<String>,
    /// What is wrong, and usually what is expected instead.
    pub message: String,
}

impl InputError {
    /// An error in `file` with no line and no key.
    pub fn new(file: impl AsRef<Path>, message: impl Into<String>) -> Self {
        Self {
            file: file.as_ref().to_path_buf(),
            line: None,
            key: None,
            message: message.into(),
        }
    }

    /// Sets the 1-based line (`None` clears it).
    pub fn at_line(mut self, line: impl Into<Option<usize>>) -> Self {
        self.line = line.into();
        self
    }

    /// Sets the key path.
    pub fn with_key(mut self, key: impl Into<String>) -> Self {
        self.key = Some(key.into());
        self
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        f.write_str(": ")?;
        if let Some(key) = &self.key {
            write!(f, "{key}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for InputError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_omits_absent_parts() {
        let e = InputError::new("case.toml", "must satisfy -1 < nu < 0.5, got 0.5");
        assert_eq!(
            e.to_string(),
            "case.toml: must satisfy -1 < nu < 0.5, got 0.5"
        );
        let e = e.at_line(12);
        assert_eq!(
            e.to_string(),
            "case.toml:12: must satisfy -1 < nu < 0.5, got 0.5"
        );
        let e = e.with_key("body[0].material.nu");
        assert_eq!(
            e.to_string(),
            "case.toml:12: body[0].material.nu: must satisfy -1 < nu < 0.5, got 0.5"
        );
        let e = e.at_line(None);
        assert_eq!(
            e.to_string(),
            "case.toml: body[0].material.nu: must satisfy -1 < nu < 0.5, got 0.5"
        );
    }
}
