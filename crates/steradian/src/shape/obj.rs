//! # `obj`: Wavefront OBJ meshes
//!
//! Mitsuba plugin `obj`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `filename` | string | — | path of the `.obj` file |
//! | `face_normals` | bool | false | flat shading: ignore/skip vertex normals |
//! | `flip_tex_coords` | bool | **true** | v → 1 − v (OBJ's texture origin is bottom-left) |
//! | `flip_normals` | bool | false | flip geometric and shading normals |
//! | `to_world` | transform | identity | object → world |
//!
//! steradian reads `v`, `vt`, `vn` and `f` records (polygons are triangulated, faces whose
//! corners use different position/uv/normal indices are de-duplicated into one index per
//! corner), ignores materials, groups and objects (all objects become one mesh), and then
//! builds a [`Mesh`](super::Mesh): when the file has no normals and `face_normals` is false,
//! smooth angle-weighted vertex normals are computed, as in Mitsuba. With `face_normals` the
//! file's normals are not read at all.
//!
//! Where steradian differs on purpose: a file in which some faces give normals (`vn`) and
//! others do not is an error that says so (set `face_normals`, or give every face normals).
//! Mitsuba 3.9.1 loads it and gives the other faces' vertices zero normals, which render
//! black.

use std::io::BufReader;
use std::path::Path;

use glam::{Vec2, Vec3};

use super::{MeshData, ShapeError};

/// Reads an OBJ file into object-space mesh data.
/// Default `flip_tex_coords` (Mitsuba's): OBJ's texture origin is bottom-left.
pub const DEFAULT_FLIP_TEX_COORDS: bool = true;

/// Whether [`read_obj`] reads the file's vertex normals (`face_normals` false) or ignores
/// them (`face_normals` true: the mesh is flat-shaded whatever the file gives).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexNormals {
    Read,
    Ignore,
}

pub fn read_obj(
    path: &Path,
    flip_tex_coords: bool,
    vertex_normals: VertexNormals,
) -> Result<MeshData, ShapeError> {
    let file = std::fs::File::open(path)
        .map_err(|e| ShapeError(format!("cannot open OBJ file \"{}\": {e}", path.display())))?;
    let mut reader = BufReader::new(file);
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut reader, &options, |_| Err(tobj::LoadError::OpenFileFailed))
    }));
    let (models, _materials) = match result {
        Ok(Ok(r)) => r,
        Ok(Err(e)) => {
            return Err(ShapeError(format!("cannot parse OBJ file \"{}\": {e}", path.display())))
        }
        Err(_) => {
            return Err(ShapeError(format!(
                "cannot parse OBJ file \"{}\": malformed data",
                path.display()
            )))
        }
    };
    // normals are read when the file gives them, and then every model must give one per vertex
    let given = |m: &tobj::Model| !m.mesh.normals.is_empty();
    let complete = |m: &tobj::Model| given(m) && m.mesh.normals.len() == m.mesh.positions.len();
    let read_normals = vertex_normals == VertexNormals::Read && models.iter().any(given);
    if read_normals && !models.iter().all(complete) {
        return Err(ShapeError(format!(
            "OBJ file \"{}\": some faces give vertex normals (vn) and others do not (Mitsuba 3 \
             gives the others zero normals, which render black); give every face normals, or set \
             face_normals to true",
            path.display()
        )));
    }
    let all_uvs = models.iter().all(|m| !m.mesh.texcoords.is_empty());
    let mut data = MeshData::default();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for m in &models {
        let mesh = &m.mesh;
        let base = data.positions.len() as u32;
        let nv = mesh.positions.len() / 3;
        data.positions.extend(mesh.positions.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])));
        if read_normals {
            normals.extend(mesh.normals.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])));
        }
        if all_uvs {
            if mesh.texcoords.len() != 2 * nv {
                return Err(ShapeError(format!(
                    "OBJ file \"{}\": some faces give texture coordinates (vt) and others do not \
                     (Mitsuba 3 leaves the others' undefined); give every face texture coordinates",
                    path.display()
                )));
            }
            uvs.extend(
                mesh.texcoords
                    .chunks_exact(2)
                    .map(|c| Vec2::new(c[0], if flip_tex_coords { 1.0 - c[1] } else { c[1] })),
            );
        }
        if mesh.indices.len() % 3 != 0 {
            return Err(ShapeError(format!(
                "OBJ file \"{}\": faces were not triangulated",
                path.display()
            )));
        }
        for tri in mesh.indices.chunks_exact(3) {
            let t = [tri[0], tri[1], tri[2]];
            if let Some(&bad) = t.iter().find(|&&i| i as usize >= nv) {
                return Err(ShapeError(format!(
                    "OBJ file \"{}\": face refers to missing vertex {bad}",
                    path.display()
                )));
            }
            data.indices.push(t.map(|i| i + base));
        }
    }
    if data.indices.is_empty() {
        return Err(ShapeError(format!("OBJ file \"{}\" contains no triangles", path.display())));
    }
    if read_normals {
        data.normals = Some(normals);
    }
    if all_uvs {
        data.uvs = Some(uvs);
    }
    Ok(data)
}
