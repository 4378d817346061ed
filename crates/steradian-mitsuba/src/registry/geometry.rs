//! Shape plugins' geometry: `obj`, `ply`, `serialized`, `rectangle`, `disk`, `cube`, `sphere`,
//! `cylinder`, `linearcurve`, `bsplinecurve`, `sdfgrid`, `ellipsoids`, `ellipsoidsmesh`, each
//! built from its node with its `to_world` and `flip_normals`. What a shape
//! carries besides (BSDF, area emitter, sensor) and how groups place it is `shapes`' business;
//! the geometry sits apart so that a sensor (a `distant` sensor's `target`) can build a shape
//! without importing the module that nests sensors in shapes.

use std::path::PathBuf;
use std::sync::Arc;

use steradian::geometry::Transform;
use steradian::shape::{
    self, ellipsoid_shells, read_curves, read_ellipsoids, read_obj, read_ply_with_attributes,
    BSplineCurve, Cylinder, Disk, EllipsoidCloud, EllipsoidShells, Ellipsoids, ExtentClamping,
    LinearCurve, Mesh, MeshData, Rectangle, SdfGrid, SdfNormals, Shape, ShapeError, Shell,
    ShellTemplate, Sphere, VertexNormals, DEFAULT_FLIP_TEX_COORDS,
};
use steradian::texture::GridVolume;

use super::{at_filename, choice, lookup, AttributeSource, Builder, MeshAttributes, Plugins};
use crate::error::{LoadError, LoadWarning};
use crate::tree::PluginNode;

/// What a shape builder reads: the scene being built (for file paths), the shape's node, and
/// the `to_world` and `flip_normals` every shape has.
pub(super) struct ShapeArgs<'a> {
    pub(super) b: &'a Builder,
    pub(super) node: &'a PluginNode,
    pub(super) to_world: Transform,
    pub(super) flip: bool,
}

/// Builds one shape from its node.
pub(super) type BuildShape = fn(&ShapeArgs) -> Result<Shape, LoadError>;

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
    ("linearcurve", linearcurve),
    ("bsplinecurve", bsplinecurve),
    ("sdfgrid", sdfgrid),
    ("ellipsoids", ellipsoids),
    ("ellipsoidsmesh", ellipsoidsmesh),
    ("shapegroup", group_placeholder),
    ("instance", group_placeholder),
    ("merge", group_placeholder),
];

/// `shapegroup`, `instance` and `merge` are handled by [`build`] before the table is consulted; the
/// table names them so that unknown-type errors and the README's list include them.
fn group_placeholder(s: &ShapeArgs) -> Result<Shape, LoadError> {
    Err(LoadError::at(&s.node.pos, format!("{} cannot be nested in another object", s.node.desc())))
}

/// A shape error at the node.
fn shape_err(node: &PluginNode) -> impl Fn(ShapeError) -> LoadError + '_ {
    move |e| LoadError::at(&node.pos, format!("{}: {e}", node.desc()))
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
    let data = data.map_err(at_filename::<ShapeError>(s.node))?;
    let mesh = Mesh::from_data(data, &s.to_world, s.flip, face_normals)
        .map_err(at_filename::<ShapeError>(s.node))?;
    Ok(Shape::Mesh(mesh))
}

fn obj(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let path = mesh_file(s)?;
    let face_normals = face_normals(s.node)?;
    let flip_tex = s.node.props.get_bool("flip_tex_coords")?.unwrap_or(DEFAULT_FLIP_TEX_COORDS);
    let vertex_normals = if face_normals { VertexNormals::Ignore } else { VertexNormals::Read };
    mesh(s, read_obj(&path, flip_tex, vertex_normals), face_normals)
}

/// A `ply` mesh; its attributes are kept in the builder for the shape's BSDF
/// (`mesh_attribute` textures).
fn ply(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let path = mesh_file(s)?;
    let face_normals = face_normals(s.node)?;
    let (data, list) =
        read_ply_with_attributes(&path).map_err(at_filename::<ShapeError>(s.node))?;
    // the triangles are copied for the textures only when the file has attributes
    let indices = if list.is_empty() { Arc::from([]) } else { data.indices.as_slice().into() };
    let attributes = MeshAttributes { indices, list };
    let shape = mesh(s, Ok(data), face_normals)?;
    s.b.mesh_attributes.replace(AttributeSource::Mesh(attributes));
    Ok(shape)
}

