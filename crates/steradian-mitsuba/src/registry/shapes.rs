//! Shape plugins: `obj`, `ply`, `serialized`, `rectangle`, `disk`, `cube`, `sphere`, `cylinder`, with
//! their BSDF and area emitter.

use std::sync::Arc;

use steradian::scene::ShapeBinding;
use steradian::shape::{cube, read_obj, read_ply, Cylinder, Disk, Mesh, Rectangle, Shape, Sphere};
use steradian::Vec3;

use super::{emitters, unknown_type, Builder};
use crate::error::LoadError;
use crate::xml::{ObjectTag, PluginNode};

const KNOWN: &[&str] =
    &["obj", "ply", "serialized", "rectangle", "disk", "cube", "sphere", "cylinder"];

/// Builds a shape node and adds it (with its BSDF and area light) to the scene.
pub(crate) fn build(b: &mut Builder, node: &Arc<PluginNode>) -> Result<(), LoadError> {
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let flip_normals = p.get_bool("flip_normals")?.unwrap_or(false);
    let shape_err =
        |e: steradian::shape::ShapeError| LoadError::at(&node.pos, format!("{}: {e}", node.desc()));
    // Errors reading a mesh file are placed at its `filename`.
    let mesh_err = |e: steradian::shape::ShapeError| {
        LoadError::at(p.position("filename").unwrap_or(&node.pos), format!("{}: {e}", node.desc()))
    };

    let mesh_file = |name: &str| -> Result<std::path::PathBuf, LoadError> {
        let file = p.get_string(name)?.ok_or_else(|| {
            LoadError::at(&node.pos, format!("{}: missing '{name}'", node.desc()))
        })?;
        Ok(b.resolve_path(node, &file))
    };

    let shape = match node.plugin_type.as_str() {
        "obj" => {
            let path = mesh_file("filename")?;
            let face_normals = p.get_bool("face_normals")?.unwrap_or(false);
            let flip_tex = p.get_bool("flip_tex_coords")?.unwrap_or(true);
            let data = read_obj(&path, flip_tex).map_err(mesh_err)?;
            Shape::Mesh(
                Mesh::from_data(data, &to_world, flip_normals, face_normals).map_err(mesh_err)?,
            )
        }
        "ply" => {
            let path = mesh_file("filename")?;
            let face_normals = p.get_bool("face_normals")?.unwrap_or(false);
            let data = read_ply(&path).map_err(mesh_err)?;
            Shape::Mesh(
                Mesh::from_data(data, &to_world, flip_normals, face_normals).map_err(mesh_err)?,
            )
        }
        "serialized" => Shape::Mesh(serialized(b, node, &to_world, flip_normals)?),
        "rectangle" => Shape::Rectangle(Rectangle::new(&to_world, flip_normals)),
        "disk" => Shape::Disk(Disk::new(&to_world, flip_normals)),
        "cube" => Shape::Mesh(cube(&to_world, flip_normals)),
        "sphere" => {
            let center = p.get_point("center")?.unwrap_or(Vec3::ZERO);
            let radius = p.get_float("radius")?.unwrap_or(1.0);
            if !(radius.is_finite() && radius != 0.0) {
                return Err(LoadError::at(
                    p.position("radius").unwrap_or(&node.pos),
                    format!("{}: radius must be non-zero and finite, got {radius}", node.desc()),
                ));
            }
            Shape::Sphere(Sphere::new(center, radius, &to_world, flip_normals))
        }
        "cylinder" => {
            let p0 = p.get_point("p0")?.unwrap_or(Vec3::ZERO);
            let p1 = p.get_point("p1")?.unwrap_or(Vec3::Z);
            let radius = p.get_float("radius")?.unwrap_or(1.0);
            Shape::Cylinder(
                Cylinder::new(p0, p1, radius, &to_world, flip_normals).map_err(shape_err)?,
            )
        }
        _ => return Err(unknown_type(node, KNOWN)),
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

/// `serialized`: one shape of a Mitsuba `.serialized` file (core: shape/serialized.rs).
fn serialized(
    b: &Builder,
    node: &Arc<PluginNode>,
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
