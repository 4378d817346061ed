//! The attributes of one XML element after `$name` substitution, and the number and list
//! syntax attribute values use (Mitsuba's `string::tokenize` and `string::stof`).
//!
//! Errors point at the attribute they are about (its own line and column), or at the element
//! when an attribute is missing.

use crate::error::LoadError;
use crate::source::SourcePos;

/// Splits a list value at whitespace and commas (Mitsuba's `string::tokenize`).
pub(super) fn tokenize(s: &str) -> Vec<&str> {
    s.split(|c: char| c.is_whitespace() || c == ',').filter(|t| !t.is_empty()).collect()
}

/// A floating-point number as Mitsuba's `string::stof` reads it (no trailing garbage).
pub(super) fn parse_f64(s: &str) -> Option<f64> {
    let t = s.trim();
    if t.is_empty() {
        return None;
    }
    t.parse::<f64>().ok()
}

/// One attribute after `$` substitution.
#[derive(Debug)]
pub(super) struct Attr {
    pub name: String,
    pub value: String,
    pub pos: SourcePos,
}

/// The attributes of one element, with the element's name and position.
#[derive(Debug)]
pub(super) struct Attrs {
    pub elem: String,
    pub pos: SourcePos,
    pub list: Vec<Attr>,
}

impl Attrs {
    pub fn error(&self, msg: impl Into<String>) -> LoadError {
        LoadError::at(&self.pos, msg)
    }

    pub fn get(&self, name: &str) -> Option<&Attr> {
        self.list.iter().find(|a| a.name == name)
    }

    pub fn require(&self, name: &str) -> Result<&Attr, LoadError> {
        self.get(name)
            .ok_or_else(|| self.error(format!("missing attribute '{name}' in <{}>", self.elem)))
    }

    /// Refuses attributes outside `allowed`, at the attribute.
    pub fn allow(&self, allowed: &[&str]) -> Result<(), LoadError> {
        match self.list.iter().find(|a| !allowed.contains(&a.name.as_str())) {
            Some(a) => Err(LoadError::at(
                &a.pos,
                format!("unexpected attribute '{}' in <{}>", a.name, self.elem),
            )),
            None => Ok(()),
        }
    }

    /// A finite number from (part of) attribute `a`.
    pub fn number(&self, a: &Attr, token: &str) -> Result<f64, LoadError> {
        match parse_f64(token) {
            Some(v) if v.is_finite() => Ok(v),
            Some(_) => Err(LoadError::at(
                &a.pos,
                format!("NaN or infinite value \"{token}\" in '{}' of <{}>", a.name, self.elem),
            )),
            None => Err(LoadError::at(
                &a.pos,
                format!("could not parse number \"{token}\" in '{}' of <{}>", a.name, self.elem),
            )),
        }
    }
}
