//! Typed, usage-tracked properties of one plugin.
//!
//! Every accessor marks the property as read; [`Properties::check_all_used`] then reports
//! the first property the plugin never asked for, as Mitsuba does ("unreferenced
//! property"). Read flags use atomics, so accessors take `&self` and the tree stays
//! `Send + Sync`. The names a plugin asked for as values and did not find are kept too, so
//! that a nested object given under such a name (a `<texture name="intensity">` in a spot
//! light) is reported as a value that cannot vary, not as an unknown object.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

use glam::Vec3;
use steradian::geometry::Transform;

use crate::error::LoadError;
use crate::source::SourcePos;

/// A spectrum property (`<spectrum>`), already reduced to what RGB rendering needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpectrumValue {
    /// `<spectrum value="v"/>`: the same value at every wavelength.
    Uniform(f32),
    /// A `wavelength:value` list (or a flat emitter spectrum) converted to linear sRGB.
    Rgb(Vec3),
}

impl SpectrumValue {
    /// The value as linear RGB.
    pub fn rgb(&self) -> Vec3 {
        match *self {
            SpectrumValue::Uniform(v) => Vec3::splat(v),
            SpectrumValue::Rgb(c) => c,
        }
    }
}

/// The value of one property, typed by the XML tag it came from.
#[derive(Clone, Debug, PartialEq)]
pub enum PropertyValue {
    Bool(bool),
    Int(i64),
    Float(f64),
    String(String),
    Point(Vec3),
    Vector(Vec3),
    Rgb(Vec3),
    Spectrum(SpectrumValue),
    Transform(Transform),
}

impl PropertyValue {
    /// The XML tag name of this kind of value (`integer`, `float`, `rgb`, …).
    pub fn type_name(&self) -> &'static str {
        match self {
            PropertyValue::Bool(_) => "boolean",
            PropertyValue::Int(_) => "integer",
            PropertyValue::Float(_) => "float",
            PropertyValue::String(_) => "string",
            PropertyValue::Point(_) => "point",
            PropertyValue::Vector(_) => "vector",
            PropertyValue::Rgb(_) => "rgb",
            PropertyValue::Spectrum(_) => "spectrum",
            PropertyValue::Transform(_) => "transform",
        }
    }
}

#[derive(Debug)]
struct Entry {
    name: String,
    value: PropertyValue,
    pos: SourcePos,
    used: AtomicBool,
}

/// The properties of one plugin, in document order.
#[derive(Debug, Default)]
pub struct Properties {
    /// How the owner is described in errors, e.g. `<integrator type="path">`.
    owner: String,
    entries: Vec<Entry>,
    /// Names asked for through a typed accessor and not given as properties, with the type
    /// asked for (e.g. "float").
    missing: Mutex<Vec<(String, &'static str)>>,
}

impl Properties {
    /// Empty properties of the plugin described as `owner` (e.g. `<bsdf type="diffuse">`).
    pub fn new(owner: impl Into<String>) -> Self {
        Properties { owner: owner.into(), entries: Vec::new(), missing: Mutex::default() }
    }

    /// How the owning plugin is described in error messages.
    pub fn owner(&self) -> &str {
        &self.owner
    }

    /// Adds a property. The parser has already refused duplicates; a duplicate here is
    /// an error too.
    pub fn insert(
        &mut self,
        name: impl Into<String>,
        value: PropertyValue,
        pos: SourcePos,
    ) -> Result<(), LoadError> {
        let name = name.into();
        if let Some(prev) = self.entries.iter().find(|e| e.name == name) {
            return Err(LoadError::at(
                &pos,
                format!(
                    "property '{name}' is specified twice in {} (first at {})",
                    self.owner,
                    prev.pos.line_col()
                ),
            ));
        }
        self.entries.push(Entry { name, value, pos, used: AtomicBool::new(false) });
        Ok(())
    }

