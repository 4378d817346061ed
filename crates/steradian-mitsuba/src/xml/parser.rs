//! The XML parser proper: documents, `<include>`s, elements and objects, read into a
//! [`RawTree`] that [`link`](super::link) then turns into the shared scene tree.
//!
//! Follows Mitsuba 3's `src/core/xml.cpp` (see the crate docs for the rules). Each element's
//! attributes get their `$name`s substituted ([`Params`]) before anything reads them;
//! property elements are parsed by [`values`](super::values), transform operations by
//! [`transform`](super::transform).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use steradian::geometry::Transform;

use super::attrs::{Attr, Attrs};
use super::link::{RawChild, RawNode, RawTree};
use super::params::Params;
use super::{transform, typed_spectrum, values};
use crate::error::{LoadError, LoadWarning};
use crate::file_resolver::FileResolver;
use crate::properties::{Properties, PropertyValue};
use crate::source::SourcePos;
use crate::tree::{describe, ObjectTag, SceneNode};
use crate::upgrade;

/// Nesting deeper than this is refused (protects the stack).
const MAX_DEPTH: usize = 128;
/// Mitsuba's `MI_XML_INCLUDE_MAX_RECURSION`.
const MAX_INCLUDE_DEPTH: usize = 15;

/// Parses the scene file at `path`. `defines` are `-D name=value` parameters: they override
/// `<default>`s, and one the scene never uses as `$name` is an error (as in Mitsuba 3).
pub fn parse_file(path: &Path, defines: &[(String, String)]) -> Result<SceneNode, LoadError> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        LoadError::new(None, format!("cannot read scene file \"{}\": {e}", path.display()))
    })?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut p = Parser::new(defines, &dir);
    p.resolver.record(path);
    p.include_stack.push(path.canonicalize().unwrap_or_else(|_| path.to_path_buf()));
    p.parse_root(Arc::new(path.to_path_buf()), &text, dir)
}

/// Parses a scene from a string (positions name the file `<string>`); `base_dir` stands for
/// the scene file's folder in the file search ([`FileResolver`]).
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
    let mut p = Parser::new(defines, base_dir);
    p.parse_root(Arc::new(name.to_path_buf()), xml, base_dir.to_path_buf())
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
    params: Params,
    tree: RawTree,
    /// The search folders: the scene's folder and the `<path>`s read so far.
    resolver: FileResolver,
    warnings: Vec<LoadWarning>,
    /// The files being read, outermost first (to refuse include cycles).
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

