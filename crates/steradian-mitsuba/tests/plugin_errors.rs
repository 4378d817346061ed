//! Malformed scenes that parse as XML but that the plugin registry must reject: each error
//! names the problem in plain words, names the right file and line:column, and the loader
//! never panics.

mod common;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use steradian::testkit::{temp_dir, write_file};
use steradian_mitsuba::{load_file, load_string, LoadError};

/// Wraps scene-level elements: the first line of `body` is line 2 of the file.
fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>")
}

/// A scene with a working integrator (line 2) and sensor (line 3) before `body` (line 4 on).
fn full_scene(body: &str) -> String {
    scene(&format!("<integrator type=\"path\"/>\n<sensor type=\"perspective\"/>\n{body}"))
}

/// Loads `xml` as `bad.xml`, expecting an error and no panic.
#[track_caller]
fn err(xml: &str) -> LoadError {
    match catch_unwind(AssertUnwindSafe(|| {
        load_string(xml, Path::new("bad.xml"), Path::new("."), &[])
    })) {
        Ok(Ok(_)) => panic!("expected an error for:\n{xml}"),
        Ok(Err(e)) => e,
        Err(_) => panic!("the loader panicked on:\n{xml}"),
    }
}

/// The error is at `bad.xml:line:col` and its message contains every needle.
#[track_caller]
fn check(e: &LoadError, line: u32, col: u32, needles: &[&str]) {
    common::check_error(e, Path::new("bad.xml"), line, col, needles);
}

// ---------------------------------------------------------------------------------------------
// Unknown plugin types

#[test]
fn unknown_shape_type() {
    let e = err(&scene("<shape type=\"spheer\"/>"));
    check(&e, 2, 1, &["unknown shape plugin type 'spheer'", "sphere"]);
}

#[test]
fn unknown_bsdf_type() {
    check(
        &err(&scene("<bsdf type=\"polarizer\"/>")),
        2,
        1,
        &["the Mitsuba 3 bsdf plugin 'polarizer' is not supported by steradian", "diffuse"],
    );
    // Nested in a shape, and nested in a twosided BSDF.
    let xml = scene("<shape type=\"sphere\">\n  <bsdf type=\"plastik\"/>\n</shape>");
    check(&err(&xml), 3, 3, &["unknown bsdf plugin type 'plastik'"]);
    let xml = scene("<bsdf type=\"twosided\">\n    <bsdf type=\"conductr\"/>\n</bsdf>");
    check(&err(&xml), 3, 5, &["unknown bsdf plugin type 'conductr'"]);
}

/// Mitsuba 3 plugins steradian lacks are named as unsupported; misspellings stay unknown.
#[test]
fn mitsuba_plugins_steradian_lacks_are_unsupported_not_unknown() {
    for (tag, ty) in [
        ("bsdf", "measured_polarized"),
        ("bsdf", "polarizer"),
        ("emitter", "timed_sunsky"),
        ("integrator", "stokes"),
    ] {
        let e = err(&scene(&format!("<{tag} type=\"{ty}\"/>")));
        let want = format!("the Mitsuba 3 {tag} plugin '{ty}' is not supported by steradian");
        check(&e, 2, 1, &[&want]);
        assert!(!e.message.contains("unknown"), "{e}");
    }
}

#[test]
fn unknown_emitter_type() {
    check(
        &err(&scene("<emitter type=\"envmapp\"/>")),
        2,
        1,
        &["unknown emitter plugin type 'envmapp'", "constant", "envmap"],
    );
    let xml = scene("<shape type=\"sphere\">\n  <emitter type=\"point\"/>\n</shape>");
    check(
        &err(&xml),
        3,
        3,
        &["a shape can only carry an 'area' or 'directionalarea' emitter, not 'point'"],
    );
}

#[test]
fn unknown_sensor_type() {
    check(
        &err(&scene("<sensor type=\"distnat\"/>")),
        2,
        1,
        &["unknown sensor plugin type 'distnat'", "perspective", "distant"],
    );
}

