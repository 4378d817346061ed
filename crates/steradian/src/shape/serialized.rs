//! # `serialized`: Mitsuba's compressed binary triangle meshes
//!
//! Mitsuba plugin `serialized`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `filename` | string | — | path of the `.serialized` file |
//! | `shape_index` | integer | 0 ([`DEFAULT_SHAPE_INDEX`]) | which shape of a multi-shape file, ≥ 0 |
//! | `face_normals` | bool | false ([`DEFAULT_FACE_NORMALS`]) | flat shading: ignore the file's vertex normals |
//! | `flip_normals` | bool | false | flip geometric and shading normals (read for every shape) |
//! | `to_world` | transform | identity | object → world |
//!
//! These are all the parameters Mitsuba 3's plugin reads; anything else is an error.
//!
//! ## The format as steradian reads it
//!
//! Everything is little endian. A file is one or more shapes followed by a table:
//!
//! - per shape: `u16` format id `0x041C`, `u16` version (3 or 4), then one zlib stream holding
//!   - `u32` flags: `0x0001` vertex normals, `0x0002` texture coordinates, `0x0008` vertex
//!     colours, `0x0010` face normals, `0x1000` single, `0x2000` double precision;
//!   - version 4 only: the shape's name, UTF-8, NUL-terminated;
//!   - `u64` vertex count, `u64` triangle count;
//!   - positions (x y z per vertex), then, when flagged, normals (x y z), texture coordinates
//!     (u v) and colours (r g b), each as `f64` when `0x2000` is set, else `f32` (as in
//!     Mitsuba, a file with neither precision flag is read as single precision);
//!   - triangle indices (3 per triangle), `u32`.
//! - at the end: the byte offset of every shape (`u64` in version 4, `u32` in version 3; the
//!   first is 0), then the `u32` number of shapes.
//!
//! Shape 0 is read from the start of the file without consulting the table (as Mitsuba does,
//! so a file without one still loads); any other `shape_index` is looked up in the table, and
//! the header at that offset must repeat the file's format id and version. Each array is
//! decoded into its final form as the stream inflates (no per-vertex allocation, and no copy
//! of the whole inflated shape); the stream's Adler-32 checksum is verified. When the file has no normals and `face_normals` is false,
//! smooth angle-weighted vertex normals are computed, as in Mitsuba (see [`Mesh`](super::Mesh));
//! texture coordinates are used as stored (no v flip).
//!
//! ## Compared with Mitsuba 3
//!
//! - Vertex colours are skipped, as Mitsuba 3 does (it has no use for them either).
//! - The face-normals flag `0x0010` in a file is ignored, as Mitsuba 3.9.1 does (checked: such
//!   a mesh still gets smooth vertex normals); only the `face_normals` parameter counts.
//! - `u64` indices (which the format reserves for meshes of more than 2³² − 1 vertices, and
//!   which Mitsuba 3 does not read either) are refused with an error.
//! - A shape without triangles is refused (as `obj` and `ply` refuse one).
//! - Errors are clearer: a `shape_index` past the last shape names the file's shape count
//!   (Mitsuba 3 reports a failed 8-byte read, and reads garbage for `shape_index` equal to the
//!   count), and a truncated or corrupt file (bad checksum included), a wrong format id or
//!   version, or a table that does not fit the file is an error naming the file, never a
//!   crash.

use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

use glam::{Vec2, Vec3};

use super::{MeshData, ShapeError};

/// Mitsuba's default `shape_index`: the first shape of the file.
pub const DEFAULT_SHAPE_INDEX: u32 = 0;
/// Mitsuba's default `face_normals`: smooth shading.
pub const DEFAULT_FACE_NORMALS: bool = false;

/// The format id every shape header starts with.
pub const FORMAT_ID: u16 = 0x041C;

const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const DOUBLE_PRECISION: u32 = 0x2000;

/// Longest shape name accepted (bytes): a corrupt stream without a NUL ends here.
const MAX_NAME_BYTES: usize = 1 << 16;

