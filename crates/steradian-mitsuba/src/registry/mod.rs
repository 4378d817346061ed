//! The plugin registry: turns the parsed tree into the core renderer's [`Scene`].
//!
//! Each node is built by the function for its tag and `type`: one file per plugin family, each
//! with one table ([`Plugins`]) from `type` to builder, which both dispatch and the "unknown
//! plugin type" error read (a unit test checks that README.md's table of supported plugins
//! names every entry). A builder reads its properties through the typed accessors and takes
//! its children; afterwards [`PluginNode::check_all_used`] makes anything the plugin did not
//! read an error, as Mitsuba's "unreferenced property" is. An object referenced several times
//! (`<ref>`) is built once and shared.

mod bsdfs;
mod emitters;
mod field_of_view;
mod geometry;
mod integrators;
mod media;
pub(crate) mod sensors;
mod shapes;
mod textures;

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use steradian::bsdf::Bsdf;
use steradian::emitter::Support;
use steradian::integrator::Integrator;
use steradian::param::ParamError;
use steradian::render::Job;
use steradian::scene::{Scene, SceneDescription};
use steradian::texture::MeshAttributeData;

use crate::error::{LoadError, LoadWarning};
use crate::file_resolver::FileResolver;
use crate::tree::{ObjectTag, PluginNode, SceneNode};

/// State while a scene is assembled.
pub(crate) struct Builder {
    desc: SceneDescription,
    /// BSDFs already built, by node identity (shared through `<ref>`).
    bsdf_cache: HashMap<*const PluginNode, u32>,
    /// Shape groups already built, by node identity: index into the scene's groups.
    group_cache: HashMap<*const PluginNode, u32>,
    /// Media already built, by node identity: index into the scene's media.
    medium_cache: HashMap<*const PluginNode, u32>,
    /// Area emitters attached to a shape so far, by node identity, and where (an emitter
    /// declared once and referenced from two shapes is an error, as in Mitsuba).
    pub(crate) attached_emitters: HashMap<*const PluginNode, crate::SourcePos>,
    /// The first sensor's medium and where that sensor is: every sensor must share it.
    sensor_medium: Option<(crate::SourcePos, Option<u32>)>,
    default_bsdf: Option<u32>,
    black_bsdf: Option<u32>,
    /// Directory for relative paths when the scene did not come from a file.
    base_dir: PathBuf,
    /// The scene's search folders.
    resolver: FileResolver,
    /// What the builders warned about so far (they see the builder by shared reference).
    warnings: RefCell<Vec<LoadWarning>>,
    /// What a `mesh_attribute` texture built now can read.
    pub(crate) mesh_attributes: RefCell<AttributeSource>,
    /// Set when a `mesh_attribute` texture was built: the BSDF being built belongs to its
    /// shape and is not shared through the cache.
    pub(crate) read_mesh_attribute: Cell<bool>,
    /// The scene's `ciesky`, once built: the daylight factor's outdoor reference.
    pub(crate) sky: Cell<Option<(steradian::emitter::SkyModel, steradian::emitter::SkyLevel)>>,
    /// Work planes that report the daylight factor: where each is declared, and what it is.
    pub(crate) daylight_planes: RefCell<Vec<(crate::SourcePos, String)>>,
    /// The `type` of the scene's `<integrator>` (its first), known before any emitter is
    /// built: `envmap`'s default sampling depends on it.
    pub(crate) integrator_type: Option<String>,
}

/// What a `mesh_attribute` texture can read where it is built.
pub(crate) enum AttributeSource {
    /// Nothing: the texture is not in a shape's BSDF (an emitter's, a sensor's).
    None,
    /// A scene-level BSDF or texture, checked now and built again where a shape uses it.
    Deferred,
    /// The BSDF of a mesh with these attributes.
    Mesh(MeshAttributes),
}

