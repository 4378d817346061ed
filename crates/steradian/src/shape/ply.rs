//! # `ply`: Stanford PLY meshes
//!
//! Mitsuba plugin `ply`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `filename` | string | — | path of the `.ply` file |
//! | `face_normals` | bool | false | flat shading: ignore vertex normals |
//! | `flip_normals` | bool | false | flip geometric and shading normals |
//! | `to_world` | transform | identity | object → world |
//!
//! steradian reads ASCII and binary (little and big endian) files. The `vertex` element must
//! have `x`, `y`, `z` (float or double); `nx`, `ny`, `nz` are used as vertex normals when all
//! three are present, and texture coordinates are taken from `u`/`v`, `s`/`t` or
//! `texture_u`/`texture_v` (also `texture_s`/`texture_t`). The `face` element's
//! `vertex_indices` (or `vertex_index`) list (any integer type) gives polygons, which are
//! fan-triangulated. Other elements and properties are skipped. When the file has no normals
//! and `face_normals` is false, smooth angle-weighted vertex normals are computed, as in
//! Mitsuba. Malformed, truncated or inconsistent files give an error, never a crash.

use std::io::BufReader;
use std::path::Path;

use glam::{Vec2, Vec3};
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, Property, PropertyAccess};

use super::{MeshData, ShapeError};

#[derive(Default)]
struct PlyVertex {
    p: [f32; 3],
    n: [f32; 3],
    uv: [f32; 2],
    /// Bits: x y z nx ny nz u v.
    seen: u8,
}

fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v as f64,
        Property::UChar(v) => v as f64,
        Property::Short(v) => v as f64,
        Property::UShort(v) => v as f64,
        Property::Int(v) => v as f64,
        Property::UInt(v) => v as f64,
        Property::Float(v) => v as f64,
        Property::Double(v) => v,
        _ => return None,
    })
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        PlyVertex::default()
    }

    fn set_property(&mut self, name: String, property: Property) {
        let Some(v) = scalar(&property) else { return };
        let v = v as f32;
        let bit = match name.as_str() {
            "x" => {
                self.p[0] = v;
                0
            }
            "y" => {
                self.p[1] = v;
                1
            }
            "z" => {
                self.p[2] = v;
                2
            }
            "nx" => {
                self.n[0] = v;
                3
            }
            "ny" => {
                self.n[1] = v;
                4
            }
            "nz" => {
                self.n[2] = v;
                5
            }
            "u" | "s" | "texture_u" | "texture_s" => {
                self.uv[0] = v;
                6
            }
            "v" | "t" | "texture_v" | "texture_t" => {
                self.uv[1] = v;
                7
            }
            _ => return,
        };
        self.seen |= 1 << bit;
    }
}

#[derive(Default)]
struct PlyFace {
    indices: Option<Result<Vec<u32>, ()>>,
}

fn index_list(p: Property) -> Option<Result<Vec<u32>, ()>> {
    fn conv<T: TryInto<u32> + Copy>(v: Vec<T>) -> Result<Vec<u32>, ()> {
        v.into_iter().map(|x| x.try_into().map_err(|_| ())).collect()
    }
    Some(match p {
        Property::ListChar(v) => conv(v),
        Property::ListUChar(v) => conv(v),
        Property::ListShort(v) => conv(v),
        Property::ListUShort(v) => conv(v),
        Property::ListInt(v) => conv(v),
        Property::ListUInt(v) => Ok(v),
        _ => return None,
    })
}

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        PlyFace::default()
    }

    fn set_property(&mut self, name: String, property: Property) {
        if name == "vertex_indices" || name == "vertex_index" {
            self.indices = index_list(property);
        }
    }
}

/// Reads a PLY file into object-space mesh data.
pub fn read_ply(path: &Path) -> Result<MeshData, ShapeError> {
    let err = |msg: String| ShapeError(format!("PLY file \"{}\": {msg}", path.display()));
    let file = std::fs::File::open(path)
        .map_err(|e| ShapeError(format!("cannot open PLY file \"{}\": {e}", path.display())))?;
    let mut reader = BufReader::new(file);
    // ply-rs reports errors as io::Error; guard against panics in the parser all the same.
    let result =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| read_ply_inner(&mut reader)));
    let data = match result {
        Ok(r) => r.map_err(err)?,
        Err(_) => return Err(err("malformed data".into())),
    };
    Ok(data)
}

fn read_ply_inner(reader: &mut BufReader<std::fs::File>) -> Result<MeshData, String> {
    let header = Parser::<DefaultElement>::new()
        .read_header(reader)
        .map_err(|e| format!("invalid header: {e}"))?;
    let vparser = Parser::<PlyVertex>::new();
    let fparser = Parser::<PlyFace>::new();
    let sparser = Parser::<DefaultElement>::new();
    let mut vertices: Option<Vec<PlyVertex>> = None;
    let mut faces: Option<Vec<PlyFace>> = None;
    for (name, def) in &header.elements {
        match name.as_str() {
            "vertex" => {
                vertices = Some(
                    vparser
                        .read_payload_for_element(reader, def, &header)
                        .map_err(|e| format!("cannot read vertices: {e}"))?,
                )
            }
            "face" => {
                faces = Some(
                    fparser
                        .read_payload_for_element(reader, def, &header)
                        .map_err(|e| format!("cannot read faces: {e}"))?,
                )
            }
            _ => {
                sparser
                    .read_payload_for_element(reader, def, &header)
                    .map_err(|e| format!("cannot read element \"{name}\": {e}"))?;
            }
        }
    }
    let vertices = vertices.ok_or("no \"vertex\" element")?;
    let faces = faces.ok_or("no \"face\" element")?;
    let all = |bits: u8| vertices.iter().all(|v| v.seen & bits == bits);
    if !all(0b111) {
        return Err("vertices need x, y and z properties".into());
    }
    let positions: Vec<Vec3> = vertices.iter().map(|v| Vec3::from(v.p)).collect();
    let normals = (!vertices.is_empty() && all(0b111_000))
        .then(|| vertices.iter().map(|v| Vec3::from(v.n)).collect());
    let uvs = (!vertices.is_empty() && all(0b1100_0000))
        .then(|| vertices.iter().map(|v| Vec2::from(v.uv)).collect());
    let nv = positions.len();
    let mut indices = Vec::with_capacity(faces.len());
    for (f, face) in faces.into_iter().enumerate() {
        let idx = match face.indices {
            None => return Err(format!("face {f} has no vertex_indices list")),
            Some(Err(())) => return Err(format!("face {f} has a negative vertex index")),
            Some(Ok(v)) => v,
        };
        if let Some(&bad) = idx.iter().find(|&&i| i as usize >= nv) {
            return Err(format!(
                "face {f} refers to vertex {bad}, but there are only {nv} vertices"
            ));
        }
        for k in 2..idx.len() {
            indices.push([idx[0], idx[k - 1], idx[k]]);
        }
    }
    if indices.is_empty() {
        return Err("no triangles".into());
    }
    Ok(MeshData { positions, normals, uvs, indices })
}
