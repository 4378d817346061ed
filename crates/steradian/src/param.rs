//! Errors of plugin constructors about one of their parameters.
//!
//! A constructor that checks its parameters (`Phong::new`, `SpotLight::new`, the cameras, the
//! `path` integrator's `parse_*` functions) returns a [`ParamError`] that names the parameter
//! at fault by its Mitsuba name, so a scene loader can point at the line that sets it without
//! reading the message. This module imports nothing from the crate: every layer may use it.

use std::fmt;

/// A parameter value a plugin refuses.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParamError {
    /// The parameter at fault, by its Mitsuba name (`exponent`, `far_clip`).
    pub param: &'static str,
    /// A second parameter the check compares `param` with (`near_clip` for "far_clip must
    /// exceed near_clip"): where a scene leaves `param` at its default, this is the one it set.
    pub related: Option<&'static str>,
    /// What is wrong, as a sentence that names the parameter; `Display` prints it as it is.
    pub reason: String,
}

impl ParamError {
    /// An error about `param`.
    pub fn new(param: &'static str, reason: impl Into<String>) -> Self {
        ParamError { param, related: None, reason: reason.into() }
    }

    /// The same error, comparing `param` with `related`.
    pub fn with_related(self, related: &'static str) -> Self {
        ParamError { related: Some(related), ..self }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.reason)
    }
}

impl std::error::Error for ParamError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displays_the_reason_and_keeps_the_names() {
        let e = ParamError::new("far_clip", "far_clip (1) must exceed near_clip (2)")
            .with_related("near_clip");
        assert_eq!(e.to_string(), "far_clip (1) must exceed near_clip (2)");
        assert_eq!((e.param, e.related), ("far_clip", Some("near_clip")));
    }
}
