//! OBJ and PLY reader tests (files written into a temporary directory).

use glam::{Vec2, Vec3};

use super::*;
use crate::geometry::Transform;
use crate::testkit::{temp_dir, write_file};

/// Every triangle corner of `d` maps a position to the expected uv.
fn corner_uvs(d: &MeshData) -> Vec<(Vec3, Vec2)> {
    let uvs = d.uvs.as_ref().unwrap();
    d.indices.iter().flatten().map(|&i| (d.positions[i as usize], uvs[i as usize])).collect()
}

#[test]
fn obj_quads_with_per_corner_uvs_and_normals() {
    let dir = temp_dir("shape-obj-quads-with-per-corner-uvs-and-normals");
    let src = "# quad split across two faces with different uvs at shared positions\n\
        v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
        vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.25\n\
        vn 0 0 1\n\
        f 1/1/1 2/2/1 3/3/1\n\
        f 1/5/1 3/3/1 4/4/1\n";
    let p = write_file(&dir, "corners.obj", src.as_bytes());
    let d = read_obj(&p, false, VertexNormals::Read).unwrap();
    assert_eq!(d.indices.len(), 2);
    assert!(d.normals.as_ref().unwrap().iter().all(|&n| n == Vec3::Z));
    let c = corner_uvs(&d);
    let expect = [
        (Vec3::ZERO, Vec2::new(0.0, 0.0)),
        (Vec3::X, Vec2::new(1.0, 0.0)),
        (Vec3::new(1.0, 1.0, 0.0), Vec2::new(1.0, 1.0)),
        (Vec3::ZERO, Vec2::new(0.5, 0.25)),
        (Vec3::new(1.0, 1.0, 0.0), Vec2::new(1.0, 1.0)),
        (Vec3::Y, Vec2::new(0.0, 1.0)),
    ];
    assert_eq!(c, expect);
    // flip_tex_coords (Mitsuba's default): v → 1 − v
    let d = read_obj(&p, true, VertexNormals::Read).unwrap();
    assert_eq!(corner_uvs(&d)[3], (Vec3::ZERO, Vec2::new(0.5, 0.75)));

    // a quad face (triangulated), no normals: smooth normals are computed by Mesh
    let src = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
    let d =
        read_obj(&write_file(&dir, "quad.obj", src.as_bytes()), true, VertexNormals::Read).unwrap();
    assert_eq!(d.indices.len(), 2);
    assert!(d.normals.is_none() && d.uvs.is_none());
    let m = Mesh::from_data(d, &Transform::translate(Vec3::Z), false, false).unwrap();
    assert!((m.surface_area() - 4.0).abs() < 1e-6);
    assert!(m.normals.as_ref().unwrap().iter().all(|&n| (n - Vec3::Z).length() < 1e-6));
    assert!(m.positions.iter().all(|p| p.z == 1.0));
}

#[test]
fn obj_errors() {
    let dir = temp_dir("shape-obj-errors");
    let missing = dir.join("missing.obj");
    let e = read_obj(&missing, true, VertexNormals::Read).unwrap_err();
    assert!(e.to_string().contains("cannot open"), "{e}");
    let garbage: Vec<u8> =
        (0..4096u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8).collect();
    assert!(
        read_obj(&write_file(&dir, "garbage.obj", &garbage), true, VertexNormals::Read).is_err()
    );
    assert!(read_obj(
        &write_file(&dir, "empty.obj", b"# nothing\nv 0 0 0\n"),
        true,
        VertexNormals::Read
    )
    .is_err());
    assert!(read_obj(
        &write_file(&dir, "range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
        true,
        VertexNormals::Read
    )
    .is_err());
    assert!(read_obj(
        &write_file(&dir, "bad.obj", b"v 0 0 zero\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        true,
        VertexNormals::Read
    )
    .is_err());
}

/// Faces of which only some give vertex normals (or uvs): an error that says so and names the way out
/// (Mitsuba 3.9.1 gives the others zero normals, which render black); with `face_normals`
/// the file's normals are ignored and the mesh loads, flat.
#[test]
fn obj_with_normals_or_uvs_on_some_faces_only() {
    let dir = temp_dir("obj_partial_normals");
    let src = b"v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvn 0 1 0\nf 1//1 2//1 3//1\nf 1 3 4\n";
    let p = write_file(&dir, "partial.obj", src);
    let e = read_obj(&p, true, VertexNormals::Read).unwrap_err();
    assert!(e.0.contains("some faces give vertex normals (vn) and others do not"), "{}", e.0);
    assert!(e.0.contains("face_normals"), "{}", e.0);
    let d = read_obj(&p, true, VertexNormals::Ignore).unwrap();
    assert_eq!((d.indices.len(), d.normals.is_none()), (2, true));
    // the same for texture coordinates (Mitsuba 3.9.1 leaves the others' undefined)
    let src =
        b"v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\nf 1 3 4\n";
    let e =
        read_obj(&write_file(&dir, "partial_uv.obj", src), true, VertexNormals::Read).unwrap_err();
    assert!(e.0.contains("some faces give texture coordinates (vt) and others do not"), "{}", e.0);
}

const TET_ASCII: &str = "ply\nformat ascii 1.0\ncomment test\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
property float s\nproperty float t\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n0 0 1 0.5 0.5\n4 0 1 2 3\n3 0 1 4\n";

#[test]
fn ply_ascii_with_polygons() {
    let dir = temp_dir("shape-ply-ascii-with-polygons");
    let d = read_ply(&write_file(&dir, "a.ply", TET_ASCII.as_bytes())).unwrap();
    assert_eq!(d.positions.len(), 5);
    assert_eq!(d.indices, vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]]);
    assert!(d.normals.is_none());
    assert_eq!(d.uvs.as_ref().unwrap()[4], Vec2::new(0.5, 0.5));
}