#[test]
fn unknown_integrator_type() {
    check(
        &err(&scene("<integrator type=\"pathh\"/>")),
        2,
        1,
        &["unknown integrator plugin type 'pathh'", "path", "volpath"],
    );
}

#[test]
fn unknown_rfilter_film_and_sampler_types() {
    let xml = scene("<sensor type=\"perspective\">\n  <film type=\"hdrfilm\">\n    <rfilter type=\"sinc\"/>\n  </film>\n</sensor>");
    check(&err(&xml), 4, 5, &["unknown rfilter plugin type 'sinc'", "gaussian"]);
    let xml = scene("<sensor type=\"perspective\">\n  <sampler type=\"halton\"/>\n</sensor>");
    check(&err(&xml), 3, 3, &["unknown sampler plugin type 'halton'", "independent"]);
    let xml = scene("<sensor type=\"perspective\">\n  <film type=\"specfilm\"/>\n</sensor>");
    check(&err(&xml), 3, 3, &["the Mitsuba 3 film plugin 'specfilm' is not supported", "hdrfilm"]);
}

// ---------------------------------------------------------------------------------------------
// Unreferenced (unused) and mistyped parameters

#[test]
fn unused_parameter_on_a_shape() {
    let xml = scene("<shape type=\"sphere\">\n  <float name=\"radius\" value=\"1\"/>\n  <float name=\"radios\" value=\"2\"/>\n</shape>");
    check(&err(&xml), 4, 3, &["unreferenced property 'radios' in <shape type=\"sphere\">"]);
    // A rectangle has no radius.
    let xml = scene(
        "<shape type=\"rectangle\" id=\"r\">\n  <float name=\"radius\" value=\"2\"/>\n</shape>",
    );
    check(
        &err(&xml),
        3,
        3,
        &["unreferenced property 'radius' in <shape type=\"rectangle\" id=\"r\">"],
    );
}

#[test]
fn unused_parameter_on_a_bsdf() {
    let xml =
        scene("<bsdf type=\"diffuse\">\n  <rgb name=\"reflectence\" value=\"0.5\"/>\n</bsdf>");
    check(&err(&xml), 3, 3, &["unreferenced property 'reflectence' in <bsdf type=\"diffuse\">"]);
}

#[test]
fn unused_parameter_on_a_film() {
    let xml = scene("<sensor type=\"perspective\">\n  <film type=\"hdrfilm\">\n    <integer name=\"widht\" value=\"64\"/>\n  </film>\n</sensor>");
    check(&err(&xml), 4, 5, &["unreferenced property 'widht' in <film type=\"hdrfilm\">"]);
}

#[test]
fn unused_parameter_on_an_integrator() {
    let xml = scene(
        "<integrator type=\"path\">\n  <integer name=\"maxdepth\" value=\"4\"/>\n</integrator>",
    );
    check(&err(&xml), 3, 3, &["unreferenced property 'maxdepth' in <integrator type=\"path\">"]);
}

#[test]
fn unused_parameter_on_an_emitter() {
    // A point light takes an intensity, not a radiance.
    let xml = scene("<emitter type=\"point\">\n  <rgb name=\"radiance\" value=\"1\"/>\n</emitter>");
    check(&err(&xml), 3, 3, &["unreferenced property 'radiance' in <emitter type=\"point\">"]);
}

#[test]
fn mistyped_parameters() {
    let xml = scene(
        "<integrator type=\"path\">\n  <float name=\"max_depth\" value=\"8\"/>\n</integrator>",
    );
    check(
        &err(&xml),
        3,
        3,
        &["property 'max_depth' of <integrator type=\"path\"> must be integer, got float"],
    );
    let xml =
        scene("<sensor type=\"perspective\">\n    <string name=\"fov\" value=\"45\"/>\n</sensor>");
    check(
        &err(&xml),
        3,
        5,
        &["property 'fov' of <sensor type=\"perspective\"> must be float, got string"],
    );
    let xml = scene(
        "<shape type=\"sphere\">\n  <string name=\"flip_normals\" value=\"true\"/>\n</shape>",
    );
    check(
        &err(&xml),
        3,
        3,
        &["property 'flip_normals' of <shape type=\"sphere\"> must be boolean, got string"],
    );
}

