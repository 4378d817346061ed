//! Parsing: XML text → a tree of [`PluginNode`]s with typed [`Properties`].
//!
//! Follows Mitsuba 3's `src/core/xml.cpp` (see the crate docs for the rules).

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use glam::Vec3;
use steradian::geometry::Transform;

use crate::error::LoadError;
use crate::properties::{Properties, PropertyValue, SpectrumValue};
use crate::source::SourcePos;
use crate::spectrum::{self, SpectrumRole};
use crate::upgrade;

/// Nesting deeper than this is refused (protects the stack).
const MAX_DEPTH: usize = 128;
/// Mitsuba's `MI_XML_INCLUDE_MAX_RECURSION`.
const MAX_INCLUDE_DEPTH: usize = 15;

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
}

impl std::ops::Deref for SceneNode {
    type Target = PluginNode;
    fn deref(&self) -> &PluginNode {
        &self.root
    }
}

pub(crate) fn describe(tag: ObjectTag, plugin_type: &str, id: Option<&str>) -> String {
    match id {
        Some(id) => format!("<{} type=\"{plugin_type}\" id=\"{id}\">", tag.name()),
        None => format!("<{} type=\"{plugin_type}\">", tag.name()),
    }
}

/// Splits a list value at whitespace and commas (Mitsuba's `string::tokenize`).
pub(crate) fn tokenize(s: &str) -> Vec<&str> {
    s.split(|c: char| c.is_whitespace() || c == ',').filter(|t| !t.is_empty()).collect()
}

/// A floating-point number as Mitsuba's `string::stof` reads it (no trailing garbage).
pub(crate) fn parse_f64(s: &str) -> Option<f64> {
    let t = s.trim();
    if t.is_empty() {
        return None;
    }
    t.parse::<f64>().ok()
}

/// One attribute after `$` substitution.
#[derive(Debug)]
pub(crate) struct Attr {
    pub name: String,
    pub value: String,
    pub pos: SourcePos,
}

/// The attributes of one element, with the element's name and position.
#[derive(Debug)]
pub(crate) struct Attrs {
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

/// Parses the scene file at `path`. `defines` are `-D name=value` parameters: they override
/// `<default>`s, and one the scene never uses as `$name` is an error (as in Mitsuba 3).
pub fn parse_file(path: &Path, defines: &[(String, String)]) -> Result<SceneNode, LoadError> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        LoadError::new(None, format!("cannot read scene file \"{}\": {e}", path.display()))
    })?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut p = Parser::new(defines);
    p.include_stack.push(path.canonicalize().unwrap_or_else(|_| path.to_path_buf()));
    p.parse_root(Arc::new(path.to_path_buf()), &text, dir)
}

/// Parses a scene from a string (positions name the file `<string>`); `<include>`s are
/// resolved relative to `base_dir`.
pub fn parse_string(
    xml: &str,
    base_dir: &Path,
    defines: &[(String, String)],
) -> Result<SceneNode, LoadError> {
    parse_string_named(xml, Path::new("<string>"), base_dir, defines)
}

/// [`parse_string`] with the name error positions should give the source.
pub fn parse_string_named(
    xml: &str,
    name: &Path,
    base_dir: &Path,
    defines: &[(String, String)],
) -> Result<SceneNode, LoadError> {
    let mut p = Parser::new(defines);
    p.parse_root(Arc::new(name.to_path_buf()), xml, base_dir.to_path_buf())
}

struct Param {
    name: String,
    value: String,
    used: bool,
}

#[derive(Clone)]
enum IdTarget {
    /// The object is still being parsed.
    Pending,
    Node(usize),
    Alias(String),
}

struct RawNode {
    tag: ObjectTag,
    plugin_type: String,
    id: Option<String>,
    name: Option<String>,
    pos: SourcePos,
    props: Properties,
    children: Vec<RawChild>,
}

enum RawChild {
    Nested(usize),
    Ref { id: String, name: Option<String>, pos: SourcePos },
}

/// The object whose content is being read.
struct Builder {
    tag: ObjectTag,
    plugin_type: String,
    desc: String,
    props: Properties,
    children: Vec<RawChild>,
    /// Slot names taken so far (properties and named children share one namespace).
    names: HashMap<String, SourcePos>,
}