    /// Removes a property (used by the version upgrade); does not count as a read.
    pub(crate) fn remove(&mut self, name: &str) -> Option<(PropertyValue, SourcePos)> {
        let i = self.entries.iter().position(|e| e.name == name)?;
        let e = self.entries.remove(i);
        Some((e.value, e.pos))
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Is there a property of this name? (Does not mark it as read.)
    pub fn contains(&self, name: &str) -> bool {
        self.entries.iter().any(|e| e.name == name)
    }

    /// Where the property was given. (Does not mark it as read.)
    pub fn position(&self, name: &str) -> Option<&SourcePos> {
        self.entries.iter().find(|e| e.name == name).map(|e| &e.pos)
    }

    /// All properties in document order: name, value, position. (Does not mark them.)
    pub fn iter(&self) -> impl Iterator<Item = (&str, &PropertyValue, &SourcePos)> {
        self.entries.iter().map(|e| (e.name.as_str(), &e.value, &e.pos))
    }

    /// The raw value, marking the property as read.
    pub fn get(&self, name: &str) -> Option<&PropertyValue> {
        let e = self.entries.iter().find(|e| e.name == name)?;
        e.used.store(true, Ordering::Relaxed);
        Some(&e.value)
    }

    /// Marks a property as read without looking at it.
    pub fn mark_used(&self, name: &str) {
        if let Some(e) = self.entries.iter().find(|e| e.name == name) {
            e.used.store(true, Ordering::Relaxed);
        }
    }

    /// Names of the properties nobody has read, in document order.
    pub fn unused(&self) -> Vec<&str> {
        self.entries
            .iter()
            .filter(|e| !e.used.load(Ordering::Relaxed))
            .map(|e| e.name.as_str())
            .collect()
    }

    /// The type of value (e.g. "float") the plugin asked `name` to be, where it found no such
    /// property.
    pub fn asked_as_value(&self, name: &str) -> Option<&'static str> {
        let missing = self.missing.lock().ok()?;
        missing.iter().find(|(n, _)| n == name).map(|&(_, expected)| expected)
    }

    /// Errors on the first property that was never read:
    /// `unreferenced property 'foo' in <bsdf type="diffuse">`, at that property.
    pub fn check_all_used(&self, plugin_desc: &str) -> Result<(), LoadError> {
        match self.entries.iter().find(|e| !e.used.load(Ordering::Relaxed)) {
            Some(e) => Err(LoadError::at(
                &e.pos,
                format!("unreferenced property '{}' in {plugin_desc}", e.name),
            )),
            None => Ok(()),
        }
    }

    fn typed<T>(
        &self,
        name: &str,
        expected: &'static str,
        f: impl FnOnce(&PropertyValue) -> Option<T>,
    ) -> Result<Option<T>, LoadError> {
        let Some(e) = self.entries.iter().find(|e| e.name == name) else {
            if let Ok(mut m) = self.missing.lock() {
                if !m.iter().any(|(n, _)| n == name) {
                    m.push((name.to_owned(), expected));
                }
            }
            return Ok(None);
        };
        e.used.store(true, Ordering::Relaxed);
        match f(&e.value) {
            Some(v) => Ok(Some(v)),
            None => Err(LoadError::at(
                &e.pos,
                format!(
                    "property '{name}' of {} must be {expected}, got {}",
                    self.owner,
                    e.value.type_name()
                ),
            )),
        }
    }

    /// `<boolean>`.
    pub fn get_bool(&self, name: &str) -> Result<Option<bool>, LoadError> {
        self.typed(name, "boolean", |v| match v {
            PropertyValue::Bool(b) => Some(*b),
            _ => None,
        })
    }

    /// `<integer>` only: a `<float>` is an error, as in Mitsuba.
    pub fn get_int(&self, name: &str) -> Result<Option<i64>, LoadError> {
        self.typed(name, "integer", |v| match v {
            PropertyValue::Int(i) => Some(*i),
            _ => None,
        })
    }

    /// `<float>`; an `<integer>` is accepted and converted (Mitsuba's `Properties` does so).
    pub fn get_float(&self, name: &str) -> Result<Option<f32>, LoadError> {
        self.typed(name, "float", |v| match v {
            PropertyValue::Float(f) => Some(*f as f32),
            PropertyValue::Int(i) => Some(*i as f32),
            _ => None,
        })
    }