// ---------------------------------------------------------------------------------------------
// Meshes: the error is in the scene file, at the filename, and names the mesh file.

/// Writes `mesh` (if any) as `dir/mesh_name` and a scene loading it with a `<shape type>`;
/// returns the scene path and the error. The `filename` property is at line 3, column 5.
fn mesh_err(
    test: &str,
    shape_type: &str,
    mesh_name: &str,
    mesh: Option<&[u8]>,
) -> (PathBuf, LoadError) {
    let dir = temp_dir(test);
    if let Some(bytes) = mesh {
        write_file(&dir, mesh_name, bytes);
    }
    let xml = format!(
        "<scene version=\"3.0.0\">\n<shape type=\"{shape_type}\">\n    <string name=\"filename\" value=\"{mesh_name}\"/>\n</shape>\n</scene>"
    );
    let path = write_file(&dir, "scene.xml", xml);
    let r = catch_unwind(AssertUnwindSafe(|| load_file(&path, &[])));
    match r {
        Ok(Ok(_)) => panic!("expected an error for {shape_type} {mesh_name}"),
        Ok(Err(e)) => (path, e),
        Err(_) => panic!("the loader panicked on {shape_type} {mesh_name}"),
    }
}

/// The error is at the `filename` property of [`mesh_err`]'s scene (line 3, column 5) and
/// its message contains every needle.
#[track_caller]
fn check_mesh(path: &Path, e: &LoadError, needles: &[&str]) {
    common::check_error(e, path, 3, 5, needles);
}

#[test]
fn mesh_file_missing() {
    let (path, e) = mesh_err("obj-missing", "obj", "nothere.obj", None);
    check_mesh(&path, &e, &["<shape type=\"obj\">", "cannot open OBJ file", "nothere.obj"]);
    let (path, e) = mesh_err("ply-missing", "ply", "nothere.ply", None);
    check_mesh(&path, &e, &["<shape type=\"ply\">", "cannot open PLY file", "nothere.ply"]);
}

/// Deterministic garbage, including invalid UTF-8 and NUL bytes.
fn garbage() -> Vec<u8> {
    let mut x = 0x9E37_79B9_7F4A_7C15u64;
    (0..4096)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

#[test]
fn mesh_file_corrupt() {
    let (path, e) = mesh_err("obj-garbage", "obj", "garbage.obj", Some(&garbage()));
    check_mesh(&path, &e, &["<shape type=\"obj\">", "OBJ file", "garbage.obj"]);
    let (path, e) = mesh_err("ply-garbage", "ply", "garbage.ply", Some(&garbage()));
    check_mesh(&path, &e, &["<shape type=\"ply\">", "PLY file", "garbage.ply", "header"]);
    let (path, e) = mesh_err("obj-empty", "obj", "empty.obj", Some(b""));
    check_mesh(&path, &e, &["empty.obj", "no triangles"]);
}

/// A binary little-endian PLY: 3 vertices (float x y z) and one triangle.
fn binary_ply() -> Vec<u8> {
    let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            b.extend(c.to_le_bytes());
        }
    }
    b.push(3);
    for i in [0i32, 1, 2] {
        b.extend(i.to_le_bytes());
    }
    b
}

