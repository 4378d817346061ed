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
//! fan-triangulated. Other elements are skipped. When the file has no normals and
//! `face_normals` is false, smooth angle-weighted vertex normals are computed, as in Mitsuba.
//! Malformed, truncated or inconsistent files give an error, never a crash.
//!
//! ## Attributes (for `mesh_attribute` textures)
//!
//! The other scalar properties of `vertex` and `face` become attributes named as Mitsuba 3
//! names them, `vertex_…` or `face_…`:
//! - `r`, `g`, `b` (or `red`, `green`, `blue`), with `a` (`alpha`) when present: `…_color`;
//! - consecutive properties `P_x P_y P_z`, `P_r P_g P_b` (named `…_P_color`), `P_0 P_1 P_2` or
//!   `P_1 P_2 P_3`, or a single one of them: `…_P` with 3 or 1 channels. Groups of another
//!   size, a prefix seen before, names without `_` or with a longer suffix are skipped, as
//!   Mitsuba skips them (it warns).
//!
//! Values are converted as Mitsuba 3.9.1 converts them: floats and `uchar` as stored, other
//! integer types normalised by their largest value and then read as sRGB-encoded (decoded to
//! linear). A face attribute of a polygon holds for each of its triangles.

use std::io::BufReader;
use std::path::Path;

use glam::{Vec2, Vec3};
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, ElementDef, Property, PropertyAccess, PropertyType};

use super::{MeshData, ShapeError};
use crate::texture::{AttributeScope, MeshAttributeData};

#[derive(Default)]
struct PlyVertex {
    p: [f32; 3],
    n: [f32; 3],
    uv: [f32; 2],
    /// Bits: x y z nx ny nz u v.
    seen: u8,
    /// The other scalar properties in the header's order (converted, [`attribute_value`]);
    /// empty, without an allocation, when the file has none.
    extras: Vec<f32>,
}

/// The value Mitsuba 3.9.1 stores for a property of an attribute: floats and `uchar` as they
/// are, other integers normalised by their type's largest value and decoded from sRGB.
fn attribute_value(p: &Property) -> Option<f32> {
    let normalised = match *p {
        Property::UChar(v) => return Some(v as f32),
        Property::Float(v) => return Some(v),
        Property::Double(v) => return Some(v as f32),
        Property::Char(v) => v as f64 / i8::MAX as f64,
        Property::Short(v) => v as f64 / i16::MAX as f64,
        Property::UShort(v) => v as f64 / u16::MAX as f64,
        Property::Int(v) => v as f64 / i32::MAX as f64,
        Property::UInt(v) => v as f64 / u32::MAX as f64,
        _ => return None,
    };
    let linear = if normalised <= 0.04045 {
        normalised / 12.92
    } else {
        ((normalised + 0.055) / 1.055).powf(2.4)
    };
    Some(linear as f32)
}

/// Vertex properties that are geometry, not attributes.
fn is_vertex_geometry(name: &str) -> bool {
    matches!(
        name,
        "x" | "y"
            | "z"
            | "nx"
            | "ny"
            | "nz"
            | "u"
            | "v"
            | "s"
            | "t"
            | "texture_u"
            | "texture_v"
            | "texture_s"
            | "texture_t"
    )
}

/// Face properties that are the face's vertices.
fn is_face_geometry(name: &str) -> bool {
    name == "vertex_indices" || name == "vertex_index"
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
        if !is_vertex_geometry(&name) {
            if let Some(v) = attribute_value(&property) {
                self.extras.push(v);
            }
            return;
        }
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
    /// The other scalar properties, as [`PlyVertex::extras`].
    extras: Vec<f32>,
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
        if is_face_geometry(&name) {
            self.indices = index_list(property);
        } else if let Some(v) = attribute_value(&property) {
            self.extras.push(v);
        }
    }
}

/// Reads a PLY file into object-space mesh data.
pub fn read_ply(path: &Path) -> Result<MeshData, ShapeError> {
    read_ply_with_attributes(path).map(|(data, _)| data)
}

/// Reads a PLY file into object-space mesh data and its vertex and face attributes (named
/// as Mitsuba names them, see the module documentation; face attributes have one entry per
/// triangle of `indices`).
pub fn read_ply_with_attributes(
    path: &Path,
) -> Result<(MeshData, Vec<MeshAttributeData>), ShapeError> {
    let err = |msg: String| ShapeError(format!("PLY file \"{}\": {msg}", path.display()));
    let file = std::fs::File::open(path)
        .map_err(|e| ShapeError(format!("cannot open PLY file \"{}\": {e}", path.display())))?;
    let mut reader = BufReader::new(file);
    // ply-rs reports errors as io::Error; guard against panics in the parser all the same.
    let result =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| read_ply_inner(&mut reader)));
    match result {
        Ok(r) => r.map_err(err),
        Err(_) => Err(err("malformed data".into())),
    }
}

