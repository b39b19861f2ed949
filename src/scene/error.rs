//! Located scene errors: the file (or built-in name), the line when known, and what is
//! wrong.

use std::fmt;

/// An error in a scene description.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// File path or `builtin:NAME`.
    pub source: String,
    /// (line, column), 1-based, when known.
    pub location: Option<(u32, u32)>,
    /// What is wrong.
    pub message: String,
}

impl SceneError {
    /// An error in `source` at `location`.
    pub fn new(
        source: impl Into<String>,
        location: Option<(u32, u32)>,
        message: impl Into<String>,
    ) -> SceneError {
        SceneError {
            source: source.into(),
            location,
            message: message.into(),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Some((line, col)) => write!(f, "{}:{}:{}: {}", self.source, line, col, self.message),
            None => write!(f, "{}: {}", self.source, self.message),
        }
    }
}

impl std::error::Error for SceneError {}
