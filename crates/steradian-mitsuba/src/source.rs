//! Source positions: which file, line and column an element or attribute came from.

use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

/// A position in a scene file. `line` and `col` are 1-based; `col` counts characters.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SourcePos {
    /// The file (shared by every position in it). Strings parsed with
    /// [`parse_string`](crate::parse_string) use the name `<string>`.
    pub file: Arc<PathBuf>,
    pub line: u32,
    pub col: u32,
}

impl SourcePos {
    /// `line:col`, without the file name.
    pub fn line_col(&self) -> String {
        format!("{}:{}", self.line, self.col)
    }
}

impl fmt::Display for SourcePos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.col)
    }
}
