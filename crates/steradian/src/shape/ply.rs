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
//! The reader is steradian's own: binary files are decoded record by record from one large
//! buffer straight into the final position and index arrays (no per-vertex or per-face
//! allocation), so reading a 20-million-triangle sphere (380 MB) takes about a second and
//! needs no memory beyond the mesh itself. The `ply-rs` crate it replaced kept every vertex
//! and face as a separate object, about 1.6 GB more for that file.
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

use std::io::{BufRead, BufReader, Read, Seek};
use std::path::Path;

use glam::{Vec2, Vec3};

use super::{MeshData, ShapeError};
use crate::texture::{AttributeScope, MeshAttributeData};

/// Bytes read from the file at a time.
const READ_BUFFER: usize = 1 << 20;
/// A header longer than this is not a PLY header (a binary file read by mistake).
const MAX_HEADER_LINES: usize = 10_000;

/// The scalar types of the PLY format (with their sized aliases `int8` … `float64`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    Char,
    UChar,
    Short,
    UShort,
    Int,
    UInt,
    Float,
    Double,
}

impl Scalar {
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::Char,
            "uchar" | "uint8" => Scalar::UChar,
            "short" | "int16" => Scalar::Short,
            "ushort" | "uint16" => Scalar::UShort,
            "int" | "int32" => Scalar::Int,
            "uint" | "uint32" => Scalar::UInt,
            "float" | "float32" => Scalar::Float,
            "double" | "float64" => Scalar::Double,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::Char | Scalar::UChar => 1,
            Scalar::Short | Scalar::UShort => 2,
            Scalar::Int | Scalar::UInt | Scalar::Float => 4,
            Scalar::Double => 8,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Scalar::Char => "char",
            Scalar::UChar => "uchar",
            Scalar::Short => "short",
            Scalar::UShort => "ushort",
            Scalar::Int => "int",
            Scalar::UInt => "uint",
            Scalar::Float => "float",
            Scalar::Double => "double",
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::Float | Scalar::Double)
    }

    /// The value stored in `b` (at least [`Scalar::size`] bytes); every type is exact in f64.
    #[inline]
    fn decode(self, b: &[u8], order: ByteOrder) -> f64 {
        macro_rules! read {
            ($t:ty, $n:expr) => {{
                let bytes: [u8; $n] = b[..$n].try_into().expect("sized by the caller");
                match order {
                    ByteOrder::Little => <$t>::from_le_bytes(bytes),
                    ByteOrder::Big => <$t>::from_be_bytes(bytes),
                }
            }};
        }
        match self {
            Scalar::Char => b[0] as i8 as f64,
            Scalar::UChar => b[0] as f64,
            Scalar::Short => read!(i16, 2) as f64,
            Scalar::UShort => read!(u16, 2) as f64,
            Scalar::Int => read!(i32, 4) as f64,
            Scalar::UInt => read!(u32, 4) as f64,
            Scalar::Float => read!(f32, 4) as f64,
            Scalar::Double => read!(f64, 8),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ByteOrder {
    Little,
    Big,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Ascii,
    Binary(ByteOrder),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PropertyType {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Clone, Debug)]
struct PropertyDef {
    name: String,
    ty: PropertyType,
}

#[derive(Clone, Debug)]
struct ElementDef {
    name: String,
    count: usize,
    properties: Vec<PropertyDef>,
}

/// The value Mitsuba 3.9.1 stores for a property of an attribute: floats and `uchar` as they
/// are, other integers normalised by their type's largest value and decoded from sRGB.
fn attribute_value(ty: Scalar, v: f64) -> f32 {
    let normalised = match ty {
        Scalar::UChar | Scalar::Float | Scalar::Double => return v as f32,
        Scalar::Char => v / i8::MAX as f64,
        Scalar::Short => v / i16::MAX as f64,
        Scalar::UShort => v / u16::MAX as f64,
        Scalar::Int => v / i32::MAX as f64,
        Scalar::UInt => v / u32::MAX as f64,
    };
    let linear = if normalised <= 0.04045 {
        normalised / 12.92
    } else {
        ((normalised + 0.055) / 1.055).powf(2.4)
    };
    linear as f32
}

/// Where a property's values go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Slot {
    Position(usize),
    Normal(usize),
    Uv(usize),
    /// Face vertex indices (an integer list).
    Indices,
    /// The k-th attribute field of the element.
    Attribute(usize),
    Skip,
}

/// The slot of each vertex property.
fn vertex_slot(name: &str) -> Option<Slot> {
    Some(match name {
        "x" => Slot::Position(0),
        "y" => Slot::Position(1),
        "z" => Slot::Position(2),
        "nx" => Slot::Normal(0),
        "ny" => Slot::Normal(1),
        "nz" => Slot::Normal(2),
        "u" | "s" | "texture_u" | "texture_s" => Slot::Uv(0),
        "v" | "t" | "texture_v" | "texture_t" => Slot::Uv(1),
        _ => return None,
    })
}

/// Face properties that are the face's vertices.
fn is_face_geometry(name: &str) -> bool {
    name == "vertex_indices" || name == "vertex_index"
}

/// The slots of an element's properties (`geometry` gives the non-attribute ones) and the
/// names of its attribute fields, in the header's order.
fn slots(
    def: &ElementDef,
    geometry: impl Fn(&PropertyDef) -> Option<Slot>,
) -> (Vec<Slot>, Vec<String>) {
    let mut names = Vec::new();
    let slots = def
        .properties
        .iter()
        .map(|p| match (geometry(p), p.ty) {
            (Some(slot), _) => slot,
            (None, PropertyType::Scalar(_)) => {
                names.push(p.name.clone());
                Slot::Attribute(names.len() - 1)
            }
            (None, PropertyType::List { .. }) => Slot::Skip,
        })
        .collect();
    (slots, names)
}

/// The element data the reader walks through: a binary stream or the tokens of an ASCII body.
enum Body {
    Binary(BinaryInput),
    Ascii { text: String, pos: usize },
}

/// A binary body, read [`READ_BUFFER`] bytes at a time and decoded in place from the buffer.
struct BinaryInput {
    file: std::fs::File,
    buf: Vec<u8>,
    /// Next unread byte of `buf`.
    pos: usize,
    /// Bytes of the file not yet in `buf`.
    remaining: u64,
    order: ByteOrder,
}

impl BinaryInput {
    /// The next `n` bytes.
    #[inline]
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        if self.buf.len() - self.pos < n {
            self.refill(n)?;
        }
        let bytes = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(bytes)
    }

    /// Keeps the unread bytes and reads more, so that at least `n` are buffered.
    #[cold]
    fn refill(&mut self, n: usize) -> Result<(), String> {
        let have = self.buf.len() - self.pos;
        if (n - have) as u64 > self.remaining {
            return Err("the file ends early".into());
        }
        self.buf.drain(..self.pos);
        self.pos = 0;
        let target = (n.max(READ_BUFFER) as u64).min(have as u64 + self.remaining) as usize;
        self.buf.resize(target, 0);
        self.file
            .read_exact(&mut self.buf[have..])
            .map_err(|e| format!("cannot read the file: {e}"))?;
        self.remaining -= (target - have) as u64;
        Ok(())
    }
}