impl Builder {
    fn new(tag: ObjectTag, plugin_type: &str, id: Option<&str>) -> Self {
        let desc = describe(tag, plugin_type, id);
        Builder {
            tag,
            plugin_type: plugin_type.to_string(),
            props: Properties::new(desc.clone()),
            desc,
            children: Vec::new(),
            names: HashMap::new(),
        }
    }

    fn claim(&mut self, name: &str, pos: &SourcePos) -> Result<(), LoadError> {
        if let Some(prev) = self.names.get(name) {
            return Err(LoadError::at(
                pos,
                format!(
                    "property '{name}' is specified twice in {} (first at {})",
                    self.desc,
                    prev.line_col()
                ),
            ));
        }
        self.names.insert(name.to_string(), pos.clone());
        Ok(())
    }
}

/// One open document.
struct Src<'d, 'i> {
    path: Arc<PathBuf>,
    doc: &'d roxmltree::Document<'i>,
    dir: PathBuf,
    /// Apply the pre-2.0 upgrade rules.
    upgrade: bool,
}

impl Src<'_, '_> {
    fn pos(&self, byte: usize) -> SourcePos {
        let p = self.doc.text_pos_at(byte);
        SourcePos { file: self.path.clone(), line: p.row, col: p.col }
    }
}

struct Parser {
    params: Vec<Param>,
    /// Names given as defines (checked for use at the end).
    define_names: Vec<String>,
    nodes: Vec<Option<RawNode>>,
    ids: HashMap<String, (IdTarget, SourcePos)>,
    include_stack: Vec<PathBuf>,
}

fn xml_error(path: &Arc<PathBuf>, e: &roxmltree::Error) -> LoadError {
    let p = e.pos();
    let pos = SourcePos { file: path.clone(), line: p.row, col: p.col };
    let msg = e.to_string();
    // roxmltree appends " at line:col"; the position is already in front.
    let msg = msg.rsplit_once(" at ").map(|(m, _)| m.to_string()).unwrap_or(msg);
    LoadError::at(&pos, format!("malformed XML: {msg}"))
}

fn parse_doc<'i>(path: &Arc<PathBuf>, text: &'i str) -> Result<roxmltree::Document<'i>, LoadError> {
    let opts = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    roxmltree::Document::parse_with_options(text, opts).map_err(|e| xml_error(path, &e))
}

/// Parses `major.minor.patch`.
fn parse_version(s: &str) -> Option<[u32; 3]> {
    let parts: Vec<&str> = s.split(['.', ' ']).filter(|t| !t.is_empty()).collect();
    if parts.len() != 3 {
        return None;
    }
    let mut v = [0u32; 3];
    for (i, p) in parts.iter().enumerate() {
        if !p.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        v[i] = p.parse().ok()?;
    }
    Some(v)
}

impl Parser {
    fn new(defines: &[(String, String)]) -> Self {
        Parser {
            params: defines
                .iter()
                .map(|(n, v)| Param { name: n.clone(), value: v.clone(), used: false })
                .collect(),
            define_names: defines.iter().map(|(n, _)| n.clone()).collect(),
            nodes: Vec::new(),
            ids: HashMap::new(),
            include_stack: Vec::new(),
        }
    }

    /// Attributes of `el` with `$name` parameters substituted (longest names first, as
    /// Mitsuba does); a `$` left over is an undefined parameter.
    fn attrs(&mut self, src: &Src, el: roxmltree::Node, elem: &str) -> Result<Attrs, LoadError> {
        self.params.sort_by_key(|p| std::cmp::Reverse(p.name.len()));
        let mut list = Vec::new();
        for a in el.attributes() {
            let pos = src.pos(a.range().start);
            let mut value = a.value().to_string();
            if value.contains('$') {
                for p in self.params.iter_mut() {
                    let key = format!("${}", p.name);
                    if value.contains(&key) {
                        value = value.replace(&key, &p.value);
                        p.used = true;
                    }
                }
                if let Some(i) = value.find('$') {
                    let name: String = value[i + 1..]
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    return Err(LoadError::at(
                        &pos,
                        format!("undefined parameter '${name}' in attribute '{}' (declare it with <default name=\"{name}\" value=\"…\"/> or pass it as a define)", a.name()),
                    ));
                }
            }
            list.push(Attr { name: a.name().to_string(), value, pos });
        }
        Ok(Attrs { elem: elem.to_string(), pos: src.pos(el.range().start), list })
    }