/// The scalar properties of an element that become attributes, in the header's order.
fn attribute_fields(def: &ElementDef, is_geometry: fn(&str) -> bool) -> Vec<String> {
    def.properties
        .iter()
        .filter(|(name, p)| {
            matches!(p.data_type, PropertyType::Scalar(_)) && !is_geometry(name.as_str())
        })
        .map(|(name, _)| name.clone())
        .collect()
}

/// Mitsuba's grouping of attribute fields: for each attribute its name (without the
/// `vertex_`/`face_` scope) and the indices of its fields in `names`.
fn group_fields(names: &[String]) -> Vec<(String, Vec<usize>)> {
    let find = |n: &str| names.iter().position(|x| x == n);
    let mut groups = Vec::new();
    let mut reserved: Vec<&str> = vec!["r", "g", "b", "a"];
    let colour = match (find("r"), find("g"), find("b")) {
        (Some(r), Some(g), Some(b)) => Some(([r, g, b], find("a"))),
        _ => match (find("red"), find("green"), find("blue")) {
            (Some(r), Some(g), Some(b)) => {
                reserved.extend(["red", "green", "blue", "alpha"]);
                Some(([r, g, b], find("alpha")))
            }
            _ => None,
        },
    };
    if let Some((rgb, alpha)) = colour {
        let mut fields = rgb.to_vec();
        fields.extend(alpha);
        groups.push(("color".to_string(), fields));
    }
    // suffix rows: the k-th field of an attribute of category c has suffix POSTFIXES[k][c]
    const POSTFIXES: [&[u8; 4]; 4] = [b"xr01", b"yg12", b"zb23", b"wa34"];
    struct Current<'a> {
        prefix: &'a str,
        category: usize,
        fields: Vec<usize>,
    }
    fn flush<'a>(
        c: Option<Current<'a>>,
        groups: &mut Vec<(String, Vec<usize>)>,
        seen: &mut Vec<&'a str>,
    ) {
        if let Some(c) = c {
            if c.fields.len() == 1 || c.fields.len() == 3 {
                let colour = if c.category == 1 { "_color" } else { "" };
                groups.push((format!("{}{colour}", c.prefix), c.fields));
                seen.push(c.prefix);
            }
        }
    }
    let mut seen: Vec<&str> = Vec::new();
    let mut current: Option<Current> = None;
    let mut skip_prefix: Option<&str> = None;
    for (i, name) in names.iter().enumerate() {
        if reserved.contains(&name.as_str()) {
            continue;
        }
        let Some(pos) = name.rfind('_') else {
            flush(current.take(), &mut groups, &mut seen);
            continue;
        };
        let (prefix, suffix) = (&name[..pos], &name.as_bytes()[pos + 1..]);
        if skip_prefix == Some(prefix) {
            continue;
        }
        skip_prefix = None;
        if suffix.len() != 1 {
            flush(current.take(), &mut groups, &mut seen);
            continue;
        }
        if current.as_ref().is_some_and(|c| c.prefix != prefix) {
            flush(current.take(), &mut groups, &mut seen);
        }
        match &mut current {
            None => {
                if seen.contains(&prefix) {
                    skip_prefix = Some(prefix);
                    continue;
                }
                if let Some(category) = POSTFIXES[0].iter().position(|&c| c == suffix[0]) {
                    current = Some(Current { prefix, category, fields: vec![i] });
                }
            }
            Some(c) => {
                let level = c.fields.len();
                if level < 4 && POSTFIXES[level][c.category] == suffix[0] {
                    c.fields.push(i);
                } else {
                    // an invalid sequence: the attribute is skipped
                    current = None;
                    skip_prefix = Some(prefix);
                }
            }
        }
    }
    flush(current.take(), &mut groups, &mut seen);
    groups
}

