//! The one error type of the loader: a message plus the source position it is about.

use std::fmt;

use crate::source::SourcePos;

/// An error a scene file (or the command line) caused.
///
/// Displays like a compiler diagnostic: `path:line:col: error: message`, or
/// `error: message` when there is no position (for example an unreadable file).
#[derive(Clone, Debug, PartialEq)]
pub struct LoadError {
    /// Where the offending element or attribute starts, when known.
    pub pos: Option<SourcePos>,
    /// The problem in plain words.
    pub message: String,
}

impl LoadError {
    /// An error with an optional position.
    pub fn new(pos: Option<SourcePos>, message: impl Into<String>) -> Self {
        LoadError { pos, message: message.into() }
    }

    /// An error at `pos`.
    pub fn at(pos: &SourcePos, message: impl Into<String>) -> Self {
        LoadError { pos: Some(pos.clone()), message: message.into() }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.pos {
            Some(p) => write!(f, "{p}: error: {}", self.message),
            None => write!(f, "error: {}", self.message),
        }
    }
}

impl std::error::Error for LoadError {}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;
    use std::sync::Arc;

    use super::*;

    #[test]
    fn displays_like_a_compiler() {
        let pos = SourcePos { file: Arc::new(PathBuf::from("a/b.xml")), line: 3, col: 7 };
        let e = LoadError::at(&pos, "unexpected tag <foo>");
        assert_eq!(e.to_string(), "a/b.xml:3:7: error: unexpected tag <foo>");
        assert_eq!(LoadError::new(None, "x").to_string(), "error: x");
    }
}