/// A mesh's attributes as its file gave them, with its triangles.
pub(crate) struct MeshAttributes {
    pub(crate) indices: Arc<[[u32; 3]]>,
    pub(crate) list: Vec<MeshAttributeData>,
}

impl Builder {
    /// The file a relative name in `node` means: the first of the scene's search folders
    /// that holds it ([`FileResolver`]), else the name beside the file the element was
    /// written in (includes have their own folder), else beside the loader's base.
    pub(crate) fn resolve_path(&self, node: &PluginNode, file: &str) -> PathBuf {
        let declared_in = if node.pos.file.is_file() {
            node.pos.file.parent().map(Path::to_path_buf).unwrap_or_default()
        } else {
            self.base_dir.clone()
        };
        let path = self.resolver.resolve(file, &declared_in);
        self.resolver.record(&path);
        path
    }

    /// Records a warning for the front end (the scene still loads).
    pub(crate) fn warn(&self, w: LoadWarning) {
        self.warnings.borrow_mut().push(w);
    }

    fn add_bsdf(&mut self, bsdf: Bsdf) -> u32 {
        self.desc.bsdfs.push(bsdf);
        (self.desc.bsdfs.len() - 1) as u32
    }

    /// The BSDF of `node`, built once.
    pub(crate) fn bsdf_index(&mut self, node: &Arc<PluginNode>) -> Result<u32, LoadError> {
        let key = Arc::as_ptr(node);
        if let Some(&i) = self.bsdf_cache.get(&key) {
            return Ok(i);
        }
        let shared = self.read_mesh_attribute.replace(false);
        let bsdf = bsdfs::build(self, node)?;
        let i = self.add_bsdf(bsdf);
        // a BSDF reading its mesh's attributes is built again for every shape
        if !self.read_mesh_attribute.replace(shared) {
            self.bsdf_cache.insert(key, i);
        }
        Ok(i)
    }

    /// The medium of `node`, built once (shared through `<ref>`): its index in the scene.
    pub(crate) fn medium_index(&mut self, node: &Arc<PluginNode>) -> Result<u32, LoadError> {
        let key = Arc::as_ptr(node);
        if let Some(&i) = self.medium_cache.get(&key) {
            return Ok(i);
        }
        let medium = media::build(self, node)?;
        self.desc.media.push(medium);
        let i = (self.desc.media.len() - 1) as u32;
        self.medium_cache.insert(key, i);
        Ok(i)
    }

    /// The media a shape names in its slots (`interior`, `exterior`): `<medium name="...">`
    /// nested or `<ref name="..." id="..."/>`. Any other `<medium>` child is an error at it
    /// (Mitsuba ignores it silently).
    pub(crate) fn media_of(
        &mut self,
        node: &PluginNode,
        slots: &[&str],
    ) -> Result<Vec<Option<u32>>, LoadError> {
        let children = node.children_of(ObjectTag::Medium);
        let mut found = vec![None; slots.len()];
        for c in children {
            let slot = c.name.as_deref().and_then(|n| slots.iter().position(|s| *s == n));
            let Some(slot) = slot else {
                let names: Vec<String> = slots.iter().map(|s| format!("'{s}'")).collect();
                return Err(LoadError::at(
                    c.pos(),
                    format!(
                        "{}: a medium in {} must be named {} (name=\"...\")",
                        c.node.desc(),
                        node.desc(),
                        names.join(" or ")
                    ),
                ));
            };
            if found[slot].is_some() {
                return Err(LoadError::at(
                    c.pos(),
                    format!("{} names its '{}' medium twice", node.desc(), slots[slot]),
                ));
            }
            found[slot] = Some(self.medium_index(&c.node)?);
        }
        Ok(found)
    }