impl Body {
    /// The next scalar of type `ty`; an error at the end of the data or, in ASCII, for a token
    /// that is not a number of that kind.
    #[inline]
    fn scalar(&mut self, ty: Scalar) -> Result<f64, String> {
        match self {
            Body::Binary(input) => {
                let order = input.order;
                Ok(ty.decode(input.take(ty.size())?, order))
            }
            Body::Ascii { text, pos } => {
                let rest = &text[*pos..];
                let start = rest.len() - rest.trim_start().len();
                let token =
                    rest[start..].split_ascii_whitespace().next().ok_or("the file ends early")?;
                *pos += start + token.len();
                let v = if ty.is_integer() {
                    token.parse::<i64>().map(|v| v as f64).ok()
                } else {
                    token.parse::<f64>().ok()
                };
                v.ok_or_else(|| format!("\"{token}\" is not a valid {} value", ty.name()))
            }
        }
    }

    /// `n` scalars of type `ty` into `out` (cleared first).
    fn scalars(&mut self, ty: Scalar, n: usize, out: &mut Vec<f64>) -> Result<(), String> {
        out.clear();
        match self {
            Body::Binary(input) => {
                let order = input.order;
                let bytes = input.take(n * ty.size())?;
                out.extend(bytes.chunks_exact(ty.size()).map(|b| ty.decode(b, order)));
            }
            Body::Ascii { .. } => {
                for _ in 0..n {
                    let v = self.scalar(ty)?;
                    out.push(v);
                }
            }
        }
        Ok(())
    }

