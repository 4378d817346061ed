//! Purpose: `mesh_attribute` textures read PLY vertex and face attributes as Mitsuba 3.9.1 does:
//! `reference/mesh-attribute.xml` (float vertex colours in a scene-level BSDF shared by two
//! spheres, float face colours and a face scalar driving a conductor's roughness, uchar face
//! colours and a ushort vertex weight on the floor) passes Mitsuba's Z-test against a 4096-spp
//! `llvm_ad_rgb` reference; reading the face colours where the vertex colours belong, or
//! normalising the uchar colours, fails it; bad uses are refused at the texture.

mod common;

use std::path::Path;

use common::{check_error, reference_scene as data, z_test_against};

const SPP: u32 = 64;

fn scene_with(from: &str, to: &str) -> steradian::render::Job {
    common::reference_scene_with("mesh-attribute.xml", from, to)
}

#[test]
fn mesh_attributes_match_mitsuba() {
    let job = steradian_mitsuba::load_file(&data("mesh-attribute.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(z_test_against(&job, SPP, "mesh-attribute", "mesh_attribute").passes());
}

#[test]
fn face_colours_for_vertex_colours_fail_the_test() {
    let job = scene_with(
        "<string name=\"name\" value=\"vertex_color\"/>",
        "<string name=\"name\" value=\"face_c_color\"/>",
    );
    assert!(!z_test_against(&job, SPP, "mesh-attribute", "face colours on the spheres").passes());
}

#[test]
fn uchar_colours_taken_as_normalised_fail_the_test() {
    // Mitsuba stores uchar attributes as they are (0..255); dividing them by 255 once more
    // is what a loader normalising them on read would render
    let job = scene_with("value=\"0.0039215686\"", "value=\"0.0000153787\"");
    assert!(!z_test_against(&job, SPP, "mesh-attribute", "normalised uchar colours").passes());
}

fn load_err(shape: &str) -> steradian_mitsuba::LoadError {
    let dir = data("");
    let xml = format!("<scene version=\"3.0.0\">\n{shape}\n</scene>");
    steradian_mitsuba::load_string(&xml, Path::new("attr.xml"), &dir, &[]).unwrap_err()
}

#[test]
fn unknown_names_list_the_mesh_attributes() {
    let e = load_err(
        "<shape type=\"ply\"><string name=\"filename\" value=\"mesh_attribute/sphere.ply\"/>\n\
         <bsdf type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\">\n\
         <string name=\"name\" value=\"vertex_colour\"/></texture></bsdf></shape>",
    );
    check_error(
        &e,
        Path::new("attr.xml"),
        4,
        1,
        &[
            "no attribute \"vertex_colour\"",
            "\"vertex_color\"",
            "\"face_c_color\"",
            "\"face_weight\"",
        ],
    );
}

#[test]
fn three_channels_for_a_scalar_parameter_are_refused() {
    let e = load_err(
        "<shape type=\"ply\"><string name=\"filename\" value=\"mesh_attribute/sphere.ply\"/>\n\
         <bsdf type=\"roughconductor\">\n<texture type=\"mesh_attribute\" name=\"alpha\">\n\
         <string name=\"name\" value=\"face_c_color\"/></texture></bsdf></shape>",
    );
    check_error(&e, Path::new("attr.xml"), 4, 1, &["'alpha' is a single number", "3 channels"]);
}

#[test]
fn names_without_a_scope_and_uses_outside_a_mesh_bsdf_are_refused() {
    let e = load_err(
        "<shape type=\"ply\"><string name=\"filename\" value=\"mesh_attribute/sphere.ply\"/>\n\
         <bsdf type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\">\n\
         <string name=\"name\" value=\"color\"/></texture></bsdf></shape>",
    );
    check_error(&e, Path::new("attr.xml"), 4, 1, &["must start with \"vertex_\" or \"face_\""]);
    let e = load_err(
        "<shape type=\"ply\"><string name=\"filename\" value=\"mesh_attribute/sphere.ply\"/>\n\
         <emitter type=\"area\"><texture type=\"mesh_attribute\" name=\"radiance\">\n\
         <string name=\"name\" value=\"vertex_color\"/></texture></emitter></shape>",
    );
    check_error(&e, Path::new("attr.xml"), 3, 22, &["no mesh attributes here", "emitter"]);
    let e = load_err(
        "<shape type=\"sphere\">\n\
         <bsdf type=\"diffuse\"><texture type=\"mesh_attribute\" name=\"reflectance\">\n\
         <string name=\"name\" value=\"vertex_color\"/></texture></bsdf></shape>",
    );
    check_error(&e, Path::new("attr.xml"), 4, 1, &["the mesh has no attributes"]);
}

/// A polygon's face attribute holds on each of its fan triangles.
#[test]
fn polygon_face_attributes_cover_every_triangle() {
    let dir = steradian::testkit::temp_dir("mesh-attribute-quads");
    let ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n\
               property float z\nelement face 2\nproperty list uchar int vertex_indices\n\
               property float k_0\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n\
               4 0 1 2 3 0.25\n3 1 4 2 0.75\n";
    let path = steradian::testkit::write_file(&dir, "quads.ply", ply);
    let (data, attrs) = steradian::shape::read_ply_with_attributes(&path).unwrap();
    assert_eq!(data.indices.len(), 3);
    assert_eq!(attrs.len(), 1);
    assert_eq!(attrs[0].name, "face_k");
    assert_eq!(attrs[0].values, vec![0.25, 0.25, 0.75]);
}