    fn parse_root(
        &mut self,
        path: Arc<PathBuf>,
        text: &str,
        dir: PathBuf,
    ) -> Result<SceneNode, LoadError> {
        let doc = parse_doc(&path, text)?;
        let root = doc.root_element();
        let mut src = Src { path: path.clone(), doc: &doc, dir, upgrade: false };
        let name = root.tag_name().name().to_string();
        let attrs = self.attrs(&src, root, &name)?;
        if name != "scene" {
            return Err(attrs.error(format!("the root element must be <scene>, not <{name}>")));
        }
        src.upgrade = self.scene_version(&attrs, true)?;
        attrs.allow(&["version", "id"])?;
        let id = attrs.get("id").map(|a| a.value.clone());
        let mut b = Builder::new(ObjectTag::Scene, "scene", id.as_deref());
        if let Some(id) = &id {
            self.ids.insert(id.clone(), (IdTarget::Pending, attrs.pos.clone()));
        }
        self.parse_children(&src, root, &mut b, 1)?;
        let idx = self.push(b, id.clone(), None, attrs.pos.clone());
        if let Some(id) = id {
            self.ids.insert(id, (IdTarget::Node(idx), attrs.pos.clone()));
        }
        for d in &self.define_names {
            if !self.params.iter().any(|p| &p.name == d && p.used) {
                return Err(attrs.error(format!(
                    "unused parameter '{d}': it was given as a define but the scene never uses ${d}"
                )));
            }
        }
        self.resolve(idx)
    }

    /// Reads `version`; returns whether the document needs the pre-2.0 upgrade.
    fn scene_version(&self, attrs: &Attrs, required: bool) -> Result<bool, LoadError> {
        match attrs.get("version") {
            None if required => Err(attrs.error("missing version attribute in root element <scene>")),
            None => Ok(false),
            Some(a) => match parse_version(&a.value) {
                Some(v) => Ok(upgrade::needs_upgrade(v)),
                None => Err(LoadError::at(
                    &a.pos,
                    format!("could not parse version number \"{}\" (expected major.minor.patch, e.g. 3.0.0)", a.value),
                )),
            },
        }
    }

    fn push(
        &mut self,
        b: Builder,
        id: Option<String>,
        name: Option<String>,
        pos: SourcePos,
    ) -> usize {
        self.nodes.push(Some(RawNode {
            tag: b.tag,
            plugin_type: b.plugin_type,
            id,
            name,
            pos,
            props: b.props,
            children: b.children,
        }));
        self.nodes.len() - 1
    }

    fn parse_children(
        &mut self,
        src: &Src,
        el: roxmltree::Node,
        b: &mut Builder,
        depth: usize,
    ) -> Result<(), LoadError> {
        for ch in el.children() {
            if ch.is_element() {
                self.parse_element(src, ch, b, depth)?;
            } else if ch.is_text() {
                let t = ch.text().unwrap_or("");
                if !t.trim().is_empty() {
                    return Err(LoadError::at(
                        &src.pos(ch.range().start),
                        format!("unexpected text \"{}\" in {}", t.trim(), b.desc),
                    ));
                }
            }
        }
        if src.upgrade {
            upgrade_uv(b)?;
        }
        Ok(())
    }

    /// A property or transform-op element must not contain elements or text.
    fn no_content(&self, src: &Src, el: roxmltree::Node, what: &str) -> Result<(), LoadError> {
        for ch in el.children() {
            if ch.is_element() {
                return Err(LoadError::at(
                    &src.pos(ch.range().start),
                    format!("<{}> cannot occur inside {what}", ch.tag_name().name()),
                ));
            }
            if ch.is_text() && !ch.text().unwrap_or("").trim().is_empty() {
                return Err(LoadError::at(
                    &src.pos(ch.range().start),
                    format!("unexpected text inside {what}"),
                ));
            }
        }
        Ok(())
    }

