//! # steradian-mitsuba: Mitsuba 3 XML scenes
//!
//! Loading a scene is a pipeline of three stages:
//!
//! 1. **XML → tree** ([`parse_file`], [`parse_string`]): the XML layer reads the file,
//!    applies `<default>`s, `-D` defines and `$name` substitution, follows `<include>`s,
//!    upgrades pre-2.0 scenes, parses every property strictly into a typed value
//!    ([`Properties`]) and links `<ref>`s. The result is a [`SceneNode`]: a tree of
//!    [`PluginNode`]s (tag, `type`, id, properties, children) in which referenced objects
//!    are shared. Every error carries the file, line and column it is about ([`LoadError`]).
//! 2. **Tree → plugins** (plugin registry, phase 2): each node is handed to the plugin for
//!    its tag and `type`, which reads its properties through the typed accessors
//!    (`get_float`, `get_spectrum`, …) and takes its child objects ([`PluginNode::child`],
//!    [`PluginNode::children_of`]). Accessors record what was read, so afterwards
//!    [`PluginNode::check_all_used`] reports anything the plugin ignored, as Mitsuba's
//!    "unreferenced property" error does.
//! 3. **Plugins → `Scene`**: the registry assembles the core renderer's scene.
//!
//! ## Semantics (from Mitsuba 3's `src/core/xml.cpp`)
//! - `<scene version="x.y.z">` is required; versions below 2.0.0 are upgraded
//!   ([`upgrade`]). Mitsuba upgrades only `< 2.0.0`, so 2.x files are read as they are.
//! - `$name` is replaced in every attribute, longest parameter names first; a `$` left
//!   over is an error. Defines override `<default>`s. A define the scene never uses as
//!   `$name` is an error ("Unused parameter", as in current Mitsuba 3).
//! - References may point forwards or backwards (Mitsuba links them after parsing);
//!   an unknown id is an error at the `<ref>`. Duplicate ids are errors.
//! - `<include filename>` is resolved relative to the including file; the children of its
//!   `<scene>` root are merged into the current object.
//! - `<integer>` is parsed strictly (`1.5` is an error); `<boolean>` accepts `true`/`false`
//!   in any case; `<point>`/`<vector>` need `value` or all of `x`, `y`, `z`; `<rgb>` takes
//!   1 (broadcast) or 3 numbers.
//! - Spectra: see [`spectrum`].
//! - Deliberately stricter than Mitsuba: degenerate transforms (zero scale, NaN, `up`
//!   parallel to the view direction, singular matrices) are errors; spectrum wavelengths
//!   must increase strictly; the root must be `<scene>`; an included file must have a
//!   `<scene>` root; `<path>` and `<spectrum filename>` are not supported yet.
//!
//! ## Module map
//!
//! Imports run one way: a module uses only the modules in its last column, never one above
//! it, so there is no import cycle (checked by listing every `crate::`/`super::` path).
//!
//! | module       | holds | may import |
//! |--------------|-------|------------|
//! | `registry`   | stage 2: tree → core plugins → `Scene`; one file and one name → builder table per family | `tree`, `properties`, `error` |
//! | `xml`        | stage 1: XML → tree; `parser` uses `attrs`, `params`, `values`, `transform`, `link` | `tree`, `properties`, `spectrum`, `upgrade`, `error`, `source` |
//! | `tree`       | the parsed scene tree ([`PluginNode`], [`SceneNode`]) | `properties`, `error`, `source` |
//! | `upgrade`    | the pre-2.0 upgrade rules | `properties`, `error` |
//! | `properties` | typed, usage-tracked properties | `error`, `source` |
//! | `spectrum`   | `wavelength:value` spectra → RGB | none |
//! | `error`      | [`LoadError`] | `source` |
//! | `source`     | [`SourcePos`] | none |
//!
//! The crate root ([`load_file`], [`load_string`]) runs `xml` then `registry`; `verify`
//! (closed-form validation cases) loads its scenes through the root.

pub mod error;
pub mod properties;
pub mod source;
pub mod spectrum;
pub mod tree;
pub mod upgrade;
pub mod xml;

pub use error::LoadError;
pub use properties::{Properties, PropertyValue, SpectrumValue};
pub use source::SourcePos;
pub use tree::{Child, ObjectTag, PluginNode, SceneNode};
pub use xml::{parse_file, parse_string};

mod registry;

use std::path::Path;

use steradian::scene::Scene;

pub use registry::build_scene;

/// Loads a Mitsuba 3 XML scene file into a renderable scene. `defines` override the file's
/// `<default>`s (`-D name=value`).
pub fn load_file(path: &Path, defines: &[(String, String)]) -> Result<Scene, LoadError> {
    let tree = parse_file(path, defines)?;
    let base = path.parent().unwrap_or(Path::new("."));
    build_scene(&tree, base)
}

/// Loads a scene from a string. `name` is how error messages call it; relative file names
/// (meshes) resolve against `base_dir`.
pub fn load_string(
    xml: &str,
    name: &Path,
    base_dir: &Path,
    defines: &[(String, String)],
) -> Result<Scene, LoadError> {
    let tree = xml::parse_string_named(xml, name, base_dir, defines)?;
    build_scene(&tree, base_dir)
}
pub mod verify;
