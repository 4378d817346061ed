//! Ids and references: the objects read so far (by index, with their `<ref>`s unresolved),
//! and linking them into the shared tree once the whole scene has been read.
//!
//! References may point forwards or backwards, as in Mitsuba, which links after parsing; an
//! object referenced several times becomes one shared node. An unknown id is an error at its
//! `<ref>`, and so is a reference cycle (an object that contains itself).

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use crate::error::{LoadError, LoadWarning};
use crate::file_resolver::FileResolver;
use crate::properties::Properties;
use crate::source::SourcePos;
use crate::tree::{Child, ObjectTag, PluginNode, SceneNode};

/// What an id stands for.
#[derive(Clone)]
enum IdTarget {
    /// The object is still being read.
    Pending,
    Node(usize),
    /// `<alias id="target" as="name">`.
    Alias(String),
}

/// An object as read, before its references are resolved.
pub(super) struct RawNode {
    pub tag: ObjectTag,
    pub plugin_type: String,
    pub id: Option<String>,
    pub name: Option<String>,
    pub pos: SourcePos,
    pub props: Properties,
    pub children: Vec<RawChild>,
}

/// A child object as read: nested (by index) or a `<ref>` still to resolve.
pub(super) enum RawChild {
    Nested(usize),
    Ref { id: String, name: Option<String>, pos: SourcePos },
}

/// Every object read so far, and every id.
#[derive(Default)]
pub(super) struct RawTree {
    nodes: Vec<Option<RawNode>>,
    ids: HashMap<String, (IdTarget, SourcePos)>,
}

impl RawTree {
    /// Where `id` was first declared, if it was.
    pub fn declared_at(&self, id: &str) -> Option<&SourcePos> {
        self.ids.get(id).map(|(_, pos)| pos)
    }

    /// Declares `id` for the object whose content is being read (at `pos`).
    pub fn reserve(&mut self, id: String, pos: SourcePos) {
        self.ids.insert(id, (IdTarget::Pending, pos));
    }

    /// Declares `alias` as another name of the object `target`.
    pub fn alias(&mut self, alias: String, target: String, pos: SourcePos) {
        self.ids.insert(alias, (IdTarget::Alias(target), pos));
    }

    /// Adds an object that has been read completely; its id (if any) now names it.
    pub fn push(&mut self, node: RawNode) -> usize {
        let idx = self.nodes.len();
        if let Some(id) = &node.id {
            self.ids.insert(id.clone(), (IdTarget::Node(idx), node.pos.clone()));
        }
        self.nodes.push(Some(node));
        idx
    }

    /// Links references and builds the shared tree under object `root`.
    pub fn link(
        mut self,
        root: usize,
        resolver: FileResolver,
        warnings: Vec<LoadWarning>,
    ) -> Result<SceneNode, LoadError> {
        let mut built: Vec<Option<Arc<PluginNode>>> = vec![None; self.nodes.len()];
        let mut visiting = vec![false; self.nodes.len()];
        let root = self.build(root, None, &mut built, &mut visiting)?;
        let mut ids = BTreeMap::new();
        for id in self.ids.keys() {
            if let Ok(idx) = self.lookup(id, None) {
                // Objects that nothing reached (impossible: all hang off the root) are skipped.
                if let Some(n) = &built[idx] {
                    ids.insert(id.clone(), n.clone());
                }
            }
        }
        Ok(SceneNode { root, ids, resolver, warnings })
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
                    children.push(Child::new(node.name.clone(), node, None));
                }
                RawChild::Ref { id, name, pos } => {
                    let target = self.lookup(&id, Some(&pos))?;
                    let node = self.build(target, Some(&pos), built, visiting)?;
                    children.push(Child::new(name, node, Some(pos)));
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