fn binary_ply(big_endian: bool) -> Vec<u8> {
    let fmt = if big_endian { "binary_big_endian" } else { "binary_little_endian" };
    let mut out = format!(
        "ply\nformat {fmt} 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n\
element material 1\nproperty uchar id\n\
element face 1\nproperty list uchar uint vertex_index\nend_header\n"
    )
    .into_bytes();
    let f64b =
        |v: f64| if big_endian { v.to_be_bytes().to_vec() } else { v.to_le_bytes().to_vec() };
    let f32b =
        |v: f32| if big_endian { v.to_be_bytes().to_vec() } else { v.to_le_bytes().to_vec() };
    let u32b =
        |v: u32| if big_endian { v.to_be_bytes().to_vec() } else { v.to_le_bytes().to_vec() };
    for (p, uv) in [
        ([0.0, 0.0, 2.0], [0.0, 0.0]),
        ([3.0, 0.0, 2.0], [1.0, 0.0]),
        ([0.0, 3.0, 2.0], [0.0, 1.0]),
    ] {
        for c in p {
            out.extend(f64b(c));
        }
        for c in [0.0f32, 0.0, 1.0] {
            out.extend(f32b(c));
        }
        for c in uv {
            out.extend(f32b(c));
        }
    }
    out.push(7); // material id
    out.push(3);
    for i in [0u32, 1, 2] {
        out.extend(u32b(i));
    }
    out
}

#[test]
fn ply_binary_with_normals_and_uvs() {
    let dir = temp_dir("shape-ply-binary-with-normals-and-uvs");
    for be in [false, true] {
        let d = read_ply(&write_file(&dir, &format!("b{be}.ply"), binary_ply(be))).unwrap();
        assert_eq!(
            d.positions,
            vec![Vec3::new(0.0, 0.0, 2.0), Vec3::new(3.0, 0.0, 2.0), Vec3::new(0.0, 3.0, 2.0)]
        );
        assert_eq!(d.normals.as_ref().unwrap(), &vec![Vec3::Z; 3]);
        assert_eq!(d.uvs.as_ref().unwrap()[1], Vec2::new(1.0, 0.0));
        assert_eq!(d.indices, vec![[0, 1, 2]]);
        let m = Mesh::from_data(d, &Transform::IDENTITY, false, false).unwrap();
        assert!((m.surface_area() - 4.5).abs() < 1e-6);
    }
}