    /// The `name` of a property/child after the upgrade rules; reserved `_` names refused.
    fn slot_name(&self, src: &Src, a: &Attr, parent: &Builder) -> Result<String, LoadError> {
        let mut name = a.value.clone();
        if src.upgrade {
            name = upgrade::camel_to_snake(&name);
            if parent.tag == ObjectTag::Bsdf
                && parent.plugin_type == "diffuse"
                && name == "diffuse_reflectance"
            {
                name = "reflectance".to_string();
            }
        }
        if name.starts_with('_') {
            return Err(LoadError::at(
                &a.pos,
                format!("invalid name \"{name}\": leading underscores are reserved"),
            ));
        }
        if name.is_empty() {
            return Err(LoadError::at(&a.pos, "empty 'name' attribute"));
        }
        Ok(name)
    }

    fn parse_element(
        &mut self,
        src: &Src,
        el: roxmltree::Node,
        parent: &mut Builder,
        depth: usize,
    ) -> Result<(), LoadError> {
        let mut tag = el.tag_name().name().to_string();
        if src.upgrade && tag == "lookAt" {
            tag = "lookat".to_string();
        }
        let attrs = self.attrs(src, el, &tag)?;
        if depth > MAX_DEPTH {
            return Err(attrs.error("elements are nested too deeply"));
        }
        match tag.as_str() {
            "boolean" | "integer" | "float" | "string" | "point" | "vector" | "rgb" => {
                self.no_content(src, el, &format!("<{tag}>"))?;
                self.parse_property(src, &attrs, parent)
            }
            "spectrum" if attrs.get("type").is_none() => {
                self.no_content(src, el, "<spectrum>")?;
                self.parse_property(src, &attrs, parent)
            }
            "spectrum" => self.parse_object(src, el, &attrs, ObjectTag::Spectrum, parent, depth),
            "transform" => self.parse_transform(src, el, &attrs, parent),
            "translate" | "rotate" | "scale" | "matrix" | "lookat" => Err(attrs
                .error(format!("transform operation <{tag}> can only occur inside <transform>"))),
            "ref" => {
                self.no_content(src, el, "<ref>")?;
                attrs.allow(&["id", "name"])?;
                let id = attrs.require("id")?.value.clone();
                let name = match attrs.get("name") {
                    Some(a) => {
                        let n = self.slot_name(src, a, parent)?;
                        parent.claim(&n, &attrs.pos)?;
                        Some(n)
                    }
                    None => None,
                };
                let id = if src.upgrade { upgrade::upgrade_id(&id) } else { id };
                parent.children.push(RawChild::Ref { id, name, pos: attrs.pos.clone() });
                Ok(())
            }
            "default" => {
                self.no_content(src, el, "<default>")?;
                attrs.allow(&["name", "value"])?;
                let name = attrs.require("name")?.value.clone();
                let value = attrs.require("value")?.value.clone();
                if name.is_empty() || name.contains(',') || name.contains('$') {
                    return Err(
                        attrs.error(format!("invalid parameter name \"{name}\" in <default>"))
                    );
                }
                if !self.params.iter().any(|p| p.name == name) {
                    // A <default> counts as used: only unused defines are errors.
                    self.params.push(Param { name, value, used: true });
                }
                Ok(())
            }
            "include" => {
                self.no_content(src, el, "<include>")?;
                self.parse_include(src, &attrs, parent, depth)
            }
            "alias" => {
                self.no_content(src, el, "<alias>")?;
                attrs.allow(&["id", "as"])?;
                let target = attrs.require("id")?.value.clone();
                let alias = attrs.require("as")?.value.clone();
                if let Some((_, prev)) = self.ids.get(&alias) {
                    return Err(attrs.error(format!(
                        "duplicate id \"{alias}\" (first defined at {})",
                        prev.line_col()
                    )));
                }
                if !self.ids.contains_key(&target) {
                    return Err(attrs.error(format!("<alias> refers to unknown id \"{target}\"")));
                }
                self.ids.insert(alias, (IdTarget::Alias(target), attrs.pos.clone()));
                Ok(())
            }
            "path" => Err(attrs.error("<path> (extra search folders) is not supported yet")),
            "scene" => Err(attrs.error("<scene> can only be the root element")),
            _ => match ObjectTag::from_name(&tag) {
                Some(t) => self.parse_object(src, el, &attrs, t, parent, depth),
                None => Err(attrs.error(format!("unexpected tag <{tag}>"))),
            },
        }
    }