/// zlib cannot expand data by more than about 1032:1 (a run of one byte in maximal-length
/// matches); a header that declares more data than that bound allows is corrupt, and is
/// refused before anything is allocated for it.
const MAX_INFLATE_RATIO: u64 = 1100;

/// One shape of a `.serialized` file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SerializedShape {
    /// The name stored with the shape (version 4; empty in version 3).
    pub name: String,
    /// Object-space mesh data (before `to_world`).
    pub data: MeshData,
}

/// Reads shape `shape_index` of a `.serialized` file.
pub fn read_serialized(path: &Path, shape_index: u32) -> Result<SerializedShape, ShapeError> {
    let file = File::open(path).map_err(|e| {
        ShapeError(format!("cannot open serialized file \"{}\": {e}", path.display()))
    })?;
    read_serialized_from(&mut BufReader::new(file), shape_index)
        .map_err(|m| ShapeError(format!("serialized file \"{}\": {m}", path.display())))
}

/// Reads shape `shape_index` of a `.serialized` file held by any seekable reader (a file, or
/// bytes in memory). Errors are messages without the file name.
pub fn read_serialized_from<R: Read + Seek>(
    r: &mut R,
    shape_index: u32,
) -> Result<SerializedShape, String> {
    let size = r.seek(SeekFrom::End(0)).map_err(|e| e.to_string())?;
    r.seek(SeekFrom::Start(0)).map_err(|e| e.to_string())?;
    let version = read_header(r, "the file")?;
    let mut start = 0u64;
    if shape_index != 0 {
        let count = {
            if size < 8 {
                return Err(format!("{size} bytes are too few for a shape table"));
            }
            r.seek(SeekFrom::End(-4)).map_err(|e| e.to_string())?;
            u32::from_le_bytes(read_array(r, "the shape count")?)
        };
        if shape_index >= count {
            return Err(format!(
                "shape_index {shape_index} is out of range: the file holds {count} shape{} \
                 (indices 0..={})",
                if count == 1 { "" } else { "s" },
                count.saturating_sub(1)
            ));
        }
        let entry: u64 = if version == 4 { 8 } else { 4 };
        let table = entry * count as u64 + 4;
        if table > size - 4 {
            return Err(format!(
                "the table of {count} shape offsets ({table} bytes) does not fit in the file \
                 ({size} bytes)"
            ));
        }
        r.seek(SeekFrom::Start(size - 4 - entry * (count - shape_index) as u64))
            .map_err(|e| e.to_string())?;
        start = if version == 4 {
            u64::from_le_bytes(read_array(r, "the shape table")?)
        } else {
            u32::from_le_bytes(read_array(r, "the shape table")?) as u64
        };
        if start >= size - table {
            return Err(format!(
                "shape {shape_index} starts at byte {start}, past the shape data ({} bytes)",
                size - table
            ));
        }
        r.seek(SeekFrom::Start(start)).map_err(|e| e.to_string())?;
        let v = read_header(r, &format!("shape {shape_index}"))?;
        if v != version {
            return Err(format!(
                "shape {shape_index} has version {v}, but the file starts with version {version}"
            ));
        }
    }
    read_shape(r, version, size - start, shape_index)
}

/// Reads and checks a shape header; returns the version.
fn read_header<R: Read>(r: &mut R, what: &str) -> Result<u16, String> {
    let h: [u8; 4] = read_array(r, &format!("the header of {what}"))?;
    let id = u16::from_le_bytes([h[0], h[1]]);
    let version = u16::from_le_bytes([h[2], h[3]]);
    if id != FORMAT_ID {
        return Err(format!(
            "{what} does not start with the serialized format id 0x{FORMAT_ID:04X} \
             (found 0x{id:04X})"
        ));
    }
    if version != 3 && version != 4 {
        return Err(format!("{what} has format version {version}; versions 3 and 4 are supported"));
    }
    Ok(version)
}