/// The attributes of `scope` from each element's extra values (`names` their fields), with
/// each element's values repeated `repeat(element)` times.
fn attributes(
    scope: AttributeScope,
    names: &[String],
    extras: &[&[f32]],
    repeat: impl Fn(usize) -> usize,
) -> Vec<MeshAttributeData> {
    let prefix = match scope {
        AttributeScope::Vertex => "vertex_",
        AttributeScope::Face => "face_",
    };
    group_fields(names)
        .into_iter()
        .map(|(name, fields)| {
            let mut values = Vec::new();
            for (e, x) in extras.iter().enumerate() {
                for _ in 0..repeat(e) {
                    values.extend(fields.iter().map(|&k| x.get(k).copied().unwrap_or(0.0)));
                }
            }
            MeshAttributeData {
                name: format!("{prefix}{name}"),
                scope,
                channels: fields.len() as u8,
                values,
            }
        })
        .collect()
}

fn read_ply_inner(
    reader: &mut BufReader<std::fs::File>,
) -> Result<(MeshData, Vec<MeshAttributeData>), String> {
    let header = Parser::<DefaultElement>::new()
        .read_header(reader)
        .map_err(|e| format!("invalid header: {e}"))?;
    let vparser = Parser::<PlyVertex>::new();
    let fparser = Parser::<PlyFace>::new();
    let sparser = Parser::<DefaultElement>::new();
    let mut vertices: Option<Vec<PlyVertex>> = None;
    let mut faces: Option<Vec<PlyFace>> = None;
    let (mut vertex_fields, mut face_fields) = (Vec::new(), Vec::new());
    for (name, def) in &header.elements {
        match name.as_str() {
            "vertex" => {
                vertex_fields = attribute_fields(def, is_vertex_geometry);
                vertices = Some(
                    vparser
                        .read_payload_for_element(reader, def, &header)
                        .map_err(|e| format!("cannot read vertices: {e}"))?,
                )
            }
            "face" => {
                face_fields = attribute_fields(def, is_face_geometry);
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
    let mut triangles_per_face = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let idx = match &face.indices {
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
        if !face_fields.is_empty() {
            triangles_per_face.push(idx.len().saturating_sub(2));
        }
    }
    if indices.is_empty() {
        return Err("no triangles".into());
    }
    let mut attrs = Vec::new();
    if !vertex_fields.is_empty() {
        let extras: Vec<&[f32]> = vertices.iter().map(|v| v.extras.as_slice()).collect();
        attrs.extend(attributes(AttributeScope::Vertex, &vertex_fields, &extras, |_| 1));
    }
    if !face_fields.is_empty() {
        let extras: Vec<&[f32]> = faces.iter().map(|f| f.extras.as_slice()).collect();
        attrs.extend(attributes(AttributeScope::Face, &face_fields, &extras, |f| {
            triangles_per_face[f]
        }));
    }
    Ok((MeshData { positions, normals, uvs, indices }, attrs))
}

#[cfg(test)]
mod attribute_tests {
    use super::*;

    fn names(n: &[&str]) -> Vec<String> {
        n.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn fields_group_as_mitsuba_groups_them() {
        let g = group_fields(&names(&[
            "red", "green", "blue", "w_x", "w_y", "w_z", "q_0", "s_1", "d_r", "d_g", "d_b",
            "two_x", "two_y", "lone", "long_xx",
        ]));
        let expect: Vec<(String, Vec<usize>)> = vec![
            ("color".into(), vec![0, 1, 2]),
            ("w".into(), vec![3, 4, 5]),
            ("q".into(), vec![6]),
            ("s".into(), vec![7]),
            ("d_color".into(), vec![8, 9, 10]),
        ];
        assert_eq!(g, expect);
        // a repeated prefix is skipped; an alpha channel joins the colour
        let g = group_fields(&names(&["r", "g", "b", "a", "k_x", "m_0", "k_x"]));
        assert_eq!(
            g,
            vec![("color".into(), vec![0, 1, 2, 3]), ("k".into(), vec![4]), ("m".into(), vec![5])]
        );
    }

    #[test]
    fn integer_values_are_normalised_and_decoded_except_uchar() {
        assert_eq!(attribute_value(&Property::UChar(200)), Some(200.0));
        assert_eq!(attribute_value(&Property::Float(0.5)), Some(0.5));
        // 100/127 read as sRGB: Mitsuba 3.9.1 stores 0.582694
        let c = attribute_value(&Property::Char(100)).unwrap();
        assert!((c - 0.582694).abs() < 1e-6, "{c}");
        // 1000/65535 on the linear segment of the sRGB curve
        let u = attribute_value(&Property::UShort(1000)).unwrap();
        assert!((u - 0.00118104).abs() < 1e-8, "{u}");
        assert_eq!(attribute_value(&Property::ListInt(vec![1])), None);
    }
}