/// Less common binary layouts: big-endian `ushort` counts with `short` indices, `int8` and
/// `float64` aliases, a list property among the vertex's (skipped), an element between the
/// vertices and the faces, polygons, and a face attribute; read as their ASCII twin reads.
#[test]
fn ply_binary_layouts_read_as_ascii() {
    let dir = temp_dir("shape-ply-binary-layouts-read-as-ascii");
    let header = |format: &str| {
        format!(
            "ply\nformat {format} 1.0\nelement vertex 4\nproperty float64 x\nproperty float y\n\
property list uchar int8 tags\nproperty float z\nelement edge 1\nproperty int a\nproperty int b\n\
element face 2\nproperty list ushort short vertex_indices\nproperty uchar q_0\nend_header\n"
        )
    };
    let ascii = header("ascii")
        + "0 0 2 5 -1 0\n1 0 0 1\n1 1 1 7 1\n0 1 0 1\n0 1\n4 0 1 2 3 9\n3 3 2 1 200\n";
    let mut big = header("binary_big_endian").into_bytes();
    for (x, y, tags, z) in [
        (0.0f64, 0.0f32, &[5i8, -1][..], 0.0f32),
        (1.0, 0.0, &[], 1.0),
        (1.0, 1.0, &[7], 1.0),
        (0.0, 1.0, &[], 1.0),
    ] {
        big.extend(x.to_be_bytes());
        big.extend(y.to_be_bytes());
        big.push(tags.len() as u8);
        big.extend(tags.iter().map(|&t| t as u8));
        big.extend(z.to_be_bytes());
    }
    big.extend(0i32.to_be_bytes());
    big.extend(1i32.to_be_bytes());
    for (face, q) in [(&[0i16, 1, 2, 3][..], 9u8), (&[3, 2, 1], 200)] {
        big.extend((face.len() as u16).to_be_bytes());
        for &i in face {
            big.extend(i.to_be_bytes());
        }
        big.push(q);
    }
    let (a, a_attrs) =
        read_ply_with_attributes(&write_file(&dir, "a.ply", ascii.as_bytes())).unwrap();
    let (b, b_attrs) = read_ply_with_attributes(&write_file(&dir, "b.ply", &big)).unwrap();
    assert_eq!(a, b);
    assert_eq!(a.indices, vec![[0, 1, 2], [0, 2, 3], [3, 2, 1]]);
    assert_eq!(a.positions[2], Vec3::new(1.0, 1.0, 1.0));
    assert_eq!(a_attrs, b_attrs);
    // the face attribute holds for each triangle of its polygon
    let q = a_attrs.iter().find(|x| x.name == "face_q").unwrap();
    assert_eq!(q.values, vec![9.0, 9.0, 200.0]);
    // a list count beyond the file is an error, not an allocation
    let mut huge = big.clone();
    let at = huge.len() - 1 - 2 * 3 - 2;
    huge[at..at + 2].copy_from_slice(&u16::MAX.to_be_bytes());
    let e = read_ply(&write_file(&dir, "huge.ply", &huge)).unwrap_err();
    assert!(e.to_string().contains("ends early"), "{e}");
}

#[test]
fn ply_errors_never_panic() {
    let dir = temp_dir("shape-ply-errors-never-panic");
    let missing = dir.join("missing.ply");
    assert!(read_ply(&missing).unwrap_err().to_string().contains("cannot open"));
    let full = binary_ply(false);
    // truncated at every length after the header and inside it
    for cut in [1usize, 10, 60, full.len() - 40, full.len() - 5, full.len() - 1] {
        assert!(read_ply(&write_file(&dir, "trunc.ply", &full[..cut])).is_err(), "cut at {cut}");
    }
    let garbage: Vec<u8> =
        (0..4096u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8).collect();
    assert!(read_ply(&write_file(&dir, "garbage.ply", &garbage)).is_err());
    let mut g2 = b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty float x\nproperty float y\nproperty float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    g2.extend_from_slice(&garbage);
    assert!(read_ply(&write_file(&dir, "garbage2.ply", &g2)).is_err());
    let range = TET_ASCII.replace("3 0 1 4", "3 0 1 9");
    let e = read_ply(&write_file(&dir, "range.ply", range.as_bytes())).unwrap_err();
    assert!(e.to_string().contains("vertex 9"), "{e}");
    let neg = TET_ASCII.replace("3 0 1 4", "3 0 1 -4");
    assert!(read_ply(&write_file(&dir, "neg.ply", neg.as_bytes())).is_err());
    let noz = TET_ASCII.replace("property float z\n", "");
    assert!(read_ply(&write_file(&dir, "noz.ply", noz.as_bytes())).is_err());
    // faces before the vertices: their indices are checked once the vertices are read
    let early = "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n\
element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n\
3 0 1 9\n0 0 0\n1 0 0\n0 1 0\n";
    let e = read_ply(&write_file(&dir, "early.ply", early.as_bytes())).unwrap_err();
    assert!(e.to_string().contains("vertex 9"), "{e}");
    let good = early.replace("3 0 1 9", "3 0 1 2");
    assert_eq!(
        read_ply(&write_file(&dir, "early.ply", good.as_bytes())).unwrap().indices,
        vec![[0, 1, 2]]
    );
    let nofaces = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
    assert!(read_ply(&write_file(&dir, "nofaces.ply", nofaces.as_bytes())).is_err());
}