fn read_array<const N: usize, R: Read>(r: &mut R, what: &str) -> Result<[u8; N], String> {
    let mut b = [0u8; N];
    r.read_exact(&mut b).map_err(|e| io_message(e, what))?;
    Ok(b)
}

fn io_message(e: std::io::Error, what: &str) -> String {
    match e.kind() {
        std::io::ErrorKind::UnexpectedEof => format!("truncated: the file ends inside {what}"),
        _ => format!("cannot read {what}: {e} (corrupt compressed data?)"),
    }
}

/// Reads one shape's zlib stream; `r` is positioned right after the shape's header and
/// `available` bytes of the file remain from the header on.
fn read_shape<R: Read>(
    r: &mut R,
    version: u16,
    available: u64,
    index: u32,
) -> Result<SerializedShape, String> {
    let mut z = flate2::read::ZlibDecoder::new(r);
    let flags = u32::from_le_bytes(read_array(&mut z, &format!("shape {index}'s flags"))?);
    let mut name = Vec::new();
    if version == 4 {
        loop {
            let [c] = read_array(&mut z, &format!("shape {index}'s name"))?;
            if c == 0 {
                break;
            }
            if name.len() == MAX_NAME_BYTES {
                return Err(format!("shape {index}'s name is longer than {MAX_NAME_BYTES} bytes"));
            }
            name.push(c);
        }
    }
    let counts: [u8; 16] = read_array(&mut z, &format!("shape {index}'s counts"))?;
    let nv = u64::from_le_bytes(counts[..8].try_into().unwrap());
    let nf = u64::from_le_bytes(counts[8..].try_into().unwrap());
    if nv > u32::MAX as u64 {
        return Err(format!(
            "shape {index} has {nv} vertices; more than 2^32 - 1 (64-bit indices) is not supported"
        ));
    }
    if nf == 0 {
        return Err(format!("shape {index} has no triangles"));
    }
    let scalar: u64 = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let components = |flag: u32, n: u64| if flags & flag != 0 { n } else { 0 };
    let per_vertex =
        3 + components(HAS_NORMALS, 3) + components(HAS_TEXCOORDS, 2) + components(HAS_COLORS, 3);
    let needed = nv
        .checked_mul(per_vertex * scalar)
        .and_then(|v| nf.checked_mul(12).and_then(|f| v.checked_add(f)))
        .filter(|&n| n <= available.saturating_mul(MAX_INFLATE_RATIO))
        .ok_or_else(|| {
            format!(
                "shape {index} declares {nv} vertices and {nf} triangles, more than the file's \
                 {available} remaining bytes can hold (corrupt header?)"
            )
        })?;
    // each section is decoded straight into its final array as it inflates: no copy of the
    // whole inflated shape is ever held
    let nv = nv as usize;
    let double = scalar == 8;
    let mut section = Section { z: &mut z, index, needed };
    let s = scalar as usize;
    let positions = section.records(nv, 3 * s, |b| vec3(b, double))?;
    let normals = match flags & HAS_NORMALS {
        0 => None,
        _ => Some(section.records(nv, 3 * s, |b| vec3(b, double))?),
    };
    let uvs = match flags & HAS_TEXCOORDS {
        0 => None,
        _ => Some(section.records(nv, 2 * s, |b| vec2(b, double))?),
    };
    if flags & HAS_COLORS != 0 {
        section.records(nv, 3 * s, |_| ())?;
    }
    let indices = section.records(nf as usize, 12, |c| {
        let i = |k: usize| u32::from_le_bytes(c[k..k + 4].try_into().expect("12-byte records"));
        [i(0), i(4), i(8)]
    })?;
    // Reading on to the end of the stream makes the decoder check the Adler-32 checksum;
    // data after the arrays (none in files Mitsuba writes) is ignored, as Mitsuba does.
    let mut rest = [0u8; 64];
    loop {
        match z.read(&mut rest) {
            Ok(0) => break,
            Ok(_) => continue,
            Err(e) => return Err(io_message(e, &format!("the end of shape {index}'s stream"))),
        }
    }
    if let Some((f, bad)) = indices
        .iter()
        .enumerate()
        .find_map(|(f, t)| t.iter().find(|&&i| i as usize >= nv).map(|&i| (f, i)))
    {
        return Err(format!(
            "shape {index}: triangle {f} refers to vertex {bad}, but there are only {nv} vertices"
        ));
    }
    let name = String::from_utf8_lossy(&name).into_owned();
    Ok(SerializedShape { name, data: MeshData { positions, normals, uvs, indices } })
}