/// `linearcurve` (core: shape/linearcurve.rs).
fn linearcurve(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let curves = curve_file(s)?;
    let curve = LinearCurve::new(&curves, &s.to_world).map_err(shape_err(s.node))?;
    Ok(Shape::LinearCurve(curve))
}

/// `bsplinecurve` (core: shape/bsplinecurve.rs).
fn bsplinecurve(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let curves = curve_file(s)?;
    let curve = BSplineCurve::new(&curves, &s.to_world).map_err(shape_err(s.node))?;
    Ok(Shape::BSplineCurve(curve))
}

/// A curve shape's control points from its `filename`; Mitsuba's curves read no
/// `flip_normals`.
fn curve_file(s: &ShapeArgs) -> Result<Vec<Vec<glam::Vec4>>, LoadError> {
    if let Some(pos) = s.node.props.position("flip_normals") {
        return Err(LoadError::at(
            pos,
            format!("{}: curves have no 'flip_normals' (Mitsuba 3 refuses it)", s.node.desc()),
        ));
    }
    let path = mesh_file(s)?;
    read_curves(&path).map_err(at_filename::<ShapeError>(s.node))
}

/// An error at `flip_normals` where the shape has none: `what` is "<the shape> has" (or
/// "have").
fn refuse_flip_normals(node: &PluginNode, what: &str) -> Result<(), LoadError> {
    match node.props.position("flip_normals") {
        Some(pos) => Err(LoadError::at(
            pos,
            format!("{}: {what} no 'flip_normals' (Mitsuba 3 refuses it)", node.desc()),
        )),
        None => Ok(()),
    }
}

/// `sdfgrid` (core: shape/sdfgrid.rs): the SDF samples from a one-channel `.vol` file. Mitsuba
/// reads no `flip_normals` for it; its `grid` tensor cannot be given in XML.
fn sdfgrid(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let node = s.node;
    refuse_flip_normals(node, "an sdfgrid has")?;
    let normals = choice(
        node,
        "normals",
        SdfNormals::DEFAULT,
        &[("smooth", SdfNormals::Smooth), ("analytic", SdfNormals::Analytic)],
    )?;
    let path = mesh_file(s)?;
    let grid = GridVolume::read(&path).map_err(at_filename(node))?;
    if grid.channels != 1 {
        let reason = format!(
            "\"{}\" has {} channels; an sdfgrid's file holds 1",
            path.display(),
            grid.channels
        );
        return Err(at_filename(node)(reason));
    }
    let sdf = SdfGrid::new(grid.res, grid.into_values(), &s.to_world, normals)
        .map_err(at_filename::<ShapeError>(node))?;
    Ok(Shape::SdfGrid(sdf))
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

/// The ellipsoids of an `ellipsoids` or `ellipsoidsmesh` node (core: shape/ellipsoids.rs) and
/// each one's extent. Their `data`, `centers`, `scales` and `quaternions` tensors cannot be
/// written in XML: a scene names a PLY file.
fn ellipsoid_cloud(s: &ShapeArgs) -> Result<(EllipsoidCloud, Vec<f32>), LoadError> {
    let (node, p) = (s.node, &s.node.props);
    let positive = |name: &str, default: f32| -> Result<f32, LoadError> {
        let v = p.get_float(name)?.unwrap_or(default);
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(LoadError::at(
                p.position(name).unwrap_or(&node.pos),
                format!("{}: '{name}' must be positive and finite, got {v}", node.desc()),
            ))
        }
    };
    let scale_factor = positive("scale_factor", shape::DEFAULT_SCALE_FACTOR)?;
    let extent = positive("extent", shape::DEFAULT_EXTENT)?;
    let clamping = match p.get_bool("extent_adaptive_clamping")? {
        None => ExtentClamping::DEFAULT,
        Some(false) => ExtentClamping::Fixed,
        Some(true) => ExtentClamping::Adaptive,
    };
    let path = mesh_file(s)?;
    let cloud = read_ellipsoids(&path, scale_factor, &s.to_world)
        .map_err(at_filename::<ShapeError>(node))?;
    if clamping == ExtentClamping::Adaptive && cloud.opacities.is_none() {
        s.b.warn(LoadWarning::at(
            p.position("extent_adaptive_clamping").unwrap_or(&node.pos),
            format!(
                "{}: the file gives no opacities, so extent_adaptive_clamping is off (as in \
                 Mitsuba 3)",
                node.desc()
            ),
        ));
    }
    let extents = cloud.extents(extent, clamping);
    Ok((cloud, extents))
}

