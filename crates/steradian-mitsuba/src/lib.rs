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
//! 3. **Plugins → [`Job`]**: the registry assembles the core renderer's scene and its
//!    integrator.
//!
//! ## Semantics (from Mitsuba 3's `src/core/xml.cpp`)
//! - `<scene version="x.y.z">` is required; versions below 2.0.0 are upgraded
//!   ([`upgrade`]). Mitsuba upgrades only `< 2.0.0`, so 2.x files are read as they are.
//! - `$name` is replaced in every attribute, longest parameter names first; a `$` left
//!   over is an error. Defines override `<default>`s. A define the scene never uses as
//!   `$name` is an error ("Unused parameter", as in current Mitsuba 3).
//! - References may point forwards or backwards (Mitsuba links them after parsing);
//!   an unknown id is an error at the `<ref>`. Duplicate ids are errors.
//! - `<path value="folder"/>` (children of the root only) adds a search folder; `<include
//!   filename>`s and the plugins' file names are looked up in the search folders, the last
//!   `<path>` first and the main scene's folder last ([`FileResolver`]). The children of an
//!   included file's `<scene>` root are merged into the current object.
//! - `<integer>` is parsed strictly (`1.5` is an error); `<boolean>` accepts `true`/`false`
//!   in any case; `<point>`/`<vector>` need `value` or all of `x`, `y`, `z`; `<rgb>` takes
//!   1 (broadcast) or 3 numbers.
//! - Spectra: see [`spectrum`].
//! - Deliberately stricter than Mitsuba: degenerate transforms (zero scale, NaN, `up`
//!   parallel to the view direction, singular matrices) are errors; spectrum wavelengths
//!   must increase strictly; the root must be `<scene>`; an included file must have a
//!   `<scene>` root; `<spectrum filename>` is not supported yet.
//!
//! ## Layers
//! Each module imports only modules of lower layers, and the files inside a module import each
//! other without cycles (`crates/steradian/tests/layers.rs` reads this list and checks the
//! code against it):
//! 1. `source`, `spectrum`, `file_resolver`: [`SourcePos`]; `wavelength:value` spectra → RGB;
//!    the search folders for file names ([`FileResolver`]).
//! 2. `error`: [`LoadError`].
//! 3. `properties`: typed, usage-tracked properties.
//! 4. `tree`, `upgrade`: the parsed scene tree ([`PluginNode`], [`SceneNode`]); the pre-2.0
//!    upgrade rules.
//! 5. `xml`: stage 1, XML → tree (`parser` uses `attrs`, `params`, `values`, `transform`,
//!    `link`).
//! 6. `registry`: stage 2, tree → core plugins → [`Job`]; one file and one name → builder
//!    table per family.
//! 7. `verify`: the closed-form validation cases, loaded through the crate root.
//!
//! The crate root ([`load_file`], [`load_string`]) runs `xml` then `registry`.

pub mod error;
pub mod file_resolver;
pub mod properties;
pub mod source;
pub mod spectrum;
pub mod tree;
pub mod upgrade;
pub mod xml;

pub use error::LoadError;
pub use file_resolver::FileResolver;
pub use properties::{Properties, PropertyValue, SpectrumValue};
pub use source::SourcePos;
pub use tree::{Child, ObjectTag, PluginNode, SceneNode};
pub use xml::{parse_file, parse_string};

mod registry;

use std::path::Path;

use steradian::render::Job;

pub use registry::build_scene;

/// Loads a Mitsuba 3 XML scene file: its scene and integrator. `defines` override the file's
/// `<default>`s (`-D name=value`).
pub fn load_file(path: &Path, defines: &[(String, String)]) -> Result<Job, LoadError> {
    let tree = parse_file(path, defines)?;
    let base = path.parent().unwrap_or(Path::new("."));
    build_scene(&tree, base)
}

/// What a checkpoint of `job` must match
/// ([`SumsHeader::scene_digest`](steradian::render::SumsHeader::scene_digest)): a digest of
/// every file the scene read ([`Job::inputs`]), the `defines` it was loaded with, and its XML
/// when it was given as a string (`source`).
pub fn scene_digest(
    job: &Job,
    defines: &[(String, String)],
    source: Option<&str>,
) -> Result<u64, String> {
    let overrides: Vec<String> = defines.iter().map(|(k, v)| format!("{k}={v}")).collect();
    let mut extra: Vec<&str> = overrides.iter().map(String::as_str).collect();
    extra.extend(source);
    steradian::render::digest_inputs(&job.inputs, &extra)
        .map_err(|e| format!("cannot read the scene's files for its digest: {e}"))
}

/// Loads a scene from a string. `name` is how error messages call it; relative file names
/// (meshes) resolve against `base_dir`.
pub fn load_string(
    xml: &str,
    name: &Path,
    base_dir: &Path,
    defines: &[(String, String)],
) -> Result<Job, LoadError> {
    let tree = xml::parse_string_named(xml, name, base_dir, defines)?;
    build_scene(&tree, base_dir)
}
pub mod verify;