/// The inflated arrays of one shape, read in order.
struct Section<'a, R: Read> {
    z: &'a mut R,
    index: u32,
    /// Bytes all arrays take.
    needed: u64,
}

impl<R: Read> Section<'_, R> {
    /// The next `n` records of `size` bytes, each decoded by `decode`.
    fn records<T>(
        &mut self,
        n: usize,
        size: usize,
        decode: impl Fn(&[u8]) -> T,
    ) -> Result<Vec<T>, String> {
        const CHUNK_RECORDS: usize = 1 << 14;
        let mut out = Vec::with_capacity(n);
        let mut buf = vec![0u8; size * CHUNK_RECORDS.min(n)];
        let mut left = n;
        while left > 0 {
            let k = left.min(CHUNK_RECORDS);
            let bytes = &mut buf[..k * size];
            self.z.read_exact(bytes).map_err(|e| {
                if e.kind() == std::io::ErrorKind::UnexpectedEof {
                    format!(
                        "truncated: shape {} holds fewer than the {} bytes its arrays need",
                        self.index, self.needed
                    )
                } else {
                    io_message(e, &format!("shape {}'s data", self.index))
                }
            })?;
            out.extend(bytes.chunks_exact(size).map(&decode));
            left -= k;
        }
        Ok(out)
    }
}

fn scalar_at(bytes: &[u8], k: usize, double: bool) -> f32 {
    if double {
        f64::from_le_bytes(bytes[8 * k..8 * k + 8].try_into().expect("sized record")) as f32
    } else {
        f32::from_le_bytes(bytes[4 * k..4 * k + 4].try_into().expect("sized record"))
    }
}

fn vec3(bytes: &[u8], double: bool) -> Vec3 {
    Vec3::new(scalar_at(bytes, 0, double), scalar_at(bytes, 1, double), scalar_at(bytes, 2, double))
}

fn vec2(bytes: &[u8], double: bool) -> Vec2 {
    Vec2::new(scalar_at(bytes, 0, double), scalar_at(bytes, 1, double))
}

#[cfg(test)]
mod tests {
    use std::io::{Cursor, Write};

    use super::*;
    use crate::geometry::Transform;
    use crate::sampling::Pcg32;
    use crate::shape::Mesh;

    /// A test shape: a square pyramid (5 vertices, 6 triangles) written with the given
    /// options.
    #[derive(Clone, Copy)]
    struct Spec {
        normals: bool,
        uvs: bool,
        colors: bool,
        double: bool,
        name: &'static str,
        scale: f32,
    }