    fn parse_object(
        &mut self,
        src: &Src,
        el: roxmltree::Node,
        attrs: &Attrs,
        tag: ObjectTag,
        parent: &mut Builder,
        depth: usize,
    ) -> Result<(), LoadError> {
        attrs.allow(&["type", "id", "name"])?;
        let plugin_type = attrs.require("type")?.value.clone();
        if plugin_type.is_empty() {
            return Err(attrs.error(format!("empty 'type' attribute in <{}>", tag.name())));
        }
        let id = match attrs.get("id") {
            Some(a) if src.upgrade => Some(upgrade::upgrade_id(&a.value)),
            Some(a) if a.value.starts_with('_') => {
                return Err(LoadError::at(
                    &a.pos,
                    format!("invalid id \"{}\": leading underscores are reserved", a.value),
                ))
            }
            Some(a) if a.value.is_empty() => {
                return Err(LoadError::at(&a.pos, "empty 'id' attribute"))
            }
            Some(a) => Some(a.value.clone()),
            None => None,
        };
        let name = match attrs.get("name") {
            Some(a) => {
                let n = self.slot_name(src, a, parent)?;
                parent.claim(&n, &attrs.pos)?;
                Some(n)
            }
            None => None,
        };
        if let Some(id) = &id {
            if let Some((_, prev)) = self.ids.get(id) {
                return Err(attrs.error(format!(
                    "<{}> has duplicate id \"{id}\" (first defined at {})",
                    tag.name(),
                    prev.line_col()
                )));
            }
            self.ids.insert(id.clone(), (IdTarget::Pending, attrs.pos.clone()));
        }
        let mut b = Builder::new(tag, &plugin_type, id.as_deref());
        self.parse_children(src, el, &mut b, depth + 1)?;
        let idx = self.push(b, id.clone(), name, attrs.pos.clone());
        if let Some(id) = id {
            self.ids.insert(id, (IdTarget::Node(idx), attrs.pos.clone()));
        }
        parent.children.push(RawChild::Nested(idx));
        Ok(())
    }

    fn parse_include(
        &mut self,
        src: &Src,
        attrs: &Attrs,
        parent: &mut Builder,
        depth: usize,
    ) -> Result<(), LoadError> {
        attrs.allow(&["filename"])?;
        let fname = &attrs.require("filename")?.value;
        let path = src.dir.join(fname);
        if !path.is_file() {
            return Err(attrs.error(format!("included file \"{}\" not found", path.display())));
        }
        let canon = path.canonicalize().unwrap_or_else(|_| path.clone());
        if self.include_stack.contains(&canon) {
            return Err(attrs.error(format!(
                "include cycle: \"{}\" includes itself (directly or indirectly)",
                path.display()
            )));
        }
        if self.include_stack.len() > MAX_INCLUDE_DEPTH {
            return Err(
                attrs.error(format!("<include> nesting exceeds the limit of {MAX_INCLUDE_DEPTH}"))
            );
        }
        let text = std::fs::read_to_string(&path).map_err(|e| {
            attrs.error(format!("cannot read included file \"{}\": {e}", path.display()))
        })?;
        let ipath = Arc::new(path.clone());
        let doc = parse_doc(&ipath, &text)?;
        let root = doc.root_element();
        let mut isrc = Src {
            path: ipath,
            doc: &doc,
            dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            upgrade: false,
        };
        let rname = root.tag_name().name().to_string();
        let rattrs = self.attrs(&isrc, root, &rname)?;
        if rname != "scene" {
            return Err(rattrs.error(format!(
                "an included file must have a <scene> root element, not <{rname}>"
            )));
        }
        rattrs.allow(&["version"])?;
        isrc.upgrade = self.scene_version(&rattrs, false)?;
        self.include_stack.push(canon);
        let r = self.parse_children(&isrc, root, parent, depth);
        self.include_stack.pop();
        r
    }