    /// Reads a sensor's medium (before the sensor is built) into the scene's camera medium:
    /// its one `<medium>` child, whatever its name, as Mitsuba takes it. steradian starts every
    /// sensor's rays in one medium, so sensors in different media are an error.
    pub(crate) fn sensor_medium(&mut self, node: &PluginNode) -> Result<(), LoadError> {
        let children = node.children_of(ObjectTag::Medium);
        if let Some(second) = children.get(1) {
            return Err(LoadError::at(
                second.pos(),
                format!("{} has more than one medium", node.desc()),
            ));
        }
        let medium = match children.first() {
            Some(c) => Some(self.medium_index(&c.node)?),
            None => None,
        };
        match &self.sensor_medium {
            None => {
                self.sensor_medium = Some((node.pos.clone(), medium));
                self.desc.camera_medium = medium;
                Ok(())
            }
            Some((_, first)) if *first == medium => Ok(()),
            Some((pos, _)) => Err(LoadError::at(
                &node.pos,
                format!(
                    "{}: its medium differs from that of the sensor at {pos}; steradian starts all sensors' rays in one medium",
                    node.desc()
                ),
            )),
        }
    }

    /// Mitsuba's BSDF for a shape without one: `diffuse` 0.5, or black for emitters.
    pub(crate) fn implicit_bsdf(&mut self, emitting: bool) -> u32 {
        if emitting {
            if let Some(i) = self.black_bsdf {
                return i;
            }
            let i = self.add_bsdf(Bsdf::black());
            self.black_bsdf = Some(i);
            i
        } else {
            if let Some(i) = self.default_bsdf {
                return i;
            }
            let i = self.add_bsdf(Bsdf::default_diffuse());
            self.default_bsdf = Some(i);
            i
        }
    }
}

/// One plugin family: every `type` steradian knows, each with the function that builds it.
/// Dispatch ([`lookup`]) and the list of known names in the "unknown plugin type" error both
/// read the table, so the two cannot drift apart.
pub(crate) type Plugins<F> = [(&'static str, F)];

/// Mitsuba 3 plugins (3.9.1's plugin list, by family) that steradian does not have: a scene
/// naming one is told so by name, not that the type is unknown. Polarised and spectral-only
/// plugins stay here for good (steradian renders RGB); the others are missing features:
/// - `timed_sunsky` evaluates `sunsky` at each ray's time within the sensor's shutter (its
///   image is the sky averaged over the days and hours of its window); steradian's rays
///   carry no time.
/// - `sggx`: Mitsuba 3.9.1 samples it from a rotated copy of its matrix (the local frame is
///   built as B·S·Bᵀ where its density uses Bᵀ·S·B; upstream issue 1728), so its images are
///   biased and no reference could be matched without copying the error.
pub(crate) const MITSUBA_UNSUPPORTED: &[(&str, &[&str])] = &[
    ("bsdf", &["measured_polarized", "polarizer", "retarder"]),
    ("emitter", &["timed_sunsky"]),
    ("film", &["specfilm"]),
    ("phase", &["sggx"]),
    ("integrator", &["stokes"]),
];

/// The builder for `node`'s `type`, or an error: a Mitsuba 3 plugin steradian lacks is named as
/// unsupported, any other type is unknown; both list every `type` of the family.
pub(crate) fn lookup<F: Copy>(plugins: &Plugins<F>, node: &PluginNode) -> Result<F, LoadError> {
    if let Some((_, build)) = plugins.iter().find(|(name, _)| *name == node.plugin_type) {
        return Ok(*build);
    }
    let (tag, ty) = (node.tag.name(), node.plugin_type.as_str());
    let known = names(plugins).join(", ");
    let unsupported =
        MITSUBA_UNSUPPORTED.iter().any(|(family, list)| *family == tag && list.contains(&ty));
    let message = if unsupported {
        format!("the Mitsuba 3 {tag} plugin '{ty}' is not supported by steradian (it supports: {known})")
    } else {
        format!("unknown {tag} plugin type '{ty}' (steradian knows: {known})")
    };
    Err(LoadError::at(&node.pos, message))
}

/// The names of a family's plugins, in table order.
pub(crate) fn names<F>(plugins: &Plugins<F>) -> Vec<&'static str> {
    plugins.iter().map(|(name, _)| *name).collect()
}

/// A string property the plugin needs: "missing parameter" at the plugin when absent
/// (`hint` says what it is, e.g. " (a lat-long image)", or is empty).
pub(crate) fn required_string(
    node: &PluginNode,
    name: &str,
    hint: &str,
) -> Result<String, LoadError> {
    node.props.get_string(name)?.ok_or_else(|| {
        LoadError::at(&node.pos, format!("{}: missing parameter '{name}'{hint}", node.desc()))
    })
}

/// An error reading the file a plugin names, placed at its `filename` property (at the plugin
/// when the file came from elsewhere).
pub(crate) fn at_filename<E: std::fmt::Display>(node: &PluginNode) -> impl Fn(E) -> LoadError + '_ {
    move |e| {
        LoadError::at(
            node.props.position("filename").unwrap_or(&node.pos),
            format!("{}: {e}", node.desc()),
        )
    }
}

