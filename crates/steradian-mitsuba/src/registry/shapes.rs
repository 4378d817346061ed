//! Shapes in the scene: each shape's geometry (`geometry`) with its BSDF, area emitter and
//! nested sensors; `shapegroup` and `instance`.
//!
//! `shapegroup` (scene level, with an `id`) holds shapes that are not rendered themselves;
//! each `instance` (a `<ref>` to a group and a `to_world`) places all of them, the instance's
//! `to_world` applied after each shape's own, as in Mitsuba 3. Shapes in a group keep their
//! BSDFs (one BSDF object shared by every copy); emitters, sensors, nested groups and instances
//! in a group are refused, as Mitsuba refuses them. steradian differs in how it stores them:
//! each instance is a transformed copy of the group's geometry in the one scene BVH (Mitsuba
//! keeps one copy and a two-level BVH), so memory grows with the number of instances; images
//! are the same.

use std::sync::Arc;

use steradian::geometry::Transform;
use steradian::scene::ShapeBinding;
use steradian::shape;

use super::geometry::{ShapeArgs, SHAPES};
use super::{emitters, lookup, AttributeSource, Builder, MeshAttributes};
use crate::error::LoadError;
use crate::tree::{ObjectTag, PluginNode};

/// Builds a scene-level shape node and adds it (with its BSDF and area light) to the scene;
/// a `shapegroup` is checked and kept for its instances, an `instance` adds a copy of its
/// group's shapes.
pub(crate) fn build(b: &mut Builder, node: &Arc<PluginNode>) -> Result<(), LoadError> {
    match node.plugin_type.as_str() {
        "shapegroup" => check_group(node),
        "instance" => instance(b, node),
        _ => build_placed(b, node, None),
    }
}

/// A `shapegroup`'s shapes, after checking what Mitsuba refuses in one.
fn group_members(group: &PluginNode) -> Result<Vec<&Arc<PluginNode>>, LoadError> {
    let err = |pos: &crate::source::SourcePos, what: String| {
        Err(LoadError::at(pos, format!("{}: {what}", group.desc())))
    };
    let mut members = Vec::new();
    for c in &group.children {
        c.mark_used();
        let n = &c.node;
        if n.tag != ObjectTag::Shape {
            return err(c.pos(), format!("holds shapes only, not {}", n.desc()));
        }
        if matches!(n.plugin_type.as_str(), "shapegroup" | "instance") {
            return err(c.pos(), format!("cannot hold {} (no nested groups)", n.desc()));
        }
        if let Some(e) =
            n.children.iter().find(|e| matches!(e.node.tag, ObjectTag::Emitter | ObjectTag::Sensor))
        {
            return err(
                e.pos(),
                format!(
                    "{} in a shape group is not supported (Mitsuba 3 refuses emitters and sensors in instanced shapes)",
                    e.node.desc()
                ),
            );
        }
        members.push(n);
    }
    group.check_all_used()?;
    Ok(members)
}

fn check_group(group: &PluginNode) -> Result<(), LoadError> {
    if group.id.is_none() {
        return Err(LoadError::at(
            &group.pos,
            format!("{}: a shape group needs an id for its instances to refer to", group.desc()),
        ));
    }
    group_members(group).map(|_| ())
}

/// `instance`: the group it refers to, placed by its `to_world`.
fn instance(b: &mut Builder, node: &Arc<PluginNode>) -> Result<(), LoadError> {
    let to_world = node.props.get_transform("to_world")?.unwrap_or_default();
    let groups = node.children_of(ObjectTag::Shape);
    let group = match groups.as_slice() {
        [g] if g.node.plugin_type == "shapegroup" => g.node.clone(),
        [g] => {
            return Err(LoadError::at(
                g.pos(),
                format!("{}: refers to {}, not a shapegroup", node.desc(), g.node.desc()),
            ))
        }
        _ => {
            return Err(LoadError::at(
                &node.pos,
                format!(
                    "{}: needs exactly one <ref> to a shapegroup, got {}",
                    node.desc(),
                    groups.len()
                ),
            ))
        }
    };
    node.check_all_used()?;
    for member in group_members(&group)? {
        build_placed(b, member, Some(&to_world))?;
    }
    Ok(())
}

/// Builds a shape node, placed by `instance_to_world` after its own `to_world` when it is a
/// member of an instanced group, and adds it (with its BSDF and area light) to the scene.
fn build_placed(
    b: &mut Builder,
    node: &Arc<PluginNode>,
    instance_to_world: Option<&Transform>,
) -> Result<(), LoadError> {
    let p = &node.props;
    let own = p.get_transform("to_world")?.unwrap_or_default();
    let to_world = match instance_to_world {
        Some(t) => own.then(t),
        None => own,
    };
    let flip_normals = p.get_bool("flip_normals")?.unwrap_or(shape::DEFAULT_FLIP_NORMALS);
    let build_shape = lookup(SHAPES, node)?;
    b.mesh_attributes.replace(AttributeSource::None);
    let shape = build_shape(&ShapeArgs { b, node, to_world, flip: flip_normals })?;
    // the mesh's attributes serve its BSDF only (Mitsuba's emitters cannot read them)
    let attributes = match b.mesh_attributes.replace(AttributeSource::None) {
        // shapes other than `ply` have no attributes
        AttributeSource::None => {
            AttributeSource::Mesh(MeshAttributes { indices: Arc::from([]), list: Vec::new() })
        }
        source => source,
    };
    if !shape.surface_area().is_finite() {
        return Err(LoadError::at(
            &node.pos,
            format!("{}: the shape's surface area is not finite", node.desc()),
        ));
    }

    let bsdfs = node.children_of(ObjectTag::Bsdf);
    let emitter_nodes = node.children_of(ObjectTag::Emitter);
    if bsdfs.len() > 1 {
        return Err(LoadError::at(
            bsdfs[1].pos(),
            format!("{} has more than one BSDF", node.desc()),
        ));
    }
    if emitter_nodes.len() > 1 {
        return Err(LoadError::at(
            emitter_nodes[1].pos(),
            format!("{} has more than one emitter", node.desc()),
        ));
    }
    let shape_index = b.desc.shapes.len() as u32;
    // (the emitter's index, whether the shape carries one: `directionalarea` adds none)
    let (emitter, emitting) = match emitter_nodes.first() {
        Some(e) => match emitters::build_area(b, &e.node, shape_index)? {
            Some(light) => {
                b.desc.emitters.push(light);
                (Some((b.desc.emitters.len() - 1) as u32), true)
            }
            None => (None, true),
        },
        None => (None, false),
    };
    b.mesh_attributes.replace(attributes);
    let bsdf = match bsdfs.first() {
        Some(c) => b.bsdf_index(&c.node),
        None => Ok(b.implicit_bsdf(emitting)),
    };
    b.mesh_attributes.replace(AttributeSource::None);
    let bsdf = bsdf?;
    for c in node.children_of(ObjectTag::Sensor) {
        let sensor = super::sensors::build(b, &c.node, Some(shape_index))?;
        b.desc.sensors.push(sensor);
    }
    node.check_all_used()?;
    b.desc
        .shapes
        .push((shape, ShapeBinding { bsdf, emitter, id: node.id.clone().unwrap_or_default() }));
    Ok(())
}