    /// `n` vertex indices of integer type `ty` into `out` (cleared first); `false` when one
    /// of them is negative.
    #[inline]
    fn indices(&mut self, ty: Scalar, n: usize, out: &mut Vec<u32>) -> Result<bool, String> {
        out.clear();
        match self {
            Body::Binary(input) => {
                let order = input.order;
                let bytes = input.take(n * ty.size())?;
                let mut valid = true;
                out.extend(bytes.chunks_exact(ty.size()).map(|b| {
                    let v = ty.decode(b, order);
                    valid &= v >= 0.0;
                    v as u32
                }));
                Ok(valid)
            }
            Body::Ascii { .. } => {
                let mut valid = true;
                for _ in 0..n {
                    let v = self.scalar(ty)?;
                    valid &= (0.0..=u32::MAX as f64).contains(&v);
                    out.push(v as u32);
                }
                Ok(valid)
            }
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
    let (file, file_len) = open_file(path)?;
    read(file, file_len)
        .map_err(|msg| ShapeError(format!("PLY file \"{}\": {msg}", path.display())))
}

/// The file at `path` and its length in bytes (`u64::MAX` when unknown).
fn open_file(path: &Path) -> Result<(std::fs::File, u64), ShapeError> {
    let file = std::fs::File::open(path)
        .map_err(|e| ShapeError(format!("cannot open PLY file \"{}\": {e}", path.display())))?;
    let file_len = file.metadata().map(|m| m.len()).unwrap_or(u64::MAX);
    Ok((file, file_len))
}

/// The first element of a PLY file as a table (what Mitsuba's `ellipsoids` reads): the
/// element's property names and its records' values, row after row, as numbers. Every
/// property must be a scalar.
pub fn read_ply_table(path: &Path) -> Result<PlyTable, ShapeError> {
    let fail = |msg: String| ShapeError(format!("PLY file \"{}\": {msg}", path.display()));
    let (file, file_len) = open_file(path)?;
    let (elements, mut body) = open_body(file, file_len).map_err(fail)?;
    let def = elements.first().ok_or_else(|| fail("the header declares no element".into()))?;
    let mut types = Vec::with_capacity(def.properties.len());
    for prop in &def.properties {
        match prop.ty {
            PropertyType::Scalar(ty) => types.push(ty),
            PropertyType::List { .. } => {
                return Err(fail(format!(
                    "property \"{}\" of element \"{}\" is a list; this table holds scalars only",
                    prop.name, def.name
                )))
            }
        }
    }
    // as in `read`: a corrupt count must not reserve more than the file could fill
    let capacity =
        def.count.saturating_mul(types.len()).min(file_len.min(usize::MAX as u64) as usize);
    let mut values = Vec::with_capacity(capacity);
    for record in 0..def.count {
        for ty in &types {
            let v = body
                .scalar(*ty)
                .map_err(|e| fail(format!("record {record} of \"{}\": {e}", def.name)))?;
            values.push(v);
        }
    }
    let names = def.properties.iter().map(|p| p.name.clone()).collect();
    Ok(PlyTable { element: def.name.clone(), names, values })
}

/// One PLY element read as a table by [`read_ply_table`].
#[derive(Clone, Debug, PartialEq)]
pub struct PlyTable {
    /// The element's name (`vertex` in the files Mitsuba writes).
    pub element: String,
    /// Property names, in file order.
    pub names: Vec<String>,
    /// `names.len()` values per record, record after record.
    pub values: Vec<f64>,
}

/// The header: the format and the elements, in order.
fn read_header(reader: &mut BufReader<std::fs::File>) -> Result<(Format, Vec<ElementDef>), String> {
    let mut line = Vec::new();
    let mut next_line = |reader: &mut BufReader<std::fs::File>| -> Result<String, String> {
        line.clear();
        let n = reader.read_until(b'\n', &mut line).map_err(|e| e.to_string())?;
        if n == 0 {
            return Err("invalid header: the file ends before end_header".into());
        }
        let text =
            std::str::from_utf8(&line).map_err(|_| "invalid header: not text".to_string())?;
        Ok(text.trim_end_matches(['\n', '\r']).to_string())
    };
    if next_line(reader)?.trim() != "ply" {
        return Err("invalid header: the file does not start with \"ply\"".into());
    }
    let mut format = None;
    let mut elements: Vec<ElementDef> = Vec::new();
    for number in 2.. {
        if number > MAX_HEADER_LINES {
            return Err("invalid header: no end_header".into());
        }
        let text = next_line(reader)?;
        let words: Vec<&str> = text.split_ascii_whitespace().collect();
        let bad = || format!("invalid header line {number}: \"{text}\"");
        match words.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, "1.0"] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Binary(ByteOrder::Little),
                    "binary_big_endian" => Format::Binary(ByteOrder::Big),
                    _ => return Err(bad()),
                })
            }
            ["element", name, count] => elements.push(ElementDef {
                name: name.to_string(),
                count: count.parse().map_err(|_| bad())?,
                properties: Vec::new(),
            }),
            ["property", "list", count, item, name] => {
                let ty = PropertyType::List {
                    count: Scalar::parse(count).filter(|c| c.is_integer()).ok_or_else(bad)?,
                    item: Scalar::parse(item).ok_or_else(bad)?,
                };
                let e = elements.last_mut().ok_or_else(bad)?;
                e.properties.push(PropertyDef { name: name.to_string(), ty });
            }
            ["property", ty, name] => {
                let ty = PropertyType::Scalar(Scalar::parse(ty).ok_or_else(bad)?);
                let e = elements.last_mut().ok_or_else(bad)?;
                e.properties.push(PropertyDef { name: name.to_string(), ty });
            }
            ["end_header"] => {
                let format = format.ok_or("invalid header: no format line")?;
                return Ok((format, elements));
            }
            _ => return Err(bad()),
        }
    }
    unreachable!("the loop returns")
}