    /// `<string>`.
    pub fn get_string(&self, name: &str) -> Result<Option<String>, LoadError> {
        self.typed(name, "string", |v| match v {
            PropertyValue::String(s) => Some(s.clone()),
            _ => None,
        })
    }

    /// `<point>` (a `<vector>` is accepted too: Mitsuba stores both as one 3-vector type).
    pub fn get_point(&self, name: &str) -> Result<Option<Vec3>, LoadError> {
        self.typed(name, "point", |v| match v {
            PropertyValue::Point(p) | PropertyValue::Vector(p) => Some(*p),
            _ => None,
        })
    }

    /// `<vector>` (a `<point>` is accepted too).
    pub fn get_vector(&self, name: &str) -> Result<Option<Vec3>, LoadError> {
        self.typed(name, "vector", |v| match v {
            PropertyValue::Point(p) | PropertyValue::Vector(p) => Some(*p),
            _ => None,
        })
    }

    /// A colour as linear RGB: `<rgb>`, `<spectrum>`, or a `<float>` (uniform spectrum).
    pub fn get_spectrum(&self, name: &str) -> Result<Option<steradian::Spectrum>, LoadError> {
        self.typed(name, "rgb, spectrum or float", |v| match v {
            PropertyValue::Rgb(c) => Some((*c).into()),
            PropertyValue::Spectrum(s) => Some(s.rgb().into()),
            PropertyValue::Float(f) => Some(steradian::Spectrum::splat(*f as f32)),
            _ => None,
        })
    }

    /// `<transform>`.
    pub fn get_transform(&self, name: &str) -> Result<Option<Transform>, LoadError> {
        self.typed(name, "transform", |v| match v {
            PropertyValue::Transform(t) => Some(*t),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;
    use std::sync::Arc;

    use super::*;

    fn pos(line: u32) -> SourcePos {
        SourcePos { file: Arc::new(PathBuf::from("t.xml")), line, col: 5 }
    }

    #[test]
    fn typed_access_and_usage_tracking() {
        let mut p = Properties::new("<integrator type=\"path\">");
        p.insert("max_depth", PropertyValue::Float(8.0), pos(2)).unwrap();
        p.insert("rr_depth", PropertyValue::Int(5), pos(3)).unwrap();
        p.insert("foo", PropertyValue::Bool(true), pos(4)).unwrap();
        let e = p.get_int("max_depth").unwrap_err();
        assert_eq!(
            e.message,
            "property 'max_depth' of <integrator type=\"path\"> must be integer, got float"
        );
        assert_eq!(e.pos.unwrap().line, 2);
        assert_eq!(p.get_float("rr_depth").unwrap(), Some(5.0));
        assert_eq!(p.get_int("missing").unwrap(), None);
        let e = p.check_all_used("<integrator type=\"path\">").unwrap_err();
        assert_eq!(e.message, "unreferenced property 'foo' in <integrator type=\"path\">");
        assert_eq!(e.pos.unwrap().line, 4);
        assert_eq!(p.get_bool("foo").unwrap(), Some(true));
        p.check_all_used("x").unwrap();
        assert!(p.insert("foo", PropertyValue::Int(1), pos(9)).is_err());
    }

    #[test]
    fn spectra_accept_rgb_spectrum_and_float() {
        let mut p = Properties::new("<bsdf type=\"diffuse\">");
        p.insert("a", PropertyValue::Rgb(Vec3::new(1.0, 2.0, 3.0)), pos(1)).unwrap();
        p.insert("b", PropertyValue::Float(0.25), pos(2)).unwrap();
        p.insert("c", PropertyValue::Spectrum(SpectrumValue::Uniform(0.5)), pos(3)).unwrap();
        p.insert("d", PropertyValue::Int(1), pos(4)).unwrap();
        assert_eq!(p.get_spectrum("a").unwrap().map(Vec3::from), Some(Vec3::new(1.0, 2.0, 3.0)));
        assert_eq!(p.get_spectrum("b").unwrap().map(Vec3::from), Some(Vec3::splat(0.25)));
        assert_eq!(p.get_spectrum("c").unwrap().map(Vec3::from), Some(Vec3::splat(0.5)));
        assert!(p.get_spectrum("d").is_err());
    }
}