#[test]
fn truncated_binary_ply() {
    let whole = binary_ply();
    // The whole file loads.
    let dir = temp_dir("ply-whole");
    write_file(&dir, "tri.ply", &whole);
    let ok = "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"ply\">\n<string name=\"filename\" value=\"tri.ply\"/>\n</shape>\n</scene>";
    load_file(&write_file(&dir, "ok.xml", ok), &[]).unwrap();
    // Cut inside the vertex data and inside the face list.
    let header_end = whole.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let (path, e) = mesh_err("ply-trunc-v", "ply", "cut.ply", Some(&whole[..header_end + 17]));
    check_mesh(&path, &e, &["cut.ply", "cannot read vertices"]);
    let (path, e) = mesh_err("ply-trunc-f", "ply", "cut.ply", Some(&whole[..whole.len() - 3]));
    check_mesh(&path, &e, &["cut.ply", "cannot read faces"]);
}

#[test]
fn face_index_out_of_range() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
    let (path, e) = mesh_err("obj-index", "obj", "bad.obj", Some(obj));
    check_mesh(&path, &e, &["bad.obj", "vertex"]);
    let ply = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
    let (path, e) = mesh_err("ply-index", "ply", "bad.ply", Some(ply));
    check_mesh(&path, &e, &["bad.ply", "face 0 refers to vertex 7, but there are only 3 vertices"]);
    let mut ply = binary_ply();
    let n = ply.len();
    ply[n - 4..].copy_from_slice(&(-5i32).to_le_bytes());
    let (path, e) = mesh_err("ply-negative", "ply", "neg.ply", Some(&ply));
    check_mesh(&path, &e, &["neg.ply", "negative vertex index"]);
}

#[test]
fn mesh_without_filename() {
    check(
        &err(&scene("<shape type=\"obj\"/>")),
        2,
        1,
        &["<shape type=\"obj\">: missing 'filename'"],
    );
    check(
        &err(&scene("<shape type=\"ply\" id=\"m\">\n</shape>")),
        2,
        1,
        &["<shape type=\"ply\" id=\"m\">: missing 'filename'"],
    );
}

// ---------------------------------------------------------------------------------------------
// Sensors and films

fn film_scene(props: &str) -> String {
    scene(&format!("<sensor type=\"perspective\">\n  <film type=\"hdrfilm\">\n    {props}\n  </film>\n</sensor>"))
}

/// An unknown `component_format` is named, once prefixed by the plugin, with the three
/// formats there are.
#[test]
fn film_component_format() {
    let e = err(&film_scene("<string name=\"component_format\" value=\"uint8\"/>"));
    check(
        &e,
        4,
        5,
        &["hdrfilm: unsupported component_format \"uint8\"", "\"float32\" or \"uint32\""],
    );
    assert!(!e.to_string().contains("hdrfilm: hdrfilm:"), "{e}");
}

#[test]
fn film_size() {
    check(
        &err(&film_scene("<integer name=\"width\" value=\"0\"/>")),
        4,
        5,
        &["'width' must be a positive integer, got 0"],
    );
    check(
        &err(&film_scene("<integer name=\"width\" value=\"-16\"/>")),
        4,
        5,
        &["'width' must be a positive integer, got -16"],
    );
    check(
        &err(&film_scene("<integer name=\"height\" value=\"0\"/>")),
        4,
        5,
        &["'height' must be a positive integer, got 0"],
    );
    let e = err(&film_scene("<integer name=\"width\" value=\"10000000\"/>"));
    check(&e, 3, 3, &["<film type=\"hdrfilm\">: film size 10000000x576 is too large"]);
    assert!(!e.message.contains("hdrfilm: hdrfilm"), "{e}");
}

fn sensor_scene(props: &str) -> String {
    scene(&format!("<sensor type=\"perspective\">\n    {props}\n</sensor>"))
}

#[test]
fn field_of_view_out_of_range() {
    for fov in ["0", "180", "-10", "270"] {
        let e = err(&sensor_scene(&format!("<float name=\"fov\" value=\"{fov}\"/>")));
        check(
            &e,
            3,
            5,
            &["<sensor type=\"perspective\">", "fov must lie strictly between 0 and 180 degrees"],
        );
    }
    check(
        &err(&sensor_scene("<string name=\"focal_length\" value=\"0mm\"/>")),
        3,
        5,
        &["focal_length must look like '50mm', got '0mm'"],
    );
}