/// The mesh being read.
#[derive(Default)]
struct Output {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    indices: Vec<[u32; 3]>,
    vertex_fields: Vec<String>,
    vertex_extras: Vec<f32>,
    face_fields: Vec<String>,
    face_extras: Vec<f32>,
    triangles_per_face: Vec<usize>,
    has_vertices: bool,
    has_faces: bool,
    /// Whether the faces' indices were checked against the vertex count as they were read
    /// (the faces followed the vertices).
    indices_checked: bool,
}

/// The header's elements and the body after it.
fn open_body(file: std::fs::File, file_len: u64) -> Result<(Vec<ElementDef>, Body), String> {
    let mut reader = BufReader::with_capacity(READ_BUFFER, file);
    let (format, elements) = read_header(&mut reader)?;
    let body = match format {
        Format::Binary(order) => {
            let buf = reader.buffer().to_vec();
            let mut file = reader.into_inner();
            let read = file.stream_position().map_err(|e| format!("cannot read the file: {e}"))?;
            let remaining = file_len.saturating_sub(read);
            Body::Binary(BinaryInput { file, buf, pos: 0, remaining, order })
        }
        Format::Ascii => {
            let mut text = String::new();
            reader
                .read_to_string(&mut text)
                .map_err(|_| "the ASCII data is not text".to_string())?;
            Body::Ascii { text, pos: 0 }
        }
    };
    Ok((elements, body))
}

fn read(file: std::fs::File, file_len: u64) -> Result<(MeshData, Vec<MeshAttributeData>), String> {
    let (elements, mut body) = open_body(file, file_len)?;
    // no element can have more records than the file has bytes: a corrupt count must not
    // reserve memory the file could never fill
    let capacity = |count: usize| count.min(file_len.min(usize::MAX as u64) as usize);
    let mut out = Output::default();
    for def in &elements {
        match def.name.as_str() {
            "vertex" if !out.has_vertices => {
                read_vertices(&mut body, def, capacity(def.count), &mut out)
                    .map_err(|e| format!("cannot read vertices: {e}"))?;
                out.has_vertices = true;
            }
            "face" if !out.has_faces => {
                read_faces(&mut body, def, capacity(def.count), &mut out)
                    .map_err(|e| format!("cannot read faces: {e}"))?;
                out.has_faces = true;
            }
            name => skip_element(&mut body, def)
                .map_err(|e| format!("cannot read element \"{name}\": {e}"))?,
        }
    }
    finish(out)
}

