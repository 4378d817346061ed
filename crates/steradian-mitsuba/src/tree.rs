//! The parsed scene tree: plugin objects ([`PluginNode`]) with their typed properties and
//! child objects, shared where several `<ref>`s point at one object.
//!
//! The XML parser ([`crate::xml`]) builds it; the plugin registry reads it. Reading a
//! property or taking a child marks it as used, so [`PluginNode::check_all_used`] can report
//! whatever a plugin ignored.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::error::{LoadError, LoadWarning};
use crate::file_resolver::FileResolver;
use crate::properties::Properties;
use crate::source::SourcePos;

/// The kind of a plugin object: the XML tag it was declared with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ObjectTag {
    Scene,
    Shape,
    Bsdf,
    Emitter,
    Sensor,
    Film,
    Sampler,
    RFilter,
    Integrator,
    Texture,
    Medium,
    Phase,
    Volume,
    /// `<spectrum type="...">`: a spectrum plugin (a texture in Mitsuba).
    Spectrum,
}

impl ObjectTag {
    /// The tag for an element name (`<spectrum>` only counts with a `type`, see parser).
    pub fn from_name(name: &str) -> Option<ObjectTag> {
        Some(match name {
            "scene" => ObjectTag::Scene,
            "shape" => ObjectTag::Shape,
            "bsdf" => ObjectTag::Bsdf,
            "emitter" => ObjectTag::Emitter,
            "sensor" => ObjectTag::Sensor,
            "film" => ObjectTag::Film,
            "sampler" => ObjectTag::Sampler,
            "rfilter" => ObjectTag::RFilter,
            "integrator" => ObjectTag::Integrator,
            "texture" => ObjectTag::Texture,
            "medium" => ObjectTag::Medium,
            "phase" => ObjectTag::Phase,
            "volume" => ObjectTag::Volume,
            _ => return None,
        })
    }

    /// The XML element name.
    pub fn name(&self) -> &'static str {
        match self {
            ObjectTag::Scene => "scene",
            ObjectTag::Shape => "shape",
            ObjectTag::Bsdf => "bsdf",
            ObjectTag::Emitter => "emitter",
            ObjectTag::Sensor => "sensor",
            ObjectTag::Film => "film",
            ObjectTag::Sampler => "sampler",
            ObjectTag::RFilter => "rfilter",
            ObjectTag::Integrator => "integrator",
            ObjectTag::Texture => "texture",
            ObjectTag::Medium => "medium",
            ObjectTag::Phase => "phase",
            ObjectTag::Volume => "volume",
            ObjectTag::Spectrum => "spectrum",
        }
    }
}

/// One plugin object of the scene: `<bsdf type="diffuse" id="white">…</bsdf>`.
#[derive(Debug)]
pub struct PluginNode {
    pub tag: ObjectTag,
    /// The `type` attribute (`"scene"` for the root).
    pub plugin_type: String,
    pub id: Option<String>,
    /// The `name` attribute it was declared with (its slot in the parent), if any.
    pub name: Option<String>,
    /// Where the element starts.
    pub pos: SourcePos,
    pub props: Properties,
    /// Nested objects and resolved references, in document order.
    pub children: Vec<Child>,
}

/// A child object of a [`PluginNode`]: nested in it, or a resolved `<ref>`.
#[derive(Debug)]
pub struct Child {
    /// The slot name (`name` of the nested element or of the `<ref>`), if any.
    pub name: Option<String>,
    /// The object; shared when several `<ref>`s point at it.
    pub node: Arc<PluginNode>,
    /// Where the `<ref>` was, for a reference; `None` for a nested object.
    pub ref_pos: Option<SourcePos>,
    used: AtomicBool,
}

impl Child {
    /// A child in slot `name`, not used yet; `ref_pos` is where its `<ref>` was, if any.
    pub(crate) fn new(
        name: Option<String>,
        node: Arc<PluginNode>,
        ref_pos: Option<SourcePos>,
    ) -> Child {
        Child { name, node, ref_pos, used: AtomicBool::new(false) }
    }

    /// The position to report errors about this child at (the `<ref>` or the element).
    pub fn pos(&self) -> &SourcePos {
        self.ref_pos.as_ref().unwrap_or(&self.node.pos)
    }

    /// Marks this child as consumed by its parent plugin.
    pub fn mark_used(&self) {
        self.used.store(true, Ordering::Relaxed);
    }

    pub fn is_used(&self) -> bool {
        self.used.load(Ordering::Relaxed)
    }
}

impl PluginNode {
    /// `<bsdf type="diffuse">` (with ` id="…"` when it has one): how errors name it.
    pub fn desc(&self) -> String {
        describe(self.tag, &self.plugin_type, self.id.as_deref())
    }

    /// The child in slot `name`, marked as used.
    pub fn child(&self, name: &str) -> Option<&Child> {
        let c = self.children.iter().find(|c| c.name.as_deref() == Some(name))?;
        c.mark_used();
        Some(c)
    }

    /// All children of one kind (named or not), marked as used.
    pub fn children_of(&self, tag: ObjectTag) -> Vec<&Child> {
        let v: Vec<&Child> = self.children.iter().filter(|c| c.node.tag == tag).collect();
        for c in &v {
            c.mark_used();
        }
        v
    }

    /// Errors on the first unread property or unused child object.
    pub fn check_all_used(&self) -> Result<(), LoadError> {
        let desc = self.desc();
        self.props.check_all_used(&desc)?;
        if let Some(c) = self.children.iter().find(|c| !c.is_used()) {
            let asked = c.name.as_deref().and_then(|n| Some((n, self.props.asked_as_value(n)?)));
            if let Some((name, expected)) = asked {
                // Mitsuba 3.9.1: "The parameter 'intensity' cannot be spatially varying"
                return Err(LoadError::at(
                    c.pos(),
                    format!(
                        "'{name}' of {desc} cannot be spatially varying ({}): give it as a \
                         value ({expected})",
                        c.node.desc()
                    ),
                ));
            }
            return Err(LoadError::at(
                c.pos(),
                format!("unreferenced object {} in {desc}", c.node.desc()),
            ));
        }
        Ok(())
    }
}

/// A parsed scene: the root `<scene>` node plus every object that has an `id`.
#[derive(Debug)]
pub struct SceneNode {
    pub root: Arc<PluginNode>,
    /// Objects by `id` (aliases included), e.g. to pick a sensor.
    pub ids: BTreeMap<String, Arc<PluginNode>>,
    /// Where the plugins' relative file names are looked up (the scene's folder and its
    /// `<path>`s).
    pub resolver: FileResolver,
    /// What the parser warned about (e.g. a `<rotate>` about a non-unit axis).
    pub warnings: Vec<LoadWarning>,
}

impl std::ops::Deref for SceneNode {
    type Target = PluginNode;
    fn deref(&self) -> &PluginNode {
        &self.root
    }
}

/// How errors name an object: `<bsdf type="diffuse" id="white">`.
pub(crate) fn describe(tag: ObjectTag, plugin_type: &str, id: Option<&str>) -> String {
    match id {
        Some(id) => format!("<{} type=\"{plugin_type}\" id=\"{id}\">", tag.name()),
        None => format!("<{} type=\"{plugin_type}\">", tag.name()),
    }
}
