//! Shape plugins: `obj`, `ply`, `serialized`, `rectangle`, `disk`, `cube`, `sphere`, `cylinder`, with
//! their BSDF and area emitter; `shapegroup` and `instance`.
//!
//! `shapegroup` (scene level, with an `id`) holds shapes that are not rendered themselves;
//! each `instance` (a `<ref>` to a group and a `to_world`) places all of them, the instance's
//! `to_world` applied after each shape's own, as in Mitsuba 3. Shapes in a group keep their
//! BSDFs (one BSDF object shared by every copy); emitters, sensors, nested groups and instances
//! in a group are refused, as Mitsuba refuses them. steradian differs in how it stores them:
//! each instance is a transformed copy of the group's geometry in the one scene BVH (Mitsuba
//! keeps one copy and a two-level BVH), so memory grows with the number of instances; images
//! are the same.

use std::path::PathBuf;
use std::sync::Arc;

use steradian::geometry::Transform;
use steradian::scene::ShapeBinding;
use steradian::shape::{
    self, read_obj, read_ply, Cylinder, Disk, Mesh, MeshData, Rectangle, Shape, ShapeError, Sphere,
    DEFAULT_FLIP_TEX_COORDS,
};

use super::{emitters, lookup, Builder, Plugins};
use crate::error::LoadError;
use crate::tree::{ObjectTag, PluginNode};

/// What a shape builder reads: the scene being built (for file paths), the shape's node, and
/// the `to_world` and `flip_normals` every shape has.
pub(super) struct ShapeArgs<'a> {
    b: &'a Builder,
    node: &'a PluginNode,
    to_world: Transform,
    flip: bool,
}

/// Builds one shape from its node.
type BuildShape = fn(&ShapeArgs) -> Result<Shape, LoadError>;

/// Every shape plugin, by Mitsuba `type`.
pub(super) const SHAPES: &Plugins<BuildShape> = &[
    ("obj", obj),
    ("ply", ply),
    ("serialized", serialized_shape),
    ("rectangle", rectangle),
    ("disk", disk),
    ("cube", cube),
    ("sphere", sphere),
    ("cylinder", cylinder),
    ("shapegroup", group_placeholder),
    ("instance", group_placeholder),
];

/// `shapegroup` and `instance` are handled by [`build`] before the table is consulted; the
/// table names them so that unknown-type errors and the README's list include them.
fn group_placeholder(s: &ShapeArgs) -> Result<Shape, LoadError> {
    Err(LoadError::at(&s.node.pos, format!("{} cannot be nested in another object", s.node.desc())))
}

/// A shape error at the node.
fn shape_err(node: &PluginNode) -> impl Fn(ShapeError) -> LoadError + '_ {
    move |e| LoadError::at(&node.pos, format!("{}: {e}", node.desc()))
}

/// An error reading a mesh file, placed at its `filename`.
fn mesh_err(node: &PluginNode) -> impl Fn(ShapeError) -> LoadError + '_ {
    move |e| {
        LoadError::at(
            node.props.position("filename").unwrap_or(&node.pos),
            format!("{}: {e}", node.desc()),
        )
    }
}

/// The mesh file named by the required string property `filename`.
fn mesh_file(s: &ShapeArgs) -> Result<PathBuf, LoadError> {
    let node = s.node;
    let file = node
        .props
        .get_string("filename")?
        .ok_or_else(|| LoadError::at(&node.pos, format!("{}: missing 'filename'", node.desc())))?;
    Ok(s.b.resolve_path(node, &file))
}

/// `face_normals` of `obj` and `ply`.
fn face_normals(node: &PluginNode) -> Result<bool, LoadError> {
    Ok(node.props.get_bool("face_normals")?.unwrap_or(Mesh::DEFAULT_FACE_NORMALS))
}

/// The mesh of a file's `data` (or the error reading it), errors placed at `filename`.
fn mesh(
    s: &ShapeArgs,
    data: Result<MeshData, ShapeError>,
    face_normals: bool,
) -> Result<Shape, LoadError> {
    let data = data.map_err(mesh_err(s.node))?;
    let mesh =
        Mesh::from_data(data, &s.to_world, s.flip, face_normals).map_err(mesh_err(s.node))?;
    Ok(Shape::Mesh(mesh))
}

fn obj(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let path = mesh_file(s)?;
    let face_normals = face_normals(s.node)?;
    let flip_tex = s.node.props.get_bool("flip_tex_coords")?.unwrap_or(DEFAULT_FLIP_TEX_COORDS);
    mesh(s, read_obj(&path, flip_tex), face_normals)
}

