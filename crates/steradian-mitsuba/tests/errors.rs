//! Malformed inputs: each error names the problem and the right line:column.

mod common;

use std::path::{Path, PathBuf};

use steradian::testkit::{temp_dir, write_file};
use steradian_mitsuba::{parse_file, parse_string, LoadError, ObjectTag};

fn err(xml: &str) -> LoadError {
    err_with(xml, &[])
}

fn err_with(xml: &str, defines: &[(&str, &str)]) -> LoadError {
    let d: Vec<(String, String)> =
        defines.iter().map(|(a, b)| (a.to_string(), b.to_string())).collect();
    match parse_string(xml, Path::new("."), &d) {
        Ok(_) => panic!("expected an error for:\n{xml}"),
        Err(e) => e,
    }
}

/// The error of a scene given as a string is at `<string>:line:col` and names `needle`.
#[track_caller]
fn check(e: &LoadError, line: u32, col: u32, needle: &str) {
    common::check_error(e, Path::new("<string>"), line, col, &[needle]);
}

#[test]
fn missing_version() {
    check(&err("<scene>\n</scene>"), 1, 1, "missing version attribute");
}

#[test]
fn wrong_version_string() {
    check(
        &err("<scene version=\"3.0\">\n</scene>"),
        1,
        8,
        "could not parse version number \"3.0\"",
    );
    check(&err("<scene version=\"three\"/>"), 1, 8, "could not parse version number");
}

#[test]
fn unknown_tag() {
    check(
        &err("<scene version=\"3.0.0\">\n  <shap type=\"sphere\"/>\n</scene>"),
        2,
        3,
        "unexpected tag <shap>",
    );
}

#[test]
fn unknown_plugin_attribute() {
    check(
        &err("<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\" colour=\"red\"/>\n</scene>"),
        2,
        22,
        "unexpected attribute 'colour' in <bsdf>",
    );
}

#[test]
fn float_given_for_integer() {
    let xml = "<scene version=\"3.0.0\">\n<integrator type=\"path\">\n    <float name=\"max_depth\" value=\"8\"/>\n</integrator>\n</scene>";
    let s = parse_string(xml, Path::new("."), &[]).unwrap();
    let integ = &s.children_of(ObjectTag::Integrator)[0].node;
    let e = integ.props.get_int("max_depth").unwrap_err();
    check(
        &e,
        3,
        5,
        "property 'max_depth' of <integrator type=\"path\"> must be integer, got float",
    );
}

#[test]
fn integer_must_be_integral() {
    let xml = "<scene version=\"3.0.0\">\n<integrator type=\"path\">\n<integer name=\"max_depth\" value=\"1.5\"/>\n</integrator>\n</scene>";
    check(&err(xml), 3, 27, "could not parse integer value \"1.5\"");
}

#[test]
fn unparsable_number() {
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<float name=\"radius\" value=\"1.0x\"/>\n</shape>\n</scene>";
    check(&err(xml), 3, 22, "could not parse floating point value \"1.0x\"");
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<boolean name=\"flip_normals\" value=\"yes\"/>\n</shape>\n</scene>";
    check(&err(xml), 3, 30, "could not parse boolean value \"yes\"");
}

#[test]
fn undefined_parameter() {
    let xml = "<scene version=\"3.0.0\">\n<sampler type=\"independent\">\n<integer name=\"sample_count\" value=\"$spp\"/>\n</sampler>\n</scene>";
    check(&err(xml), 3, 30, "undefined parameter '$spp'");
}

#[test]
fn unused_define() {
    let xml = "<scene version=\"3.0.0\">\n<default name=\"spp\" value=\"4\"/>\n</scene>";
    check(&err_with(xml, &[("sp", "8")]), 1, 1, "unused parameter 'sp'");
    // A used define is fine, declared or not.
    let xml = "<scene version=\"3.0.0\">\n<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$n\"/></sampler>\n</scene>";
    parse_string(xml, Path::new("."), &[("n".into(), "3".into())]).unwrap();
}

#[test]
fn dangling_ref() {
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n    <ref id=\"nothing\"/>\n</shape>\n</scene>";
    check(&err(xml), 3, 5, "reference to unknown id \"nothing\"");
}

#[test]
fn duplicate_id() {
    let xml = "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"diffuse\" id=\"a\"/>\n</scene>";
    check(&err(xml), 3, 1, "duplicate id \"a\" (first defined at 2:1)");
}

#[test]
fn reference_cycle() {
    let xml = "<scene version=\"3.0.0\">\n<bsdf type=\"twosided\" id=\"a\">\n  <ref id=\"a\"/>\n</bsdf>\n</scene>";
    check(&err(xml), 3, 3, "reference cycle");
}

#[test]
fn nan_in_matrix() {
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"cube\">\n<transform name=\"to_world\">\n  <matrix value=\"1 0 0 0 0 1 0 0 0 0 nan 0 0 0 0 1\"/>\n</transform>\n</shape>\n</scene>";
    check(&err(xml), 4, 11, "NaN or infinite value \"nan\"");
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"cube\">\n<transform name=\"to_world\">\n  <matrix value=\"1 0 0 0 0 1 0 0 0 0 1 0\"/>\n</transform>\n</shape>\n</scene>";
    check(&err(xml), 4, 3, "16 (4×4) or 9 (3×3) numbers, got 12");
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"cube\">\n<transform name=\"to_world\">\n  <matrix value=\"1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1\"/>\n</transform>\n</shape>\n</scene>";
    check(&err(xml), 4, 3, "<matrix> is singular");
}

#[test]
fn zero_scale() {
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"cube\">\n<transform name=\"to_world\">\n  <translate x=\"1\"/>\n  <scale y=\"0\"/>\n</transform>\n</shape>\n</scene>";
    check(&err(xml), 5, 3, "singular (a scale factor is zero)");
}