/// `ellipsoids` (core: shape/ellipsoids.rs). Mitsuba reads no `flip_normals` for it.
fn ellipsoids(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let node = s.node;
    refuse_flip_normals(node, "ellipsoids have")?;
    let (cloud, extents) = ellipsoid_cloud(s)?;
    let shape = Ellipsoids::new(&cloud.ellipsoids, &extents).map_err(at_filename(node))?;
    Ok(Shape::Ellipsoids(shape))
}

/// `ellipsoidsmesh` (core: shape/ellipsoidsmesh.rs): the ellipsoids' shells as one mesh with
/// flat normals, hit from outside only; `shell` is a template's name or a nested mesh shape
/// named "shell".
fn ellipsoidsmesh(s: &ShapeArgs) -> Result<Shape, LoadError> {
    let (node, p) = (s.node, &s.node.props);
    let shell = match (p.contains("shell"), node.child("shell")) {
        (true, Some(c)) => {
            return Err(LoadError::at(
                c.pos(),
                format!("{}: 'shell' is given twice, as a string and an object", node.desc()),
            ))
        }
        (false, Some(c)) if c.node.tag == crate::tree::ObjectTag::Shape => {
            match build_geometry(s.b, &c.node)? {
                Shape::Mesh(m) => Shell::Mesh { positions: m.positions, indices: m.indices },
                _ => {
                    return Err(LoadError::at(
                        c.pos(),
                        format!(
                            "{}: the shell {} is not a triangle mesh (obj, ply, serialized, cube)",
                            node.desc(),
                            c.node.desc()
                        ),
                    ))
                }
            }
        }
        (false, Some(c)) => {
            return Err(LoadError::at(
                c.pos(),
                format!(
                    "{}: 'shell' must be a string or a mesh, not {}",
                    node.desc(),
                    c.node.desc()
                ),
            ))
        }
        _ => Shell::Named(choice(
            node,
            "shell",
            ShellTemplate::DEFAULT,
            &[
                ("ico_sphere", ShellTemplate::IcoSphere),
                ("default", ShellTemplate::IcoSphere),
                ("box", ShellTemplate::Box),
                ("uv_sphere", ShellTemplate::UvSphere),
            ],
        )?),
    };
    // accepted as Mitsuba accepts it; the shells are flat either way
    p.get_bool("face_normals")?;
    let (cloud, extents) = ellipsoid_cloud(s)?;
    let data = ellipsoid_shells(&cloud.ellipsoids, &extents, &shell).map_err(at_filename(node))?;
    let mesh = Mesh::from_data(data, &Default::default(), s.flip, true)
        .map_err(at_filename::<ShapeError>(node))?;
    Ok(Shape::EllipsoidShells(EllipsoidShells::new(mesh)))
}

/// A shape's geometry alone, where it only marks out a region (a `distant` sensor's
/// `target`): a BSDF, emitter or sensor in it is an unused object, hence an error.
pub(crate) fn build_geometry(b: &Builder, node: &PluginNode) -> Result<Shape, LoadError> {
    if matches!(node.plugin_type.as_str(), "shapegroup" | "instance" | "merge") {
        return Err(LoadError::at(&node.pos, format!("{} cannot be nested here", node.desc())));
    }
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let flip = p.get_bool("flip_normals")?.unwrap_or(shape::DEFAULT_FLIP_NORMALS);
    let shape = lookup(SHAPES, node)?(&ShapeArgs { b, node, to_world, flip })?;
    node.check_all_used()?;
    Ok(shape)
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
    let shape = read_serialized(&path, shape_index).map_err(at_filename::<ShapeError>(node))?;
    Mesh::from_data(shape.data, to_world, flip_normals, face_normals)
        .map_err(at_filename::<ShapeError>(node))
}