/// One of the allowed values of a string property, at the property on error.
pub(crate) fn choice<T: Copy>(
    node: &PluginNode,
    name: &str,
    default: T,
    options: &[(&str, T)],
) -> Result<T, LoadError> {
    let Some(v) = node.props.get_string(name)? else { return Ok(default) };
    match options.iter().find(|(s, _)| *s == v) {
        Some((_, t)) => Ok(*t),
        None => {
            let names: Vec<String> = options.iter().map(|(s, _)| format!("\"{s}\"")).collect();
            Err(LoadError::at(
                node.props.position(name).unwrap_or(&node.pos),
                format!(
                    "{}: invalid {name} \"{v}\", must be one of: {}",
                    node.desc(),
                    names.join(", ")
                ),
            ))
        }
    }
}

/// Converts a core-library error message into a loader error at `node`.
pub(crate) fn at(node: &PluginNode) -> impl Fn(String) -> LoadError + '_ {
    move |msg| LoadError::at(&node.pos, format!("{}: {msg}", node.desc()))
}

/// Errors unless every channel of parameter `name`'s value `v` is finite and non-negative,
/// at the property (or the `<texture>` child) that gives it, else at `node`.
pub(crate) fn check_non_negative(
    node: &PluginNode,
    name: &str,
    v: steradian::Spectrum,
) -> Result<(), LoadError> {
    if v.is_finite() && v.min_element() >= 0.0 {
        return Ok(());
    }
    let pos = node
        .props
        .position(name)
        .or_else(|| node.child(name).map(|c| c.pos()))
        .unwrap_or(&node.pos);
    Err(LoadError::at(
        pos,
        format!("{}: '{name}' must be finite and non-negative, got {v}", node.desc()),
    ))
}

/// Converts a core-library parameter error into a loader error at the property it names:
/// `param` where `node` gives it, else the related parameter where `node` gives that (the
/// one the scene set when it left `param` at its default), else `node` itself.
pub(crate) fn at_param(node: &PluginNode) -> impl Fn(ParamError) -> LoadError + '_ {
    move |e| {
        let pos = std::iter::once(e.param)
            .chain(e.related)
            .find_map(|n| node.props.position(n))
            .unwrap_or(&node.pos);
        LoadError::at(pos, format!("{}: {e}", node.desc()))
    }
}