fn read_vertices(
    body: &mut Body,
    def: &ElementDef,
    capacity: usize,
    out: &mut Output,
) -> Result<(), String> {
    let (slots, fields) = slots(def, |p| vertex_slot(&p.name));
    let has = |want: &[Slot]| want.iter().all(|w| slots.contains(w));
    if !has(&[Slot::Position(0), Slot::Position(1), Slot::Position(2)]) {
        return Err("vertices need x, y and z properties".into());
    }
    let normals = has(&[Slot::Normal(0), Slot::Normal(1), Slot::Normal(2)]);
    let uvs = has(&[Slot::Uv(0), Slot::Uv(1)]);
    out.positions.reserve_exact(capacity);
    if normals {
        out.normals.reserve_exact(capacity);
    }
    if uvs {
        out.uvs.reserve_exact(capacity);
    }
    let mut list = Vec::new();
    let (mut p, mut n, mut uv) = ([0f32; 3], [0f32; 3], [0f32; 2]);
    let mut extras = vec![0f32; fields.len()];
    for _ in 0..def.count {
        for (prop, slot) in def.properties.iter().zip(&slots) {
            let ty = match prop.ty {
                PropertyType::Scalar(ty) => ty,
                PropertyType::List { count, item } => {
                    let len = body.scalar(count)?;
                    body.scalars(item, list_length(len)?, &mut list)?;
                    continue;
                }
            };
            let v = body.scalar(ty)?;
            match *slot {
                Slot::Position(a) => p[a] = v as f32,
                Slot::Normal(a) => n[a] = v as f32,
                Slot::Uv(a) => uv[a] = v as f32,
                Slot::Attribute(k) => extras[k] = attribute_value(ty, v),
                Slot::Indices | Slot::Skip => {}
            }
        }
        out.positions.push(Vec3::from(p));
        if normals {
            out.normals.push(Vec3::from(n));
        }
        if uvs {
            out.uvs.push(Vec2::from(uv));
        }
        out.vertex_extras.extend_from_slice(&extras);
    }
    out.vertex_fields = fields;
    Ok(())
}

/// A list length read as a number.
fn list_length(len: f64) -> Result<usize, String> {
    if len >= 0.0 && len <= u32::MAX as f64 {
        Ok(len as usize)
    } else {
        Err(format!("a list has length {len}"))
    }
}

fn read_faces(
    body: &mut Body,
    def: &ElementDef,
    capacity: usize,
    out: &mut Output,
) -> Result<(), String> {
    let (slots, fields) = slots(def, |p| match p.ty {
        PropertyType::List { item, .. } if is_face_geometry(&p.name) && item.is_integer() => {
            Some(Slot::Indices)
        }
        _ if is_face_geometry(&p.name) => Some(Slot::Skip),
        _ => None,
    });
    if !slots.contains(&Slot::Indices) {
        return Err("the faces have no integer vertex_indices list".into());
    }
    out.indices.reserve_exact(capacity);
    // faces usually follow the vertices: their indices are checked here, with the face's
    // number; otherwise once all is read (`finish`)
    let nv = if out.has_vertices { out.positions.len() } else { usize::MAX };
    out.indices_checked = out.has_vertices;
    let mut list = Vec::new();
    let mut face = Vec::new();
    let mut extras = vec![0f32; fields.len()];
    for f in 0..def.count {
        for (prop, slot) in def.properties.iter().zip(&slots) {
            match prop.ty {
                PropertyType::Scalar(ty) => {
                    let v = body.scalar(ty)?;
                    if let Slot::Attribute(k) = *slot {
                        extras[k] = attribute_value(ty, v);
                    }
                }
                PropertyType::List { count, item } => {
                    let len = list_length(body.scalar(count)?)?;
                    if *slot == Slot::Indices {
                        if !body.indices(item, len, &mut face)? {
                            return Err(format!("face {f} has a negative vertex index"));
                        }
                        if let Some(&bad) = face.iter().find(|&&i| i as usize >= nv) {
                            return Err(format!(
                                "face {f} refers to vertex {bad}, but there are only {nv} vertices"
                            ));
                        }
                    } else {
                        body.scalars(item, len, &mut list)?;
                    }
                }
            }
        }
        for k in 2..face.len() {
            out.indices.push([face[0], face[k - 1], face[k]]);
        }
        if !fields.is_empty() {
            out.face_extras.extend_from_slice(&extras);
            out.triangles_per_face.push(face.len().saturating_sub(2));
        }
    }
    out.face_fields = fields;
    Ok(())
}