#[test]
fn scaled_camera() {
    let xml = sensor_scene(
        "<transform name=\"to_world\">\n        <scale value=\"2\"/>\n    </transform>",
    );
    check(
        &err(&xml),
        3,
        5,
        &[
            "<sensor type=\"perspective\">",
            "scale factors in the camera's to_world are not allowed",
        ],
    );
}

#[test]
fn clip_planes_out_of_order() {
    // far_clip keeps its default (10000): the error is at the near_clip the scene set
    let e = err(&sensor_scene("<float name=\"near_clip\" value=\"20000\"/>"));
    check(&e, 3, 5, &["far_clip (10000) must exceed near_clip (20000)"]);
    let xml = sensor_scene(
        "<float name=\"near_clip\" value=\"2\"/>\n    <float name=\"far_clip\" value=\"1\"/>",
    );
    check(&err(&xml), 4, 5, &["far_clip (1) must exceed near_clip (2)"]);
}

#[test]
fn thinlens_without_aperture() {
    let e = err(&scene("<sensor type=\"thinlens\" id=\"cam\">\n  <float name=\"focus_distance\" value=\"3\"/>\n</sensor>"));
    check(&e, 2, 1, &["<sensor type=\"thinlens\" id=\"cam\">: missing 'aperture_radius'"]);
    let e = err(&scene(
        "<sensor type=\"thinlens\">\n  <float name=\"aperture_radius\" value=\"-0.1\"/>\n</sensor>",
    ));
    check(&e, 3, 3, &["aperture_radius must be non-negative, got -0.1"]);
}

#[test]
fn sensor_with_two_films() {
    let xml = scene("<sensor type=\"perspective\">\n  <film type=\"hdrfilm\"/>\n  <film type=\"hdrfilm\"/>\n</sensor>");
    check(&err(&xml), 4, 3, &["<sensor type=\"perspective\"> has more than one <film>"]);
}

// ---------------------------------------------------------------------------------------------
// Emitters

#[test]
fn area_emitter_at_scene_level() {
    let e =
        err(&scene("<emitter type=\"area\">\n  <rgb name=\"radiance\" value=\"1\"/>\n</emitter>"));
    check(&e, 2, 1, &["an 'area' emitter must be nested inside the <shape> that emits"]);
}

/// An area emitter declared with an id and referenced from a shape is that shape's light
/// (Mitsuba 3.9.1 renders it so); referenced from two shapes it is an error at the second
/// reference, as in Mitsuba ("an endpoint can only be attached to a single shape").
#[test]
fn area_emitter_referenced_from_shapes() {
    let light =
        "<emitter type=\"area\" id=\"e\">\n  <rgb name=\"radiance\" value=\"2\"/>\n</emitter>";
    let camera = r#"<integrator type="path"/><sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#;
    let sphere = r#"<shape type="sphere"><point name="center" x="0" y="0" z="5"/>"#;
    let nested = scene(&format!(
        "{camera}{sphere}<emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>"
    ));
    let referenced = scene(&format!("{camera}{light}{sphere}<ref id=\"e\"/></shape>"));
    let mean = |xml: &str| common::mean_and_error(xml, "scene.xml", 3).0;
    let (a, b) = (mean(&nested), mean(&referenced));
    assert!(a > 0.0 && a == b, "nested {a}, referenced {b}");

    let twice = full_scene(&format!(
        "{light}\n<shape type=\"sphere\">\n  <ref id=\"e\"/>\n</shape>\n<shape type=\"sphere\">\n  <ref id=\"e\"/>\n</shape>"
    ));
    check(
        &err(&twice),
        11,
        3,
        &["is already attached to the shape at bad.xml:8:3", "one shape only"],
    );
}

