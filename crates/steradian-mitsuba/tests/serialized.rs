//! The `serialized` shape: the files in `tests/reference/serialized/` (written by
//! scripts/write_serialized.py, which also checks that Mitsuba 3.9.1 loads each as listed in
//! `expected.txt`) read as the generator wrote them, the loader's parameters are strict, and a
//! scene of serialized meshes renders as Mitsuba renders it (Mitsuba's Z-test rule).

use std::path::{Path, PathBuf};

use steradian::film::{read_exr, z_test};
use steradian::render::{render, RenderOptions};
use steradian::shape::read_serialized;
use steradian_mitsuba::{load_file, load_string, LoadError};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference").join(name)
}

/// Every (file, shape_index) of expected.txt: counts, attributes and position/index sums.
#[test]
fn files_read_as_the_generator_and_mitsuba_say() {
    let expected = std::fs::read_to_string(data("serialized/expected.txt")).unwrap();
    let mut checked = 0;
    for line in expected.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split_whitespace().collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let s = read_serialized(&data(&format!("serialized/{}", f[0])), f[1].parse().unwrap())
            .unwrap_or_else(|e| panic!("{e}"));
        let d = &s.data;
        assert_eq!(d.positions.len(), num(2) as usize, "{line}");
        assert_eq!(d.indices.len(), num(3) as usize, "{line}");
        assert_eq!(d.normals.is_some(), num(4) == 1.0, "{line}");
        assert_eq!(d.uvs.is_some(), num(5) == 1.0, "{line}");
        let p = |k: usize| d.positions.iter().map(|v| v[k] as f64).sum::<f64>();
        let weighted: f64 = d
            .positions
            .iter()
            .enumerate()
            .map(|(i, v)| i as f64 * (v.x as f64 + v.y as f64 + v.z as f64))
            .sum();
        let isum: u64 = d.indices.iter().flatten().map(|&i| i as u64).sum();
        let iweighted: u64 = d
            .indices
            .iter()
            .enumerate()
            .map(|(f, t)| f as u64 * t.iter().sum::<u32>() as u64)
            .sum();
        // positions are f32 in memory: sums agree to f32 rounding of each term
        for (got, want) in [(p(0), num(6)), (p(1), num(7)), (p(2), num(8)), (weighted, num(9))] {
            assert!(
                (got - want).abs() <= 1e-6 * (1.0 + want.abs()) * d.positions.len() as f64,
                "{line}: {got} vs {want}"
            );
        }
        assert_eq!((isum, iweighted), (num(10) as u64, num(11) as u64), "{line}");
        checked += 1;
    }
    assert_eq!(checked, 6);
}

/// A one-shape scene around `shape` (line 2 of bad.xml is the shape's first line).
fn load_shape(shape: &str) -> Result<steradian::render::Job, LoadError> {
    let xml = format!(
        "<scene version=\"3.0.0\">\n{shape}\n<integrator type=\"path\"/>\n\
         <sensor type=\"perspective\"/>\n</scene>"
    );
    load_string(&xml, Path::new("bad.xml"), &data(""), &[])
}

#[track_caller]
fn err_at(shape: &str, line: u32, col: u32, needles: &[&str]) {
    let e = match load_shape(shape) {
        Ok(_) => panic!("expected an error for {shape}"),
        Err(e) => e,
    };
    let pos = e.pos.as_ref().unwrap_or_else(|| panic!("no position in: {e}"));
    assert_eq!((pos.line, pos.col), (line, col), "wrong position in: {e}");
    for n in needles {
        assert!(e.message.contains(n), "{:?} does not contain {n:?}", e.message);
    }
}

#[test]
fn loader_parameters_are_strict() {
    let ok = "<shape type=\"serialized\"><string name=\"filename\" \
              value=\"serialized/two_v3.serialized\"/><integer name=\"shape_index\" value=\"1\"/>\
              <boolean name=\"face_normals\" value=\"true\"/>\
              <boolean name=\"flip_normals\" value=\"true\"/></shape>";
    load_shape(ok).unwrap();
    let file = "<shape type=\"serialized\">\n<string name=\"filename\" \
                value=\"serialized/two_v4.serialized\"/>\n";
    err_at(
        &format!("{file}<integer name=\"shape_index\" value=\"2\"/></shape>"),
        3,
        1,
        &["two_v4.serialized", "shape_index 2 is out of range", "2 shapes"],
    );
    err_at(
        &format!("{file}<integer name=\"shape_index\" value=\"-1\"/></shape>"),
        4,
        1,
        &["shape_index must be a non-negative"],
    );
    err_at(
        &format!("{file}<float name=\"shape_index\" value=\"1\"/></shape>"),
        4,
        1,
        &["shape_index"],
    );
    err_at(
        &format!("{file}<boolean name=\"flip_tex_coords\" value=\"true\"/></shape>"),
        4,
        1,
        &["flip_tex_coords"],
    );
    err_at(
        "<shape type=\"serialized\">\n<string name=\"filename\" value=\"serialized/expected.txt\"/></shape>",
        3,
        1,
        &["expected.txt", "format id 0x041C"],
    );
    err_at(
        "<shape type=\"serialized\">\n<string name=\"filename\" value=\"serialized/none\"/></shape>",
        3,
        1,
        &["cannot open serialized file", "none"],
    );
    err_at("<shape type=\"serialized\"/>", 2, 1, &["missing 'filename'"]);
}

/// serialized.xml: four serialized meshes (both versions, both precisions, shape_index 0 and
/// 1, file normals, computed smooth normals and face_normals) against Mitsuba 3.9.1 at 4096
/// spp (64 passes for the variance), by Mitsuba's own rule at 64 spp.
#[test]
fn serialized_scene_matches_mitsuba() {
    const SPP: u32 = 64;
    let scene = load_file(&data("serialized.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let out =
        render(&scene, &RenderOptions { spp: Some(SPP), seed: Some(1), ..Default::default() })
            .unwrap();
    assert_eq!(out.dropped_samples, 0);
    let img = out.film().develop();
    let reference = read_exr(&data("serialized-ref.exr")).unwrap();
    let variance = read_exr(&data("serialized-var.exr")).unwrap();
    let z = z_test(&img, SPP, &reference, &variance);
    eprintln!(
        "serialized @ {SPP} spp: {:.4} of {} pixels pass (min p {:.2e})",
        z.pass_fraction(),
        z.pixels,
        z.min_p
    );
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}
