//! Shapes in the scene: each shape's geometry (`geometry`) with its BSDF, area emitter and
//! nested sensors; `shapegroup`, `instance` and `merge`.
//!
//! `shapegroup` (scene level, with an `id`) holds shapes that are not rendered themselves;
//! each `instance` (a `<ref>` to a group and a `to_world`) places all of them, the instance's
//! `to_world` applied after each shape's own, as in Mitsuba 3. Shapes in a group keep their
//! BSDFs (one BSDF object shared by every copy); emitters, sensors, nested groups and instances
//! in a group are refused, as Mitsuba refuses them. As in Mitsuba, a group's geometry is built
//! once, with its own BVH, the first time an instance refers to it, and each instance is one
//! entry of the scene's BVH (`steradian::accel`'s two-level hierarchy): memory grows with the
//! groups' geometry, not with the number of instances; a group no instance uses costs nothing.
//!
//! `merge` holds shapes and takes no parameters (Mitsuba refuses a `to_world` or any other
//! property on it). Mitsuba 3 joins its meshes that share a BSDF, media, emitter and sensor into
//! one mesh so that its ray tracer sees fewer objects, and passes every other child through;
//! meshes with emitters are never joined (each has an emitter of its own). The image is that of
//! the children listed in its place, which is what steradian renders: its BVH is over
//! primitives, not objects, so joining meshes would gain nothing. A `merge` may sit in the
//! scene, in a `shapegroup` or in another `merge`. Where steradian differs on purpose: the
//! `shape_index` AOV counts the children one by one, where Mitsuba counts each joined mesh
//! once; a BSDF or other non-shape object directly inside a `merge` is an error (Mitsuba
//! ignores it).

use std::sync::Arc;

use steradian::scene::{InstanceDescription, ShapeBinding, SurfaceEmitter};
use steradian::shape::{self, Shape};

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
        "merge" => merged(node)?.into_iter().try_for_each(|n| build(b, n)),
        _ => build_placed(b, node),
    }
}

/// The shapes a `merge` holds, nested merges flattened, in document order.
fn merged(merge: &PluginNode) -> Result<Vec<&Arc<PluginNode>>, LoadError> {
    let mut shapes = Vec::new();
    for c in &merge.children {
        c.mark_used();
        let n = &c.node;
        if n.tag != ObjectTag::Shape {
            return Err(LoadError::at(
                c.pos(),
                format!("{}: holds shapes only, not {}", merge.desc(), n.desc()),
            ));
        }
        match n.plugin_type.as_str() {
            "merge" => shapes.extend(merged(n)?),
            "shapegroup" => {
                return Err(LoadError::at(
                    c.pos(),
                    format!(
                        "{}: a shapegroup belongs at the scene level, not in a merge",
                        merge.desc()
                    ),
                ))
            }
            _ => shapes.push(n),
        }
    }
    merge.check_all_used()?;
    Ok(shapes)
}