fn skip_element(body: &mut Body, def: &ElementDef) -> Result<(), String> {
    let mut list = Vec::new();
    for _ in 0..def.count {
        for prop in &def.properties {
            match prop.ty {
                PropertyType::Scalar(ty) => {
                    body.scalar(ty)?;
                }
                PropertyType::List { count, item } => {
                    let len = list_length(body.scalar(count)?)?;
                    body.scalars(item, len, &mut list)?;
                }
            }
        }
    }
    Ok(())
}

fn finish(out: Output) -> Result<(MeshData, Vec<MeshAttributeData>), String> {
    if !out.has_vertices {
        return Err("no \"vertex\" element".into());
    }
    if !out.has_faces {
        return Err("no \"face\" element".into());
    }
    let nv = out.positions.len();
    let unchecked = if out.indices_checked { &[][..] } else { &out.indices[..] };
    if let Some(f) = unchecked.iter().position(|t| t.iter().any(|&i| i as usize >= nv)) {
        let bad = out.indices[f].iter().find(|&&i| i as usize >= nv).expect("found above");
        return Err(format!(
            "triangle {f} refers to vertex {bad}, but there are only {nv} vertices"
        ));
    }
    if out.indices.is_empty() {
        return Err("no triangles".into());
    }
    let mut attrs = Vec::new();
    if !out.vertex_fields.is_empty() {
        attrs.extend(attributes(
            AttributeScope::Vertex,
            &out.vertex_fields,
            &out.vertex_extras,
            |_| 1,
        ));
    }
    if !out.face_fields.is_empty() {
        let per_face = &out.triangles_per_face;
        attrs.extend(attributes(AttributeScope::Face, &out.face_fields, &out.face_extras, |f| {
            per_face[f]
        }));
    }
    let normals = (nv > 0 && out.normals.len() == nv).then_some(out.normals);
    let uvs = (nv > 0 && out.uvs.len() == nv).then_some(out.uvs);
    Ok((MeshData { positions: out.positions, normals, uvs, indices: out.indices }, attrs))
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

/// The attributes of `scope` from the elements' extra values (`extras`, `names.len()` per
/// element, in the order of `names`), with each element's values repeated `repeat(element)`
/// times.
fn attributes(
    scope: AttributeScope,
    names: &[String],
    extras: &[f32],
    repeat: impl Fn(usize) -> usize,
) -> Vec<MeshAttributeData> {
    let prefix = match scope {
        AttributeScope::Vertex => "vertex_",
        AttributeScope::Face => "face_",
    };
    let stride = names.len();
    group_fields(names)
        .into_iter()
        .map(|(name, fields)| {
            let mut values = Vec::new();
            for (e, x) in extras.chunks_exact(stride).enumerate() {
                for _ in 0..repeat(e) {
                    values.extend(fields.iter().map(|&k| x[k]));
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
        assert_eq!(attribute_value(Scalar::UChar, 200.0), 200.0);
        assert_eq!(attribute_value(Scalar::Float, 0.5), 0.5);
        // 100/127 read as sRGB: Mitsuba 3.9.1 stores 0.582694
        let c = attribute_value(Scalar::Char, 100.0);
        assert!((c - 0.582694).abs() < 1e-6, "{c}");
        // 1000/65535 on the linear segment of the sRGB curve
        let u = attribute_value(Scalar::UShort, 1000.0);
        assert!((u - 0.00118104).abs() < 1e-8, "{u}");
    }
}