#[test]
fn spot_beam_wider_than_cutoff() {
    let xml = scene("<emitter type=\"spot\">\n  <float name=\"cutoff_angle\" value=\"20\"/>\n  <float name=\"beam_width\" value=\"30\"/>\n</emitter>");
    check(
        &err(&xml),
        4,
        3,
        &["<emitter type=\"spot\">", "beam_width must lie in (0°, cutoff_angle = 20°], got 30°"],
    );
    let xml = scene(
        "<emitter type=\"spot\">\n  <float name=\"cutoff_angle\" value=\"200\"/>\n</emitter>",
    );
    check(&err(&xml), 3, 3, &["cutoff_angle must lie in (0°, 180°], got 200°"]);
}

#[test]
fn negative_radiance() {
    let xml = scene("<shape type=\"sphere\">\n  <emitter type=\"area\">\n    <rgb name=\"radiance\" value=\"1, -1, 1\"/>\n  </emitter>\n</shape>");
    check(
        &err(&xml),
        4,
        5,
        &["<emitter type=\"area\">: 'radiance' must be finite and non-negative"],
    );
    let xml =
        scene("<emitter type=\"constant\">\n  <rgb name=\"radiance\" value=\"-2\"/>\n</emitter>");
    check(
        &err(&xml),
        3,
        3,
        &["<emitter type=\"constant\">: 'radiance' must be finite and non-negative"],
    );
    let xml =
        scene("<emitter type=\"point\">\n  <rgb name=\"intensity\" value=\"-1\"/>\n</emitter>");
    check(
        &err(&xml),
        3,
        3,
        &["<emitter type=\"point\">: 'intensity' must be finite and non-negative"],
    );
}

#[test]
fn two_constant_environments() {
    let xml = full_scene("<emitter type=\"constant\"/>\n<emitter type=\"constant\">\n  <rgb name=\"radiance\" value=\"2\"/>\n</emitter>");
    check(&err(&xml), 5, 1, &["only one environment emitter", "the first is at bad.xml:4:1"]);
}

// ---------------------------------------------------------------------------------------------
// Shapes, BSDFs, integrators, the scene

#[test]
fn shape_with_two_bsdfs() {
    let xml = scene("<bsdf type=\"diffuse\" id=\"white\"/>\n<shape type=\"cube\">\n  <ref id=\"white\"/>\n  <bsdf type=\"diffuse\"/>\n</shape>");
    check(&err(&xml), 5, 3, &["<shape type=\"cube\"> has more than one BSDF"]);
}

#[test]
fn twosided_with_three_bsdfs() {
    let xml = scene("<bsdf type=\"twosided\">\n  <bsdf type=\"diffuse\"/>\n  <bsdf type=\"diffuse\"/>\n  <bsdf type=\"diffuse\"/>\n</bsdf>");
    check(&err(&xml), 2, 1, &["twosided", "one or two nested BSDFs, got 3"]);
}

/// `twosided` around a BSDF that transmits is refused at the nested BSDF, as Mitsuba 3.9.1
/// refuses it ("only materials without a transmission component can be nested"); the
/// same list loads where Mitsuba loads it (a principled BSDF with `spec_trans` 0, a plastic).
#[test]
fn twosided_around_transmission() {
    let refused = [
        "<bsdf type=\"dielectric\"/>",
        "<bsdf type=\"thindielectric\"/>",
        "<bsdf type=\"roughdielectric\"/>",
        "<bsdf type=\"null\"/>",
        "<bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf>",
        "<bsdf type=\"principledthin\"/>",
        "<bsdf type=\"principled\"><float name=\"spec_trans\" value=\"0.5\"/></bsdf>",
        "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/><bsdf type=\"diffuse\"/><bsdf type=\"dielectric\"/></bsdf>",
    ];
    for inner in refused {
        let xml = scene(&format!("<bsdf type=\"twosided\">\n  {inner}\n</bsdf>"));
        check(&err(&xml), 3, 3, &["twosided:", "transmits light"]);
    }
    for inner in [
        "<bsdf type=\"principled\"><float name=\"spec_trans\" value=\"0\"/></bsdf>",
        "<bsdf type=\"principled\"/>",
        "<bsdf type=\"roughplastic\"/>",
    ] {
        let xml = full_scene(&format!("<bsdf type=\"twosided\" id=\"t\">{inner}</bsdf>"));
        load_string(&xml, Path::new("ok.xml"), Path::new("."), &[])
            .unwrap_or_else(|e| panic!("{inner}: {e}"));
    }
}