fn ply(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let path = mesh_file(s)?;
    let face_normals = face_normals(s.node)?;
    mesh(s, read_ply(&path), face_normals)
}

fn rectangle(s: &ShapeArgs) -> Result<Shape, LoadError> {
    Ok(Shape::Rectangle(Rectangle::new(&s.to_world, s.flip)))
}

fn disk(s: &ShapeArgs) -> Result<Shape, LoadError> {
    Ok(Shape::Disk(Disk::new(&s.to_world, s.flip)))
}

fn cube(s: &ShapeArgs) -> Result<Shape, LoadError> {
    Ok(Shape::Mesh(shape::cube(&s.to_world, s.flip)))
}

fn sphere(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let (p, node) = (&s.node.props, s.node);
    let center = p.get_point("center")?.unwrap_or(Sphere::DEFAULT_CENTER);
    let radius = p.get_float("radius")?.unwrap_or(Sphere::DEFAULT_RADIUS);
    if !(radius.is_finite() && radius != 0.0) {
        return Err(LoadError::at(
            p.position("radius").unwrap_or(&node.pos),
            format!("{}: radius must be non-zero and finite, got {radius}", node.desc()),
        ));
    }
    Ok(Shape::Sphere(Sphere::new(center, radius, &s.to_world, s.flip)))
}

fn cylinder(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let p = &s.node.props;
    let p0 = p.get_point("p0")?.unwrap_or(Cylinder::DEFAULT_P0);
    let p1 = p.get_point("p1")?.unwrap_or(Cylinder::DEFAULT_P1);
    let radius = p.get_float("radius")?.unwrap_or(Cylinder::DEFAULT_RADIUS);
    let cylinder = Cylinder::new(p0, p1, radius, &s.to_world, s.flip).map_err(shape_err(s.node))?;
    Ok(Shape::Cylinder(cylinder))
}

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

/// A shape's geometry alone, where it only marks out a region (a `distant` sensor's
/// `target`): a BSDF, emitter or sensor in it is an unused object, hence an error.
pub(crate) fn build_geometry(b: &Builder, node: &PluginNode) -> Result<Shape, LoadError> {
    if matches!(node.plugin_type.as_str(), "shapegroup" | "instance") {
        return Err(LoadError::at(&node.pos, format!("{} cannot be nested here", node.desc())));
    }
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let flip = p.get_bool("flip_normals")?.unwrap_or(shape::DEFAULT_FLIP_NORMALS);
    let shape = lookup(SHAPES, node)?(&ShapeArgs { b, node, to_world, flip })?;
    node.check_all_used()?;
    Ok(shape)
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
    let shape = build_shape(&ShapeArgs { b, node, to_world, flip: flip_normals })?;
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
    let bsdf = match bsdfs.first() {
        Some(c) => b.bsdf_index(&c.node)?,
        None => b.implicit_bsdf(emitting),
    };
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

/// `serialized`: one shape of a Mitsuba `.serialized` file (core: shape/serialized.rs).
fn serialized_shape(s: &ShapeArgs) -> Result<Shape, LoadError> {
    Ok(Shape::Mesh(serialized(s.b, s.node, &s.to_world, s.flip)?))
}

fn serialized(
    b: &Builder,
    node: &PluginNode,
    to_world: &steradian::geometry::Transform,
    flip_normals: bool,
) -> Result<Mesh, LoadError> {
    use steradian::shape::serialized::{
        read_serialized, DEFAULT_FACE_NORMALS, DEFAULT_SHAPE_INDEX,
    };
    let p = &node.props;
    let file = p
        .get_string("filename")?
        .ok_or_else(|| LoadError::at(&node.pos, format!("{}: missing 'filename'", node.desc())))?;
    let path = b.resolve_path(node, &file);
    let shape_index = match p.get_int("shape_index")? {
        None => DEFAULT_SHAPE_INDEX,
        Some(i) => u32::try_from(i).map_err(|_| {
            LoadError::at(
                p.position("shape_index").unwrap_or(&node.pos),
                format!(
                    "{}: shape_index must be a non-negative 32-bit integer, got {i}",
                    node.desc()
                ),
            )
        })?,
    };
    let face_normals = p.get_bool("face_normals")?.unwrap_or(DEFAULT_FACE_NORMALS);
    // Errors reading the file are placed at its `filename`.
    let file_err = |e: steradian::shape::ShapeError| {
        LoadError::at(p.position("filename").unwrap_or(&node.pos), format!("{}: {e}", node.desc()))
    };
    let shape = read_serialized(&path, shape_index).map_err(file_err)?;
    Mesh::from_data(shape.data, to_world, flip_normals, face_normals).map_err(file_err)
}