    const PYRAMID: [[f32; 3]; 5] =
        [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    const PYRAMID_FACES: [[u32; 3]; 6] =
        [[0, 2, 1], [0, 3, 2], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];

    fn stream(version: u16, s: &Spec) -> Vec<u8> {
        let mut flags = if s.double { 0x2000 } else { 0x1000 };
        flags |= (s.normals as u32) | (s.uvs as u32) << 1 | (s.colors as u32) << 3;
        let mut body = flags.to_le_bytes().to_vec();
        if version == 4 {
            body.extend_from_slice(s.name.as_bytes());
            body.push(0);
        }
        body.extend_from_slice(&5u64.to_le_bytes());
        body.extend_from_slice(&6u64.to_le_bytes());
        let put = |body: &mut Vec<u8>, x: f32| {
            if s.double {
                body.extend_from_slice(&(x as f64).to_le_bytes())
            } else {
                body.extend_from_slice(&x.to_le_bytes())
            }
        };
        for p in PYRAMID {
            p.iter().for_each(|&x| put(&mut body, x * s.scale));
        }
        if s.normals {
            for p in PYRAMID {
                Vec3::from(p).normalize().to_array().iter().for_each(|&x| put(&mut body, x));
            }
        }
        if s.uvs {
            for p in PYRAMID {
                [0.5 + 0.5 * p[0], 0.5 + 0.25 * p[1]].iter().for_each(|&x| put(&mut body, x));
            }
        }
        if s.colors {
            for _ in PYRAMID {
                [0.1, 0.2, 0.3].iter().for_each(|&x| put(&mut body, x));
            }
        }
        for f in PYRAMID_FACES {
            f.iter().for_each(|i| body.extend_from_slice(&i.to_le_bytes()));
        }
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(&body).unwrap();
        let mut out = FORMAT_ID.to_le_bytes().to_vec();
        out.extend_from_slice(&version.to_le_bytes());
        out.extend_from_slice(&z.finish().unwrap());
        out
    }

    fn file(version: u16, shapes: &[Spec]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut offsets = Vec::new();
        for s in shapes {
            offsets.push(out.len() as u64);
            out.extend_from_slice(&stream(version, s));
        }
        for o in &offsets {
            if version == 4 {
                out.extend_from_slice(&o.to_le_bytes());
            } else {
                out.extend_from_slice(&(*o as u32).to_le_bytes());
            }
        }
        out.extend_from_slice(&(offsets.len() as u32).to_le_bytes());
        out
    }

    fn read(bytes: &[u8], index: u32) -> Result<SerializedShape, String> {
        read_serialized_from(&mut Cursor::new(bytes), index)
    }

    const PLAIN: Spec =
        Spec { normals: false, uvs: false, colors: false, double: false, name: "", scale: 1.0 };

    #[test]
    fn reads_every_layout_of_both_versions() {
        for version in [3, 4] {
            for bits in 0..16u32 {
                let s = Spec {
                    normals: bits & 1 != 0,
                    uvs: bits & 2 != 0,
                    colors: bits & 4 != 0,
                    double: bits & 8 != 0,
                    name: "pyramid",
                    scale: 1.0,
                };
                let got = read(&file(version, &[s]), 0).unwrap();
                let d = &got.data;
                assert_eq!(got.name, if version == 4 { "pyramid" } else { "" });
                assert_eq!(d.positions, PYRAMID.map(Vec3::from).to_vec());
                assert_eq!(d.indices, PYRAMID_FACES.to_vec());
                assert_eq!(d.normals.is_some(), bits & 1 != 0);
                if let Some(n) = &d.normals {
                    assert!((n[4] - Vec3::Z).length() < 1e-7 && (n[0].length() - 1.0).abs() < 1e-6);
                }
                assert_eq!(
                    d.uvs.as_ref().map(|u| u[1]),
                    (bits & 2 != 0).then_some(Vec2::new(1.0, 0.25))
                );
            }
        }
    }

    #[test]
    fn shape_index_selects_a_shape_through_the_table() {
        for version in [3, 4] {
            let shapes = [
                Spec { name: "a", ..PLAIN },
                Spec { name: "b", scale: 2.0, double: true, ..PLAIN },
                Spec { name: "c", scale: 3.0, uvs: true, ..PLAIN },
            ];
            let bytes = file(version, &shapes);
            for (i, s) in shapes.iter().enumerate() {
                let got = read(&bytes, i as u32).unwrap();
                assert_eq!(got.data.positions[1], Vec3::new(s.scale, -s.scale, 0.0));
                if version == 4 {
                    assert_eq!(got.name, s.name);
                }
            }
            let e = read(&bytes, 3).unwrap_err();
            assert!(e.contains("shape_index 3 is out of range") && e.contains("3 shapes"), "{e}");
        }
        // Mesh built from it: flat and smooth shading, to_world applied.
        let d = read(&file(4, &[PLAIN]), 0).unwrap().data;
        let m = Mesh::from_data(d.clone(), &Transform::translate(Vec3::Z), false, true).unwrap();
        assert!(m.normals.is_none() && m.positions[4] == Vec3::new(0.0, 0.0, 2.0));
        let m = Mesh::from_data(d, &Transform::IDENTITY, false, false).unwrap();
        assert!(m.normals.as_ref().unwrap()[4].abs_diff_eq(Vec3::Z, 1e-6));
    }

    #[test]
    fn bad_headers_and_tables_are_clear_errors() {
        let good = file(4, &[PLAIN, PLAIN]);
        let mut b = good.clone();
        b[0] = 0x1D;
        assert!(read(&b, 0).unwrap_err().contains("format id 0x041C (found 0x041D)"));
        let mut b = good.clone();
        b[2] = 5;
        assert!(read(&b, 0).unwrap_err().contains("format version 5"));
        // the second shape's header claims version 3 in a version-4 file
        let second = stream(4, &PLAIN).len();
        let mut b = good.clone();
        b[second + 2] = 3;
        assert!(read(&b, 1).unwrap_err().contains("has version 3"));
        // a table entry pointing past the data
        let mut b = good.clone();
        let at = b.len() - 12;
        b[at..at + 8].copy_from_slice(&1_000_000u64.to_le_bytes());
        assert!(read(&b, 1).unwrap_err().contains("starts at byte 1000000"));
        // a shape count that the file cannot hold
        let mut b = good.clone();
        let at = b.len() - 4;
        b[at..].copy_from_slice(&1_000_000u32.to_le_bytes());
        assert!(read(&b, 1).unwrap_err().contains("does not fit"));
        // a shape without triangles
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(&[0, 0x10, 0, 0, 0]).unwrap();
        z.write_all(&[0; 16]).unwrap();
        let mut b = vec![0x1C, 0x04, 4, 0];
        b.extend_from_slice(&z.finish().unwrap());
        assert!(read(&b, 0).unwrap_err().contains("no triangles"));
        assert!(read(&[0x1C], 0).unwrap_err().contains("truncated"));
    }

    /// Every truncation of a file and random byte changes in it give errors, never a panic
    /// (and never a huge allocation: counts are checked against the file size first).
    #[test]
    fn truncated_and_corrupted_files_are_errors_not_panics() {
        let spec = Spec { normals: true, uvs: true, colors: true, name: "fuzz", ..PLAIN };
        for version in [3, 4] {
            let good = file(version, &[spec, spec]);
            let first = stream(version, &spec).len();
            for len in 0..good.len() {
                let r0 = read(&good[..len], 0);
                let r1 = read(&good[..len], 1);
                // shape 0 needs its whole stream, shape 1 needs the table
                assert_eq!(r0.is_err(), len < first, "version {version}, {len} bytes: {r0:?}");
                assert!(r1.is_err(), "version {version}, {len} bytes");
            }
            let original = read(&good, 0).unwrap();
            let mut rng = Pcg32::new(7, version as u64);
            for _ in 0..2000 {
                let mut b = good.clone();
                let at = (rng.next_u32() as usize) % first;
                b[at] ^= 1 + (rng.next_u32() % 255) as u8;
                // a change in the stream fails the checksum or the inflater, one in the
                // header the id/version check (4 → 3 reads the name as counts, which fails);
                // only the unused padding bits of the last deflate byte may change freely
                if let Ok(s) = read(&b, 0) {
                    assert_eq!(s, original, "version {version}: byte {at} changed the data");
                }
                // the table is read for shape 1: any byte of the file may be changed
                let mut b = good.clone();
                let at = (rng.next_u32() as usize) % b.len();
                b[at] ^= 1 + (rng.next_u32() % 255) as u8;
                if let Ok(s) = read(&b, 1) {
                    let _ = Mesh::from_data(s.data, &Transform::IDENTITY, false, false);
                }
            }
        }
    }
}