#[test]
fn negative_max_depth() {
    let xml = scene(
        "<integrator type=\"path\">\n  <integer name=\"max_depth\" value=\"-2\"/>\n</integrator>",
    );
    check(
        &err(&xml),
        3,
        3,
        &["<integrator type=\"path\">: max_depth must be -1 (unbounded) or >= 0, got -2"],
    );
    let xml = scene(
        "<integrator type=\"path\">\n  <integer name=\"rr_depth\" value=\"0\"/>\n</integrator>",
    );
    check(&err(&xml), 3, 3, &["<integrator type=\"path\">: 'rr_depth' must be at least 1"]);
}

#[test]
fn no_integrator() {
    let xml = scene("<sensor type=\"perspective\"/>\n<shape type=\"sphere\"/>");
    check(&err(&xml), 1, 1, &["the scene has no <integrator>"]);
}

#[test]
fn two_integrators() {
    let xml = scene("<integrator type=\"path\"/>\n  <integrator type=\"direct\"/>");
    check(&err(&xml), 3, 3, &["a scene has one integrator; the first is at bad.xml:2:1"]);
}

#[test]
fn unsupported_object_at_scene_level() {
    // (scene-level <texture>s and <medium>s are supported: they are referenced by id)
    let xml = full_scene("<phase type=\"hg\"/>");
    check(&err(&xml), 4, 1, &["<phase> objects are not supported at the scene level"]);
}

#[test]
fn well_formed_scene_loads() {
    // The helpers' baseline: the same frame as the cases, with nothing wrong, loads.
    let xml = full_scene("<shape type=\"sphere\"/>\n<emitter type=\"constant\"/>");
    load_string(&xml, Path::new("bad.xml"), Path::new("."), &[]).unwrap();
}

// ---------------------------------------------------------------------------------------------
// Physically impossible values