    fn parse_transform(
        &mut self,
        src: &Src,
        el: roxmltree::Node,
        attrs: &Attrs,
        parent: &mut Builder,
    ) -> Result<(), LoadError> {
        attrs.allow(&["name"])?;
        let name = self.slot_name(src, attrs.require("name")?, parent)?;
        parent.claim(&name, &attrs.pos)?;
        let mut acc = Transform::IDENTITY;
        for ch in el.children() {
            if ch.is_text() {
                if !ch.text().unwrap_or("").trim().is_empty() {
                    return Err(LoadError::at(
                        &src.pos(ch.range().start),
                        "unexpected text inside <transform>",
                    ));
                }
                continue;
            }
            if !ch.is_element() {
                continue;
            }
            let mut op = ch.tag_name().name().to_string();
            if src.upgrade && op == "lookAt" {
                op = "lookat".to_string();
            }
            let oattrs = self.attrs(src, ch, &op)?;
            if !matches!(op.as_str(), "translate" | "rotate" | "scale" | "matrix" | "lookat") {
                return Err(oattrs.error(format!(
                    "<transform> can only contain transform operations (translate, rotate, scale, matrix, lookat), not <{op}>"
                )));
            }
            self.no_content(src, ch, &format!("<{op}>"))?;
            let t = crate::transform::parse_op(&op, &oattrs)?;
            acc = acc.then(&t);
            if !acc.m.is_finite() || !acc.inv.is_finite() {
                return Err(oattrs.error("the transform becomes degenerate (NaN or infinite) here"));
            }
        }
        parent.props.insert(name, PropertyValue::Transform(acc), attrs.pos.clone())
    }