/// Builds the renderable scene from a parsed tree.
pub fn build_scene(tree: &SceneNode, base_dir: &Path) -> Result<Job, LoadError> {
    let root: &PluginNode = &tree.root;
    let mut b = Builder {
        desc: SceneDescription::default(),
        bsdf_cache: HashMap::new(),
        group_cache: HashMap::new(),
        medium_cache: HashMap::new(),
        attached_emitters: HashMap::new(),
        sensor_medium: None,
        default_bsdf: None,
        black_bsdf: None,
        base_dir: base_dir.to_path_buf(),
        resolver: tree.resolver.clone(),
        warnings: RefCell::new(tree.warnings.clone()),
        mesh_attributes: RefCell::new(AttributeSource::None),
        read_mesh_attribute: Cell::new(false),
        sky: Cell::new(None),
        daylight_planes: RefCell::new(Vec::new()),
        integrator_type: root
            .children
            .iter()
            .find(|c| c.node.tag == ObjectTag::Integrator)
            .map(|c| c.node.plugin_type.clone()),
    };
    let mut integrator_pos = None;
    let mut integrator = None;
    let mut environment_pos = None;
    // area emitters declared at the scene level with an id and referenced from a shape (as
    // Mitsuba allows): each is built with the shape that references it
    let referenced_by_shapes: Vec<*const PluginNode> = root
        .children
        .iter()
        .filter(|c| c.node.tag == ObjectTag::Shape)
        .flat_map(|c| c.node.children.iter())
        .filter(|e| e.node.tag == ObjectTag::Emitter && e.ref_pos.is_some())
        .map(|e| Arc::as_ptr(&e.node))
        .collect();
    for child in &root.children {
        child.mark_used();
        let node = &child.node;
        match node.tag {
            ObjectTag::Emitter if referenced_by_shapes.contains(&Arc::as_ptr(node)) => {}
            ObjectTag::Shape => shapes::build(&mut b, node)?,
            ObjectTag::Bsdf => {
                b.mesh_attributes.replace(AttributeSource::Deferred);
                let built = b.bsdf_index(node);
                b.mesh_attributes.replace(AttributeSource::None);
                built?;
            }
            ObjectTag::Emitter => {
                let e = emitters::build_standalone(&b, node)?;
                if e.is_environment() {
                    if let Some(first) = environment_pos.replace(node.pos.clone()) {
                        return Err(LoadError::at(
                            &node.pos,
                            format!("{}: only one environment emitter (`constant` or `envmap`) is allowed per scene; the first is at {first}", node.desc()),
                        ));
                    }
                }
                b.desc.emitters.push(e);
            }
            ObjectTag::Sensor => {
                b.sensor_medium(node)?;
                let s = sensors::build(&b, node, None)?;
                b.desc.sensors.push(s);
            }
            ObjectTag::Texture => {
                // built where it is referenced; built here too so that its errors show
                b.mesh_attributes.replace(AttributeSource::Deferred);
                let built = textures::build(&b, node);
                b.mesh_attributes.replace(AttributeSource::None);
                built?;
            }
            ObjectTag::Medium => {
                b.medium_index(node)?;
            }
            // a sampler, film or filter declared with an id and referenced from a sensor (as
            // Mitsuba allows) is built there; built here too so that its errors show (one no
            // sensor references is unused, as in Mitsuba)
            ObjectTag::Sampler => {
                sensors::build_sampler(&b, node)?;
            }
            ObjectTag::Film => {
                sensors::build_film(node)?;
            }
            ObjectTag::RFilter => {
                sensors::build_filter(node)?;
            }
            ObjectTag::Integrator => {
                if let Some(first) = integrator_pos.replace(node.pos.clone()) {
                    return Err(LoadError::at(
                        &node.pos,
                        format!("a scene has one integrator; the first is at {first}"),
                    ));
                }
                integrator = Some(integrators::build(node)?);
            }
            tag => {
                return Err(LoadError::at(
                    &node.pos,
                    format!(
                        "<{}> objects are not supported at the scene level by steradian yet",
                        tag.name()
                    ),
                ))
            }
        }
    }
    root.check_all_used()?;
    let Some(integrator) = integrator else {
        return Err(LoadError::at(
            &root.pos,
            "the scene has no <integrator> (Mitsuba 3 gives none by default; add e.g. <integrator type=\"path\"/>)",
        ));
    };
    if integrator.alpha_rule().is_none()
        && b.desc.sensors.iter().any(|s| s.film.pixel_format.has_alpha())
    {
        let pos = integrator_pos.clone().unwrap_or_else(|| root.pos.clone());
        return Err(LoadError::at(
            &pos,
            "<integrator type=\"ptracer\">: the film's pixel_format asks for an alpha channel, which needs camera samples (Mitsuba's ptracer writes its light-path splat count there): use a pixel_format without alpha",
        ));
    }
    if let (Integrator::Direct(d), Some(pos)) = (&integrator, &integrator_pos) {
        let delta = b.desc.emitters.iter().any(|e| e.support() == Support::Delta);
        if d.emitter_samples > 1 && delta {
            let n = d.emitter_samples;
            b.warn(LoadWarning::at(
                pos,
                format!(
                    "<integrator type=\"direct\">: with emitter_samples = {n}, Mitsuba 3.9.1 renders point, spot, \
                     directional and projector lights {n} times too bright (it does not divide their samples by \
                     the count); steradian renders them as one sample does (integrator/direct.rs)"
                ),
            ));
        }
    }
    if let (Some(m), Some((pos, _))) = (b.desc.camera_medium, &b.sensor_medium) {
        warn_of_unbounded_camera_medium(&b, m, pos);
    }
    sensors::resolve_daylight_factors(&mut b)?;
    b.desc.light_selection = integrator.light_selection();
    let scene = Scene::new(b.desc).map_err(|m| LoadError::at(&root.pos, m))?;
    let warnings = b.warnings.into_inner().iter().map(ToString::to_string).collect();
    Ok(Job { scene, integrator, warnings, inputs: b.resolver.files_read() })
}