/// Negative or overflowing (infinite once in single precision) reflectances, transmittances,
/// conductor IORs and roughness are errors at the property; a reflectance above 1 loads, with a
/// located warning.
#[test]
fn impossible_albedos_and_iors_are_errors_and_energy_gain_a_warning() {
    let cases = [
        (r#"<bsdf type="diffuse"><rgb name="reflectance" value="-1e30"/></bsdf>"#, "reflectance"),
        (r#"<bsdf type="diffuse"><float name="reflectance" value="1e39"/></bsdf>"#, "reflectance"),
        (
            r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.5, -0.1, 0.5"/></bsdf>"#,
            "reflectance",
        ),
        (
            r#"<bsdf type="dielectric"><float name="specular_transmittance" value="-1"/></bsdf>"#,
            "specular_transmittance",
        ),
        (
            r#"<bsdf type="plastic"><rgb name="diffuse_reflectance" value="-0.5"/></bsdf>"#,
            "diffuse_reflectance",
        ),
        (
            r#"<bsdf type="conductor"><rgb name="eta" value="-1"/><rgb name="k" value="1"/></bsdf>"#,
            "eta",
        ),
        (r#"<bsdf type="roughconductor"><float name="alpha" value="1e39"/></bsdf>"#, "roughness"),
        (
            r#"<bsdf type="mask"><float name="opacity" value="-0.5"/><bsdf type="diffuse"/></bsdf>"#,
            "opacity",
        ),
    ];
    for (bsdf, needle) in cases {
        let xml = full_scene(&format!("<shape type=\"sphere\">{bsdf}</shape>"));
        let e = err(&xml);
        // at the property element (the second tag), or at the BSDF for the roughness
        let at = if needle == "roughness" { 0 } else { bsdf[1..].find('<').unwrap() + 1 };
        check(&e, 4, (at + 22) as u32, &[needle]);
    }
    let xml = full_scene(
        "<shape type=\"sphere\">\n<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"1.5, 0.5, 0.5\"/></bsdf></shape>",
    );
    let job = load_string(&xml, Path::new("bright.xml"), Path::new("."), &[]).unwrap();
    assert_eq!(job.warnings.len(), 1, "{:?}", job.warnings);
    let w = &job.warnings[0];
    assert!(w.starts_with("bright.xml:5:22: warning: ") && w.contains("above 1"), "{w}");
}

/// Mitsuba's sensor `shutter_open`/`shutter_close` and `hdrfilm`'s `compensate` are accepted
/// (they change nothing steradian renders); a shutter that closes before it opens is an error
/// at the property, as in Mitsuba.
#[test]
fn shutter_and_compensate_are_accepted_and_checked() {
    let sensor = |props: &str| {
        scene(&format!(
            "<integrator type=\"path\"/>\n<sensor type=\"perspective\">\n{props}\n\
             <film type=\"hdrfilm\"><boolean name=\"compensate\" value=\"true\"/></film>\n</sensor>"
        ))
    };
    let ok = |xml: &str| load_string(xml, Path::new("ok.xml"), Path::new("."), &[]).unwrap();
    ok(&sensor(
        "<float name=\"shutter_open\" value=\"0.5\"/><float name=\"shutter_close\" value=\"1.5\"/>",
    ));
    ok(&sensor(""));
    let e = err(&sensor(
        "<float name=\"shutter_open\" value=\"2\"/>\n<float name=\"shutter_close\" value=\"1\"/>",
    ));
    check(&e, 5, 1, &["the shutter must open", "shutter_close = 1"]);
    let e = err(&sensor("<float name=\"shutter_open\" value=\"1\"/>"));
    check(&e, 4, 1, &["shutter_open = 1", "shutter_close = 0"]);
}

/// `direct` takes `shading_samples` or the two per-technique counts, not both (as Mitsuba).
#[test]
fn direct_refuses_both_sample_counts() {
    let xml = scene(
        "<integrator type=\"direct\">\n<integer name=\"shading_samples\" value=\"2\"/>\n\
         <integer name=\"bsdf_samples\" value=\"1\"/>\n</integrator>\n<sensor type=\"perspective\"/>",
    );
    check(&err(&xml), 3, 1, &["give either 'shading_samples'", "not both"]);
}

/// A texture given for a value that cannot vary (a spot light's `intensity`) is reported as
/// such, as Mitsuba does ("cannot be spatially varying"), not as an unknown nested object; a
/// texture under a name the plugin does not know at all stays "unreferenced".
#[test]
fn texture_for_a_single_value_is_named_as_such() {
    let checkerboard = |name: &str| format!("<texture type=\"checkerboard\" name=\"{name}\"/>");
    let spot = |child: String| full_scene(&format!("<emitter type=\"spot\">\n{child}\n</emitter>"));
    let e = err(&spot(checkerboard("intensity")));
    check(
        &e,
        5,
        1,
        &[
            "'intensity' of <emitter type=\"spot\"> cannot be spatially varying",
            "rgb, spectrum or float",
        ],
    );
    let e = err(&spot(checkerboard("intensty")));
    check(&e, 5, 1, &["unreferenced object <texture type=\"checkerboard\""]);
    assert!(!e.message.contains("spatially"), "{e}");
}
