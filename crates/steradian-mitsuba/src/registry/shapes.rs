//! Shape plugins: `obj`, `ply`, `rectangle`, `disk`, `cube`, `sphere`, `cylinder`, with
//! their BSDF and area emitter.

use std::path::PathBuf;
use std::sync::Arc;

use steradian::geometry::Transform;
use steradian::scene::ShapeBinding;
use steradian::shape::{
    self, read_obj, read_ply, Cylinder, Disk, Mesh, Rectangle, Shape, ShapeError, Sphere,
    DEFAULT_FLIP_TEX_COORDS,
};

use super::{emitters, lookup, Builder, Plugins};
use crate::error::LoadError;
use crate::tree::{ObjectTag, PluginNode};

/// Builds one shape from its node, given its `to_world` and `flip_normals`.
type BuildShape = fn(&Builder, &PluginNode, &Transform, bool) -> Result<Shape, LoadError>;

/// Every shape plugin, by Mitsuba `type`.
pub(super) const SHAPES: &Plugins<BuildShape> = &[
    ("obj", obj),
    ("ply", ply),
    ("rectangle", rectangle),
    ("disk", disk),
    ("cube", cube),
    ("sphere", sphere),
    ("cylinder", cylinder),
];

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

/// The mesh file named by the required string property `name`.
fn mesh_file(b: &Builder, node: &PluginNode, name: &str) -> Result<PathBuf, LoadError> {
    let file = node
        .props
        .get_string(name)?
        .ok_or_else(|| LoadError::at(&node.pos, format!("{}: missing '{name}'", node.desc())))?;
    Ok(b.resolve_path(node, &file))
}

fn obj(
    b: &Builder,
    node: &PluginNode,
    to_world: &Transform,
    flip: bool,
) -> Result<Shape, LoadError> {
    let p = &node.props;
    let path = mesh_file(b, node, "filename")?;
    let face_normals = p.get_bool("face_normals")?.unwrap_or(Mesh::DEFAULT_FACE_NORMALS);
    let flip_tex = p.get_bool("flip_tex_coords")?.unwrap_or(DEFAULT_FLIP_TEX_COORDS);
    let data = read_obj(&path, flip_tex).map_err(mesh_err(node))?;
    let mesh = Mesh::from_data(data, to_world, flip, face_normals).map_err(mesh_err(node))?;
    Ok(Shape::Mesh(mesh))
}

fn ply(
    b: &Builder,
    node: &PluginNode,
    to_world: &Transform,
    flip: bool,
) -> Result<Shape, LoadError> {
    let path = mesh_file(b, node, "filename")?;
    let face_normals = node.props.get_bool("face_normals")?.unwrap_or(Mesh::DEFAULT_FACE_NORMALS);
    let data = read_ply(&path).map_err(mesh_err(node))?;
    let mesh = Mesh::from_data(data, to_world, flip, face_normals).map_err(mesh_err(node))?;
    Ok(Shape::Mesh(mesh))
}

fn rectangle(
    _: &Builder,
    _: &PluginNode,
    to_world: &Transform,
    flip: bool,
) -> Result<Shape, LoadError> {
    Ok(Shape::Rectangle(Rectangle::new(to_world, flip)))
}

fn disk(_: &Builder, _: &PluginNode, to_world: &Transform, flip: bool) -> Result<Shape, LoadError> {
    Ok(Shape::Disk(Disk::new(to_world, flip)))
}

fn cube(_: &Builder, _: &PluginNode, to_world: &Transform, flip: bool) -> Result<Shape, LoadError> {
    Ok(Shape::Mesh(shape::cube(to_world, flip)))
}

fn sphere(
    _: &Builder,
    node: &PluginNode,
    to_world: &Transform,
    flip: bool,
) -> Result<Shape, LoadError> {
    let p = &node.props;
    let center = p.get_point("center")?.unwrap_or(Sphere::DEFAULT_CENTER);
    let radius = p.get_float("radius")?.unwrap_or(Sphere::DEFAULT_RADIUS);
    if !(radius.is_finite() && radius != 0.0) {
        return Err(LoadError::at(
            p.position("radius").unwrap_or(&node.pos),
            format!("{}: radius must be non-zero and finite, got {radius}", node.desc()),
        ));
    }
    Ok(Shape::Sphere(Sphere::new(center, radius, to_world, flip)))
}

fn cylinder(
    _: &Builder,
    node: &PluginNode,
    to_world: &Transform,
    flip: bool,
) -> Result<Shape, LoadError> {
    let p = &node.props;
    let p0 = p.get_point("p0")?.unwrap_or(Cylinder::DEFAULT_P0);
    let p1 = p.get_point("p1")?.unwrap_or(Cylinder::DEFAULT_P1);
    let radius = p.get_float("radius")?.unwrap_or(Cylinder::DEFAULT_RADIUS);
    let cylinder = Cylinder::new(p0, p1, radius, to_world, flip).map_err(shape_err(node))?;
    Ok(Shape::Cylinder(cylinder))
}

/// Builds a shape node and adds it (with its BSDF and area light) to the scene.
pub(crate) fn build(b: &mut Builder, node: &Arc<PluginNode>) -> Result<(), LoadError> {
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let flip_normals = p.get_bool("flip_normals")?.unwrap_or(shape::DEFAULT_FLIP_NORMALS);
    let shape = lookup(SHAPES, node)?(b, node, &to_world, flip_normals)?;
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
    let emitter = match emitter_nodes.first() {
        Some(e) => {
            let light = emitters::build_area(b, &e.node, shape_index)?;
            b.desc.emitters.push(light);
            Some((b.desc.emitters.len() - 1) as u32)
        }
        None => None,
    };
    let bsdf = match bsdfs.first() {
        Some(c) => b.bsdf_index(&c.node)?,
        None => b.implicit_bsdf(emitter.is_some()),
    };
    for c in node.children_of(ObjectTag::Sensor) {
        let sensor = super::sensors::build(&c.node, Some(shape_index))?;
        b.desc.sensors.push(sensor);
    }
    node.check_all_used()?;
    b.desc
        .shapes
        .push((shape, ShapeBinding { bsdf, emitter, id: node.id.clone().unwrap_or_default() }));
    Ok(())
}
