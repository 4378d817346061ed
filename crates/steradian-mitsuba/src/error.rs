//! The loader's diagnostics: an error ([`LoadError`]) stops the load; a warning
//! ([`LoadWarning`]) is a scene that loads but may not be what its author meant (a reflectance
//! above 1 creates energy). Both are a message plus the source position they are about.

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

/// A scene that loads and renders as written, but probably not as meant.
///
/// Displays as `path:line:col: warning: message`. The loader collects them in
/// [`Job::warnings`](steradian::render::Job::warnings) for front ends to print.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadWarning {
    /// Where the element or attribute starts.
    pub pos: SourcePos,
    /// What looks wrong, in plain words.
    pub message: String,
}

impl LoadWarning {
    /// A warning at `pos`.
    pub fn at(pos: &SourcePos, message: impl Into<String>) -> Self {
        LoadWarning { pos: pos.clone(), message: message.into() }
    }
}

impl fmt::Display for LoadWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: warning: {}", self.pos, self.message)
    }
}

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
        let w = LoadWarning::at(&pos, "reflectance above 1");
        assert_eq!(w.to_string(), "a/b.xml:3:7: warning: reflectance above 1");
    }
}