/// A `shapegroup`'s shapes (those of a `merge` in it included), after checking what Mitsuba
/// refuses in one.
fn group_members(group: &PluginNode) -> Result<Vec<&Arc<PluginNode>>, LoadError> {
    let err = |pos: &crate::source::SourcePos, what: String| {
        Err(LoadError::at(pos, format!("{}: {what}", group.desc())))
    };
    let mut members = Vec::new();
    for c in &group.children {
        c.mark_used();
        if c.node.tag != ObjectTag::Shape {
            return err(c.pos(), format!("holds shapes only, not {}", c.node.desc()));
        }
        let shapes = if c.node.plugin_type == "merge" { merged(&c.node)? } else { vec![&c.node] };
        for n in shapes {
            if matches!(n.plugin_type.as_str(), "shapegroup" | "instance") {
                return err(&n.pos, format!("cannot hold {} (no nested groups)", n.desc()));
            }
            if let Some(e) = n
                .children
                .iter()
                .find(|e| matches!(e.node.tag, ObjectTag::Emitter | ObjectTag::Sensor))
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
    let group = group_index(b, &group)?;
    b.desc.instances.push(InstanceDescription { group, to_world });
    Ok(())
}

/// The index of `group` in the scene's groups, its members built the first time.
fn group_index(b: &mut Builder, group: &Arc<PluginNode>) -> Result<u32, LoadError> {
    let key = Arc::as_ptr(group);
    if let Some(&g) = b.group_cache.get(&key) {
        return Ok(g);
    }
    let mut members = Vec::new();
    for member in group_members(group)? {
        members.push(build_shape_node(b, member)?);
    }
    b.desc.groups.push(members);
    let g = (b.desc.groups.len() - 1) as u32;
    b.group_cache.insert(key, g);
    Ok(g)
}

/// Builds a scene-level shape node and adds it (with its BSDF and area light) to the scene.
fn build_placed(b: &mut Builder, node: &Arc<PluginNode>) -> Result<(), LoadError> {
    let shape = build_shape_node(b, node)?;
    b.desc.shapes.push(shape);
    Ok(())
}

/// A shape node's shape and binding (its BSDF, its area light, added to the scene's lists;
/// its nested sensors are added to the scene's), for the next entry of the scene's shapes
/// or, without emitters and sensors, of a group's.
fn build_shape_node(
    b: &mut Builder,
    node: &Arc<PluginNode>,
) -> Result<(Shape, ShapeBinding), LoadError> {
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let flip_normals = p.get_bool("flip_normals")?.unwrap_or(shape::DEFAULT_FLIP_NORMALS);
    let build_shape = lookup(SHAPES, node)?;
    b.mesh_attributes.replace(AttributeSource::None);
    let shape = build_shape(&ShapeArgs { b, node, to_world, flip: flip_normals })?;
    // the mesh's attributes serve its BSDF only: Mitsuba 3.9.1 loads an area light that reads
    // one, but its light samples then disagree with its BSDF samples (`direct`, emitter
    // samples only against BSDF samples only: image means 1.39 against 1.70 in red) and its
    // scalar variants crash, so steradian refuses it
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
    // Mitsuba samples no points on curves, SDF grids and ellipsoid clouds: they can neither
    // emit nor carry a sensor
    if let (
        Shape::LinearCurve(_)
        | Shape::BSplineCurve(_)
        | Shape::SdfGrid(_)
        | Shape::Ellipsoids(_)
        | Shape::EllipsoidShells(_),
        Some(c),
    ) = (
        &shape,
        node.children.iter().find(|c| matches!(c.node.tag, ObjectTag::Emitter | ObjectTag::Sensor)),
    ) {
        return Err(LoadError::at(
            c.pos(),
            format!(
                "{}: {} on a shape of type '{}' is not supported (points on it cannot be sampled)",
                node.desc(),
                c.node.desc(),
                node.plugin_type
            ),
        ));
    }
    let shape_index = b.desc.shapes.len() as u32;
    if let Some(e) = emitter_nodes.first() {
        if let Some(first) = b.attached_emitters.insert(Arc::as_ptr(&e.node), e.pos().clone()) {
            return Err(LoadError::at(
                e.pos(),
                format!(
                    "{}: {} is already attached to the shape at {first}; an emitter can be attached to one shape only",
                    node.desc(),
                    e.node.desc()
                ),
            ));
        }
    }
    // (the emitter's index, whether the shape carries one: `directionalarea` adds none)
    let (emitter, emitting) = match emitter_nodes.first() {
        Some(e) => match emitters::build_area(b, &e.node, shape_index, &shape)? {
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
    let [interior, exterior] =
        <[Option<u32>; 2]>::try_from(b.media_of(node, &["interior", "exterior"])?)
            .expect("two slots");
    for c in node.children_of(ObjectTag::Sensor) {
        b.sensor_medium(&c.node)?;
        let sensor = super::sensors::build(b, &c.node, Some(shape_index))?;
        b.desc.sensors.push(sensor);
    }
    node.check_all_used()?;
    let id = node.id.clone().unwrap_or_default();
    let surface_emitter = if emitting { SurfaceEmitter::Present } else { SurfaceEmitter::Absent };
    Ok((shape, ShapeBinding { bsdf, emitter, surface_emitter, id, interior, exterior }))
}