    fn parse_property(
        &mut self,
        src: &Src,
        attrs: &Attrs,
        parent: &mut Builder,
    ) -> Result<(), LoadError> {
        let tag = attrs.elem.as_str();
        let allowed: &[&str] = match tag {
            "point" | "vector" => &["name", "value", "x", "y", "z"],
            "spectrum" => &["name", "value", "filename"],
            _ => &["name", "value"],
        };
        attrs.allow(allowed)?;
        let name = self.slot_name(src, attrs.require("name")?, parent)?;
        parent.claim(&name, &attrs.pos)?;
        let num = |a: &Attr, t: &str| -> Result<f64, LoadError> {
            parse_f64(t).ok_or_else(|| {
                LoadError::at(
                    &a.pos,
                    format!(
                        "could not parse floating point value \"{}\" in <{tag} name=\"{name}\">",
                        t.trim()
                    ),
                )
            })
        };
        let value = match tag {
            "boolean" => {
                let a = attrs.require("value")?;
                match a.value.to_lowercase().as_str() {
                    "true" => PropertyValue::Bool(true),
                    "false" => PropertyValue::Bool(false),
                    _ => {
                        return Err(LoadError::at(
                            &a.pos,
                            format!(
                            "could not parse boolean value \"{}\" (must be \"true\" or \"false\")",
                            a.value
                        ),
                        ))
                    }
                }
            }
            "integer" => {
                let a = attrs.require("value")?;
                match a.value.trim().parse::<i64>() {
                    Ok(i) => PropertyValue::Int(i),
                    Err(_) => {
                        return Err(LoadError::at(
                            &a.pos,
                            format!(
                                "could not parse integer value \"{}\" in <integer name=\"{name}\">",
                                a.value
                            ),
                        ))
                    }
                }
            }
            "float" => {
                let a = attrs.require("value")?;
                PropertyValue::Float(num(a, &a.value)?)
            }
            "string" => PropertyValue::String(attrs.require("value")?.value.clone()),
            "point" | "vector" => {
                let v = if let Some(a) = attrs.get("value") {
                    if attrs.get("x").is_some()
                        || attrs.get("y").is_some()
                        || attrs.get("z").is_some()
                    {
                        return Err(attrs.error(format!(
                            "<{tag}> can't mix 'value' with 'x'/'y'/'z' attributes"
                        )));
                    }
                    let toks = tokenize(&a.value);
                    let n = toks.iter().map(|t| num(a, t)).collect::<Result<Vec<_>, _>>()?;
                    match n.len() {
                        1 => Vec3::splat(n[0] as f32),
                        3 => Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32),
                        k => {
                            return Err(LoadError::at(
                                &a.pos,
                                format!("'value' of <{tag}> must have 1 or 3 numbers, got {k}"),
                            ))
                        }
                    }
                } else {
                    // Mitsuba requires all of x, y and z.
                    let mut v = [0.0f32; 3];
                    for (i, c) in ["x", "y", "z"].iter().enumerate() {
                        let a = attrs.require(c)?;
                        v[i] = num(a, &a.value)? as f32;
                    }
                    Vec3::from(v)
                };
                if tag == "point" {
                    PropertyValue::Point(v)
                } else {
                    PropertyValue::Vector(v)
                }
            }
            "rgb" => {
                let a = attrs.require("value")?;
                let toks = tokenize(&a.value);
                let n = toks.iter().map(|t| num(a, t)).collect::<Result<Vec<_>, _>>()?;
                match n.len() {
                    1 => PropertyValue::Rgb(Vec3::splat(n[0] as f32)),
                    3 => PropertyValue::Rgb(Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32)),
                    k => {
                        return Err(LoadError::at(
                            &a.pos,
                            format!("<rgb> needs one or three values, got {k}"),
                        ))
                    }
                }
            }
            "spectrum" => PropertyValue::Spectrum(self.parse_spectrum(
                attrs,
                &name,
                parent.tag == ObjectTag::Emitter,
            )?),
            _ => return Err(attrs.error(format!("unexpected tag <{tag}>"))),
        };
        parent.props.insert(name, value, attrs.pos.clone())
    }

    fn parse_spectrum(
        &self,
        attrs: &Attrs,
        name: &str,
        within_emitter: bool,
    ) -> Result<SpectrumValue, LoadError> {
        match (attrs.get("value"), attrs.get("filename")) {
            (Some(_), Some(_)) | (None, None) => Err(attrs
                .error("<spectrum> needs exactly one of the attributes 'value' and 'filename'")),
            (None, Some(a)) => Err(LoadError::at(
                &a.pos,
                "<spectrum filename=…> (.spd files) is not supported yet",
            )),
            (Some(a), None) => {
                let role = SpectrumRole::of(name, within_emitter);
                let toks = tokenize(&a.value);
                if toks.len() == 1 && !toks[0].contains(':') {
                    let v = parse_f64(toks[0]).ok_or_else(|| {
                        LoadError::at(
                            &a.pos,
                            format!("could not parse constant spectrum \"{}\"", toks[0]),
                        )
                    })?;
                    return Ok(match spectrum::uniform_to_rgb(v, role) {
                        Some(c) => SpectrumValue::Rgb(c),
                        None => SpectrumValue::Uniform(v as f32),
                    });
                }
                let mut wl = Vec::new();
                let mut vals = Vec::new();
                for t in &toks {
                    let pair: Vec<&str> = t.split(':').collect();
                    let (w, v) = match pair.as_slice() {
                        [w, v] => (parse_f64(w), parse_f64(v)),
                        _ => {
                            return Err(LoadError::at(
                                &a.pos,
                                format!(
                                "invalid spectrum entry \"{t}\" (expected wavelength:value pairs)"
                            ),
                            ))
                        }
                    };
                    match (w, v) {
                        (Some(w), Some(v)) if w.is_finite() && v.is_finite() => {
                            if let Some(&prev) = wl.last() {
                                if w <= prev {
                                    return Err(LoadError::at(
                                        &a.pos,
                                        "spectrum wavelengths must be strictly increasing",
                                    ));
                                }
                            }
                            wl.push(w);
                            vals.push(v);
                        }
                        _ => {
                            return Err(LoadError::at(
                                &a.pos,
                                format!("could not parse wavelength:value pair \"{t}\""),
                            ))
                        }
                    }
                }
                if wl.len() < 2 {
                    return Err(LoadError::at(
                        &a.pos,
                        "a spectrum needs at least two wavelength:value pairs",
                    ));
                }
                Ok(SpectrumValue::Rgb(spectrum::wavelength_list_to_rgb(&wl, &vals, role)))
            }
        }
    }

    /// Links references and builds the shared tree.
    fn resolve(&mut self, root: usize) -> Result<SceneNode, LoadError> {
        let mut built: Vec<Option<Arc<PluginNode>>> = vec![None; self.nodes.len()];
        let mut visiting = vec![false; self.nodes.len()];
        let root = self.build(root, None, &mut built, &mut visiting)?;
        let mut ids = BTreeMap::new();
        let keys: Vec<String> = self.ids.keys().cloned().collect();
        for id in keys {
            if let Ok(idx) = self.lookup(&id, None) {
                // Objects that nothing reached (impossible: all hang off the root) are skipped.
                if let Some(n) = &built[idx] {
                    ids.insert(id, n.clone());
                }
            }
        }
        Ok(SceneNode { root, ids })
    }

    fn lookup(&self, id: &str, pos: Option<&SourcePos>) -> Result<usize, LoadError> {
        let mut id = id.to_string();
        for _ in 0..64 {
            match self.ids.get(&id) {
                Some((IdTarget::Node(i), _)) => return Ok(*i),
                Some((IdTarget::Alias(t), _)) => id = t.clone(),
                Some((IdTarget::Pending, _)) | None => break,
            }
        }
        Err(LoadError::new(pos.cloned(), format!("reference to unknown id \"{id}\"")))
    }

    fn build(
        &mut self,
        idx: usize,
        via: Option<&SourcePos>,
        built: &mut Vec<Option<Arc<PluginNode>>>,
        visiting: &mut Vec<bool>,
    ) -> Result<Arc<PluginNode>, LoadError> {
        if let Some(n) = &built[idx] {
            return Ok(n.clone());
        }
        if visiting[idx] {
            let id = self.nodes[idx].as_ref().and_then(|n| n.id.clone()).unwrap_or_default();
            return Err(LoadError::new(
                via.cloned(),
                format!("reference cycle: \"{id}\" (directly or indirectly) contains itself"),
            ));
        }
        visiting[idx] = true;
        let raw_children =
            std::mem::take(&mut self.nodes[idx].as_mut().expect("node is built once").children);
        let mut children = Vec::with_capacity(raw_children.len());
        for rc in raw_children {
            match rc {
                RawChild::Nested(i) => {
                    let node = self.build(i, None, built, visiting)?;
                    children.push(Child {
                        name: node.name.clone(),
                        node,
                        ref_pos: None,
                        used: AtomicBool::new(false),
                    });
                }
                RawChild::Ref { id, name, pos } => {
                    let target = self.lookup(&id, Some(&pos))?;
                    let node = self.build(target, Some(&pos), built, visiting)?;
                    children.push(Child {
                        name,
                        node,
                        ref_pos: Some(pos),
                        used: AtomicBool::new(false),
                    });
                }
            }
        }
        let raw = self.nodes[idx].take().expect("node is built once");
        let node = Arc::new(PluginNode {
            tag: raw.tag,
            plugin_type: raw.plugin_type,
            id: raw.id,
            name: raw.name,
            pos: raw.pos,
            props: raw.props,
            children,
        });
        visiting[idx] = false;
        built[idx] = Some(node.clone());
        Ok(node)
    }
}