#[test]
fn lookat_up_parallel_to_direction() {
    let xml = "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<transform name=\"to_world\">\n    <lookat origin=\"0, 0, 0\" target=\"0, 2, 0\" up=\"0, 1, 0\"/>\n</transform>\n</sensor>\n</scene>";
    check(&err(xml), 4, 5, "'up' is parallel to the viewing direction");
}

#[test]
fn missing_name() {
    let xml = "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n<rgb value=\"0.5\"/>\n</bsdf>\n</scene>";
    check(&err(xml), 3, 1, "missing attribute 'name' in <rgb>");
}

#[test]
fn duplicate_property() {
    let xml = "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"0.5\"/>\n<texture name=\"reflectance\" type=\"checkerboard\"/>\n</bsdf>\n</scene>";
    check(
        &err(xml),
        4,
        1,
        "property 'reflectance' is specified twice in <bsdf type=\"diffuse\"> (first at 3:1)",
    );
}

#[test]
fn include_of_missing_file() {
    let xml =
        "<scene version=\"3.0.0\">\n\n   <include filename=\"does/not/exist.xml\"/>\n</scene>";
    check(&err(xml), 3, 4, "included file \"./does/not/exist.xml\" not found");
}

#[test]
fn include_cycle() {
    let dir = temp_dir("include-cycle");
    let a = write_file(
        &dir,
        "a.xml",
        "<scene version=\"3.0.0\">\n  <include filename=\"b.xml\"/>\n</scene>",
    );
    write_file(&dir, "b.xml", "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\"/>\n<include filename=\"a.xml\"/>\n</scene>");
    let e = parse_file(&a, &[]).unwrap_err();
    let pos = e.pos.clone().unwrap();
    assert_eq!(*pos.file, dir.join("b.xml"), "{e}");
    assert_eq!((pos.line, pos.col), (3, 1), "{e}");
    assert!(e.message.contains("include cycle"), "{e}");
}

#[test]
fn malformed_xml() {
    let e = err("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>");
    let pos = e.pos.clone().unwrap();
    assert_eq!(pos.line, 3, "{e}");
    assert!(e.message.contains("malformed XML"), "{e}");
    let e = parse_file(&PathBuf::from("/nonexistent/scene.xml"), &[]).unwrap_err();
    assert!(e.message.contains("cannot read scene file"), "{e}");
}

#[test]
fn unreferenced_property() {
    let xml = "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n  <rgb name=\"reflectance\" value=\"0.5\"/>\n  <float name=\"foo\" value=\"1\"/>\n</bsdf>\n</scene>";
    let s = parse_string(xml, Path::new("."), &[]).unwrap();
    let b = &s.children[0].node;
    b.props.get_spectrum("reflectance").unwrap();
    check(
        &b.check_all_used().unwrap_err(),
        4,
        3,
        "unreferenced property 'foo' in <bsdf type=\"diffuse\">",
    );
    b.props.get_float("foo").unwrap();
    b.check_all_used().unwrap();
}

#[test]
fn unreferenced_child_object() {
    let xml = "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\" id=\"d\"/>\n<shape type=\"sphere\">\n <ref id=\"d\"/>\n</shape>\n</scene>";
    let s = parse_string(xml, Path::new("."), &[]).unwrap();
    let shape = &s.children[1].node;
    check(
        &shape.check_all_used().unwrap_err(),
        4,
        2,
        "unreferenced object <bsdf type=\"diffuse\" id=\"d\"> in <shape type=\"sphere\">",
    );
}

#[test]
fn structural_errors() {
    check(
        &err("<scene version=\"3.0.0\">\n<translate x=\"1\"/>\n</scene>"),
        2,
        1,
        "can only occur inside <transform>",
    );
    check(
        &err("<scene version=\"3.0.0\">\n<shape type=\"cube\"><transform name=\"to_world\">\n<float name=\"x\" value=\"1\"/></transform></shape>\n</scene>"),
        3,
        1,
        "can only contain transform operations",
    );
    check(&err("<scene version=\"3.0.0\">\n<float name=\"x\" value=\"1\"><rgb name=\"y\" value=\"1\"/></float>\n</scene>"), 2, 27, "<rgb> cannot occur inside <float>");
    check(
        &err("<scene version=\"3.0.0\">\n<bsdf id=\"x\"/>\n</scene>"),
        2,
        1,
        "missing attribute 'type' in <bsdf>",
    );
    check(&err("<bsdf type=\"diffuse\" version=\"3.0.0\"/>"), 1, 1, "root element must be <scene>");
    check(
        &err("<scene version=\"3.0.0\">\n<point name=\"p\" x=\"1\" y=\"2\"/>\n</scene>"),
        2,
        1,
        "missing attribute 'z' in <point>",
    );
    check(
        &err("<scene version=\"3.0.0\">\n<rgb name=\"c\" value=\"1 2\"/>\n</scene>"),
        2,
        15,
        "one or three values, got 2",
    );
    check(&err("<scene version=\"3.0.0\">\n<rotate/>\n</scene>"), 2, 1, "inside <transform>");
    check(&err("<scene version=\"3.0.0\">\nhello\n</scene>"), 1, 24, "unexpected text \"hello\"");
    check(
        &err("<scene version=\"3.0.0\">\n<bsdf type=\"d\"><spectrum name=\"r\" value=\"500:1, 400:2\"/></bsdf>\n</scene>"),
        2,
        35,
        "strictly increasing",
    );
    check(&err("<scene version=\"3.0.0\">\n<bsdf type=\"d\"><spectrum name=\"r\" filename=\"a.spd\"/></bsdf>\n</scene>"), 2, 35, "cannot read spectrum file");
}