/// The text with every `-` inside a comment made a space where some comment holds `--` or
/// ends in `-`: XML forbids both, Mitsuba's parser (pugixml) accepts them, and real scenes
/// have them (Sionna's licence headers: `<!--` / `-- SPDX-License-Identifier` / `-->`). A
/// comment ends at the first `-->`, as in pugixml. Lengths and line breaks are kept, so
/// error positions stay those of the file.
fn lenient_comments(text: &str) -> std::borrow::Cow<'_, str> {
    let mut bodies = Vec::new();
    let mut at = 0;
    while let Some(open) = text[at..].find("<!--") {
        let start = at + open + 4;
        let Some(len) = text[start..].find("-->") else { break };
        let body = &text[start..start + len];
        if body.contains("--") || body.ends_with('-') {
            bodies.push(start..start + len);
        }
        at = start + len + 3;
    }
    if bodies.is_empty() {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = text.as_bytes().to_vec();
    for range in bodies {
        out[range].iter_mut().filter(|b| **b == b'-').for_each(|b| *b = b' ');
    }
    // only ASCII '-' bytes were replaced by ASCII spaces: still UTF-8
    match String::from_utf8(out) {
        Ok(s) => std::borrow::Cow::Owned(s),
        Err(_) => std::borrow::Cow::Borrowed(text),
    }
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
    fn new(defines: &[(String, String)], scene_dir: &Path) -> Self {
        Parser {
            params: Params::new(defines),
            tree: RawTree::default(),
            resolver: FileResolver::new(scene_dir),
            warnings: Vec::new(),
            include_stack: Vec::new(),
        }
    }

    /// Attributes of `el` with `$name` parameters substituted (longest names first, as
    /// Mitsuba does); a `$` left over is an undefined parameter.
    fn attrs(&mut self, src: &Src, el: roxmltree::Node, elem: &str) -> Result<Attrs, LoadError> {
        let mut list = Vec::new();
        for a in el.attributes() {
            let pos = src.pos(a.range().start);
            let value = self.params.substitute(a.value(), a.name(), &pos)?;
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
        let text = lenient_comments(text);
        let doc = parse_doc(&path, &text)?;
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
            self.tree.reserve(id.clone(), attrs.pos.clone());
        }
        self.parse_children(&src, root, &mut b, 1)?;
        let idx = self.push(b, id, None, attrs.pos.clone());
        self.params.check_defines_used(&attrs)?;
        let (resolver, warnings) =
            (std::mem::take(&mut self.resolver), std::mem::take(&mut self.warnings));
        std::mem::take(&mut self.tree).link(idx, resolver, warnings)
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
        self.tree.push(RawNode {
            tag: b.tag,
            plugin_type: b.plugin_type,
            id,
            name,
            pos,
            props: b.props,
            children: b.children,
        })
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
            upgrade::fold_uv(&mut b.props)?;
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

    /// The slot an object or `<ref>` with an optional `name` takes in `parent`, claimed.
    fn optional_slot(
        &self,
        src: &Src,
        attrs: &Attrs,
        parent: &mut Builder,
    ) -> Result<Option<String>, LoadError> {
        let Some(a) = attrs.get("name") else { return Ok(None) };
        let name = self.slot_name(src, a, parent)?;
        parent.claim(&name, &attrs.pos)?;
        Ok(Some(name))
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
            "spectrum"
                if attrs.get("id").is_none()
                    && attrs.get("type").is_some_and(|t| {
                        typed_spectrum::TYPED_SPECTRA.contains(&t.value.as_str())
                    }) =>
            {
                self.parse_typed_spectrum(src, el, &attrs, parent, depth)
            }
            "spectrum" => self.parse_object(src, el, &attrs, ObjectTag::Spectrum, parent, depth),
            "transform" => self.parse_transform(src, el, &attrs, parent),
            "translate" | "rotate" | "scale" | "matrix" | "lookat" => Err(attrs
                .error(format!("transform operation <{tag}> can only occur inside <transform>"))),
            "ref" => {
                self.no_content(src, el, "<ref>")?;
                attrs.allow(&["id", "name"])?;
                let id = attrs.require("id")?.value.clone();
                let name = self.optional_slot(src, &attrs, parent)?;
                let id = if src.upgrade { upgrade::upgrade_id(&id) } else { id };
                parent.children.push(RawChild::Ref { id, name, pos: attrs.pos.clone() });
                Ok(())
            }
            "default" => {
                self.no_content(src, el, "<default>")?;
                self.params.default(&attrs)
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
                if let Some(prev) = self.tree.declared_at(&alias) {
                    return Err(attrs.error(format!(
                        "duplicate id \"{alias}\" (first defined at {})",
                        prev.line_col()
                    )));
                }
                if self.tree.declared_at(&target).is_none() {
                    return Err(attrs.error(format!("<alias> refers to unknown id \"{target}\"")));
                }
                self.tree.alias(alias, target, attrs.pos.clone());
                Ok(())
            }
            "path" => {
                self.no_content(src, el, "<path>")?;
                self.parse_path(src, &attrs, parent)
            }
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
        let name = self.optional_slot(src, attrs, parent)?;
        if let Some(id) = &id {
            if let Some(prev) = self.tree.declared_at(id) {
                return Err(attrs.error(format!(
                    "<{}> has duplicate id \"{id}\" (first defined at {})",
                    tag.name(),
                    prev.line_col()
                )));
            }
            self.tree.reserve(id.clone(), attrs.pos.clone());
        }
        let mut b = Builder::new(tag, &plugin_type, id.as_deref());
        self.parse_children(src, el, &mut b, depth + 1)?;
        let idx = self.push(b, id, name, attrs.pos.clone());
        parent.children.push(RawChild::Nested(idx));
        Ok(())
    }

    /// `<spectrum type="d65" name="…">` and the other spectrum plugins
    /// (`typed_spectrum.rs`): a value of the parent's property `name`.
    fn parse_typed_spectrum(
        &mut self,
        src: &Src,
        el: roxmltree::Node,
        attrs: &Attrs,
        parent: &mut Builder,
        depth: usize,
    ) -> Result<(), LoadError> {
        attrs.allow(&["type", "name"])?;
        let ty = attrs.require("type")?.value.clone();
        let name = self.slot_name(src, attrs.require("name")?, parent)?;
        parent.claim(&name, &attrs.pos)?;
        let mut b = Builder::new(ObjectTag::Spectrum, &ty, None);
        self.parse_children(src, el, &mut b, depth + 1)?;
        if !b.children.is_empty() {
            return Err(
                attrs.error(format!("<spectrum type=\"{ty}\"> holds only properties, not objects"))
            );
        }
        let within_emitter = parent.tag == ObjectTag::Emitter;
        let value =
            typed_spectrum::typed_spectrum(&ty, &b.props, &attrs.pos, &name, within_emitter)?;
        parent.props.insert(name, PropertyValue::Spectrum(value), attrs.pos.clone())
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
        let path = self.resolver.resolve(fname, &src.dir);
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
        self.resolver.record(&path);
        let ipath = Arc::new(path.clone());
        let text = lenient_comments(&text);
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

    /// `<path value="folder"/>`: a search folder for the files named after it and for the
    /// plugins' files, searched before those already listed. Only at the scene's top level;
    /// a relative folder is taken from the declaring file's folder, else from the search
    /// folders; it must exist.
    fn parse_path(&mut self, src: &Src, attrs: &Attrs, parent: &Builder) -> Result<(), LoadError> {
        attrs.allow(&["value"])?;
        let value = &attrs.require("value")?.value;
        if parent.tag != ObjectTag::Scene {
            return Err(attrs.error(format!(
                "<path> can only be a child of the root <scene>, not of {}",
                parent.desc
            )));
        }
        let given = Path::new(value);
        let mut dir = src.dir.join(given);
        if !given.is_absolute() && !dir.exists() {
            dir = self.resolver.resolve(value, &src.dir);
        }
        if !dir.is_dir() {
            return Err(attrs.error(format!("<path>: folder \"{}\" not found", dir.display())));
        }
        self.resolver.prepend(dir);
        Ok(())
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
            let t = transform::parse_op(&op, &oattrs, &mut self.warnings)?;
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
        let resolve = |file: &str| {
            let path = self.resolver.resolve(file, &src.dir);
            self.resolver.record(&path);
            path
        };
        let value = values::parse_value(attrs, &name, parent.tag == ObjectTag::Emitter, &resolve)?;
        parent.props.insert(name, value, attrs.pos.clone())
    }
}