/// Old scenes: `uoffset`/`voffset`/`uscale`/`vscale` floats become a `to_uv` transform.
fn upgrade_uv(b: &mut Builder) -> Result<(), LoadError> {
    let mut get = |n: &str| match b.props.remove(n) {
        Some((PropertyValue::Float(f), pos)) => Some((f as f32, pos)),
        Some((other, pos)) => {
            // Not a float: put it back untouched.
            let _ = b.props.insert(n, other, pos);
            None
        }
        None => None,
    };
    let (uo, vo, us, vs) = (get("uoffset"), get("voffset"), get("uscale"), get("vscale"));
    let pos = match [&uo, &vo, &us, &vs].into_iter().flatten().next() {
        Some((_, p)) => p.clone(),
        None => return Ok(()),
    };
    let off = Vec3::new(uo.map_or(0.0, |x| x.0), vo.map_or(0.0, |x| x.0), 0.0);
    let scale = Vec3::new(us.map_or(1.0, |x| x.0), vs.map_or(1.0, |x| x.0), 1.0);
    let mut t = Transform::IDENTITY;
    if off != Vec3::ZERO {
        t = t.then(&Transform::translate(off));
    }
    if scale != Vec3::ONE {
        let s = Transform::scale(scale)
            .map_err(|_| LoadError::at(&pos, "uscale/vscale of zero makes to_uv singular"))?;
        t = t.then(&s);
    }
    b.props.insert("to_uv", PropertyValue::Transform(t), pos)
}
