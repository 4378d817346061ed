//! Scene parameters: `-D name=value` defines and `<default name value>`s, substituted for
//! `$name` in every attribute value.
//!
//! As in Mitsuba 3: a define overrides the `<default>` of the same name; names are replaced
//! longest first (so `$spp` does not eat the start of `$spp2`); a `$` left over is an
//! undefined parameter; a define the scene never uses is an error ("Unused parameter").

use super::attrs::Attrs;
use crate::error::LoadError;
use crate::source::SourcePos;

struct Param {
    name: String,
    value: String,
    used: bool,
}

/// The parameters known so far while a scene is read.
pub(super) struct Params {
    list: Vec<Param>,
    /// Names given as defines (checked for use at the end).
    define_names: Vec<String>,
}

impl Params {
    /// The defines given on the command line (or by the caller).
    pub fn new(defines: &[(String, String)]) -> Self {
        Params {
            list: defines
                .iter()
                .map(|(n, v)| Param { name: n.clone(), value: v.clone(), used: false })
                .collect(),
            define_names: defines.iter().map(|(n, _)| n.clone()).collect(),
        }
    }

    /// `value` of attribute `attr` (at `pos`) with every `$name` replaced.
    pub fn substitute(
        &mut self,
        value: &str,
        attr: &str,
        pos: &SourcePos,
    ) -> Result<String, LoadError> {
        let mut value = value.to_string();
        if !value.contains('$') {
            return Ok(value);
        }
        // Stable, so equal lengths keep the order they were declared in.
        self.list.sort_by_key(|p| std::cmp::Reverse(p.name.len()));
        for p in self.list.iter_mut() {
            let key = format!("${}", p.name);
            if value.contains(&key) {
                value = value.replace(&key, &p.value);
                p.used = true;
            }
        }
        if let Some(i) = value.find('$') {
            let name: String =
                value[i + 1..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            return Err(LoadError::at(
                pos,
                format!("undefined parameter '${name}' in attribute '{attr}' (declare it with <default name=\"{name}\" value=\"…\"/> or pass it as a define)"),
            ));
        }
        Ok(value)
    }

    /// A `<default name value>` element (its attributes); a define of the same name wins.
    pub fn default(&mut self, attrs: &Attrs) -> Result<(), LoadError> {
        attrs.allow(&["name", "value"])?;
        let name = attrs.require("name")?.value.clone();
        let value = attrs.require("value")?.value.clone();
        if name.is_empty() || name.contains(',') || name.contains('$') {
            return Err(attrs.error(format!("invalid parameter name \"{name}\" in <default>")));
        }
        if !self.list.iter().any(|p| p.name == name) {
            // A <default> counts as used: only unused defines are errors.
            self.list.push(Param { name, value, used: true });
        }
        Ok(())
    }

    /// Errors at the root element (`root`) on the first define the scene never used.
    pub fn check_defines_used(&self, root: &Attrs) -> Result<(), LoadError> {
        for d in &self.define_names {
            if !self.list.iter().any(|p| &p.name == d && p.used) {
                return Err(root.error(format!(
                    "unused parameter '{d}': it was given as a define but the scene never uses ${d}"
                )));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;
    use std::sync::Arc;

    use super::*;

    fn pos() -> SourcePos {
        SourcePos { file: Arc::new(PathBuf::from("t.xml")), line: 1, col: 1 }
    }

    #[test]
    fn longest_names_first_and_leftovers_are_errors() {
        let defines = [("n".to_string(), "1".to_string()), ("n2".to_string(), "2".to_string())];
        let mut p = Params::new(&defines);
        assert_eq!(p.substitute("$n2 $n", "value", &pos()).unwrap(), "2 1");
        assert_eq!(p.substitute("no parameter", "value", &pos()).unwrap(), "no parameter");
        let e = p.substitute("$m", "value", &pos()).unwrap_err();
        assert!(e.message.starts_with("undefined parameter '$m' in attribute 'value'"), "{e}");
    }
}