/// Warns where the sensors' medium `m` fills all space (no shape has it inside) and light
/// comes from infinity: no such light crosses an unbounded medium, so steradian renders it
/// black there, where Mitsuba 3.9.1's `volpath` lets it in.
fn warn_of_unbounded_camera_medium(b: &Builder, m: u32, pos: &crate::SourcePos) {
    use steradian::emitter::Emitter;
    let bounded = b
        .desc
        .shapes
        .iter()
        .chain(b.desc.groups.iter().flatten())
        .any(|(_, binding)| binding.interior == Some(m));
    let at_infinity = b
        .desc
        .emitters
        .iter()
        .any(|e| e.is_environment() || matches!(e, Emitter::Sun(_) | Emitter::Directional(_)));
    if !bounded && at_infinity {
        b.warn(LoadWarning::at(
            pos,
            "the sensor's medium is no shape's interior, so it fills all space and no light from \
             infinity (environment, sun, directional light) crosses it: that light does not reach \
             the camera (Mitsuba 3.9.1's volpath lets it in); to see the sky through fog, bound the \
             fog by a shape with a null BSDF and the medium as its interior"
                .to_string(),
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The README's table of supported plugins names every plugin of every family's table.
    #[test]
    fn readme_lists_every_plugin() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md");
        let readme = std::fs::read_to_string(path).unwrap();
        let families = [
            ("shapes", names(geometry::SHAPES)),
            ("BSDFs", names(bsdfs::BSDFS)),
            ("textures", names(textures::TEXTURES)),
            ("emitters", [names(emitters::EMITTERS), vec!["area"]].concat()),
            (
                "sensors",
                [names(sensors::SENSORS), names(sensors::FILMS), names(sensors::FILTERS)].concat(),
            ),
            ("samplers", names(sensors::SAMPLERS)),
            ("integrators", names(integrators::INTEGRATORS)),
            ("media", [names(media::MEDIA), names(media::VOLUMES), names(media::PHASES)].concat()),
        ];
        for (family, plugins) in families {
            let row = readme
                .lines()
                .find(|l| l.starts_with(&format!("| {family} ")))
                .unwrap_or_else(|| panic!("README.md has no row for {family}"));
            for name in plugins {
                assert!(
                    row.contains(&format!("`{name}`")),
                    "README.md's {family} row lacks {name}"
                );
            }
        }
    }
}
