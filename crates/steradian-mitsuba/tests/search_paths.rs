//! Purpose: file names in a scene are found where Mitsuba 3 finds them: in the `<path>` folders
//! (the last declared first) and the main scene's folder, from the main file and from included
//! fragments in other folders alike; bad `<path>`s are located errors. `reference/search/`
//! (a `<path>`, a fragment in `parts/` naming `meshes/box.obj`, `<rotate>`s about non-unit
//! axes) renders as Mitsuba 3.9.1 renders it.

mod common;

use std::fs;
use std::path::Path;

use common::check_error;
use steradian::testkit::{temp_dir, write_file};

/// An OBJ of `n` triangles (told apart by their count once loaded).
fn obj(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        let x = i as f32;
        s += &format!("v {x} 0 0\nv {} 0 0\nv {x} 1 0\n", x + 1.0);
    }
    for i in 0..n {
        s += &format!("f {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
    s
}

/// A fragment to include: no integrator of its own.
fn fragment(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n")
}

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n<integrator type=\"path\"/>\n</scene>\n")
}

/// Triangles of the scene's first shape.
fn triangles(path: &Path) -> u32 {
    let job = steradian_mitsuba::load_file(path, &[]).unwrap_or_else(|e| panic!("{e}"));
    job.scene.shapes.iter().map(|s| s.prim_count()).sum()
}

#[test]
fn path_folders_are_searched_last_declared_first() {
    let dir = temp_dir("search-paths-order");
    for (sub, n) in [("a", 1), ("b", 2)] {
        fs::create_dir_all(dir.join(sub)).unwrap();
        write_file(&dir.join(sub), "m.obj", obj(n));
    }
    let shape = r#"<shape type="obj"><string name="filename" value="m.obj"/></shape>"#;
    let p = write_file(&dir, "s1.xml", scene(&format!("<path value=\"a\"/>\n{shape}")));
    assert_eq!(triangles(&p), 1);
    let p = write_file(
        &dir,
        "s2.xml",
        scene(&format!("<path value=\"a\"/>\n<path value=\"b\"/>\n{shape}")),
    );
    assert_eq!(triangles(&p), 2, "the last <path> is searched first");
    // a plugin's file is looked up after the whole file is read (Mitsuba builds plugins last)
    let p = write_file(&dir, "s3.xml", scene(&format!("{shape}\n<path value=\"b\"/>")));
    assert_eq!(triangles(&p), 2);
    // absolute folders too
    let abs = dir.join("a");
    let p =
        write_file(&dir, "s4.xml", scene(&format!("<path value=\"{}\"/>\n{shape}", abs.display())));
    assert_eq!(triangles(&p), 1);
}

/// A fragment in `parts/` names `meshes/m.obj`, which lies beside the main scene: Mitsuba
/// resolves it against the scene's folder, not the fragment's.
#[test]
fn an_included_fragment_finds_files_beside_the_main_scene() {
    let dir = temp_dir("search-paths-include");
    fs::create_dir_all(dir.join("parts")).unwrap();
    fs::create_dir_all(dir.join("meshes")).unwrap();
    write_file(&dir.join("meshes"), "m.obj", obj(3));
    write_file(
        &dir.join("parts"),
        "geometry.xml",
        fragment(r#"<shape type="obj"><string name="filename" value="meshes/m.obj"/></shape>"#),
    );
    let p = write_file(&dir, "main.xml", scene(r#"<include filename="parts/geometry.xml"/>"#));
    assert_eq!(triangles(&p), 3);
    // an <include> itself is looked up in the <path> folders
    let p = write_file(
        &dir,
        "main2.xml",
        scene("<path value=\"parts\"/>\n<include filename=\"geometry.xml\"/>"),
    );
    assert_eq!(triangles(&p), 3);
    // and a fragment's own folder still serves as the last resort
    write_file(&dir.join("parts"), "local.obj", obj(4));
    write_file(
        &dir.join("parts"),
        "local.xml",
        fragment(r#"<shape type="obj"><string name="filename" value="local.obj"/></shape>"#),
    );
    let p = write_file(&dir, "main3.xml", scene(r#"<include filename="parts/local.xml"/>"#));
    assert_eq!(triangles(&p), 4);
}

#[test]
fn bad_paths_are_located_errors() {
    let dir = temp_dir("search-paths-errors");
    let p = write_file(&dir, "missing.xml", scene(r#"<path value="nowhere"/>"#));
    let e = steradian_mitsuba::load_file(&p, &[]).unwrap_err();
    check_error(&e, &p, 2, 1, &["<path>", "nowhere", "not found"]);
    let p =
        write_file(&dir, "nested.xml", scene(r#"<shape type="sphere"><path value="."/></shape>"#));
    let e = steradian_mitsuba::load_file(&p, &[]).unwrap_err();
    check_error(&e, &p, 2, 22, &["<path>", "root"]);
    let p = write_file(&dir, "attr.xml", scene(r#"<path value="." name="x"/>"#));
    let e = steradian_mitsuba::load_file(&p, &[]).unwrap_err();
    check_error(&e, &p, 2, 17, &["unexpected attribute 'name'"]);
}

/// Against Mitsuba at 4096 spp (64 passes for the variance), at 64 spp; the two rotations about
/// non-unit axes are each warned about once, at their `<rotate>`.
#[test]
fn search_scene_matches_mitsuba() {
    const SPP: u32 = 64;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference");
    let job = steradian_mitsuba::load_file(&dir.join("search/scene.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(job.warnings.len(), 2, "{:?}", job.warnings);
    for (w, line) in job.warnings.iter().zip(["objects.xml:11:13", "objects.xml:23:13"]) {
        assert!(w.contains(line) && w.contains("not normalise"), "{w}");
    }
    let z = common::z_test_against(&job, SPP, "search", "search");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// The same scene with the two `<rotate>` axes normalised (a rotation, not Mitsuba's
/// matrix) fails the test: the objects sit elsewhere.
#[test]
fn normalised_axes_fail_the_test() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/search");
    let dir = temp_dir("search-normalised");
    for sub in ["parts", "meshes", "assets"] {
        fs::create_dir_all(dir.join(sub)).unwrap();
    }
    for f in ["scene.xml", "meshes/box.obj", "assets/tetra.obj"] {
        fs::copy(src.join(f), dir.join(f)).unwrap();
    }
    let fragment = fs::read_to_string(src.join("parts/objects.xml")).unwrap();
    let fragment = fragment
        .replace(r#"x="1" y="1" z="0""#, r#"x="0.70710678" y="0.70710678" z="0""#)
        .replace(r#"x="0" y="2" z="0.5""#, r#"x="0" y="0.97014250" z="0.24253563""#);
    write_file(&dir.join("parts"), "objects.xml", fragment);
    let job = steradian_mitsuba::load_file(&dir.join("scene.xml"), &[]).unwrap();
    assert!(job.warnings.is_empty(), "{:?}", job.warnings);
    assert!(!common::z_test_against(&job, 64, "search", "search, axes normalised").passes());
}
