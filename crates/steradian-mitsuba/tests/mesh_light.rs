//! Purpose: an area light on a mesh emits on the side of its shading (vertex) normals, as
//! Mitsuba 3.9.1's does, also where the file's triangles are wound the other way:
//! `reference/mesh-light-normals.xml` (a smooth sphere wound inwards with outward normals)
//! passes Mitsuba's render-test rule against its 4096-spp `llvm_ad_rgb` reference; with
//! `face_normals` (the winding decides, inwards) the light goes dark and fails. The light
//! tracer (`ptracer`) starts its paths on the same side and passes against Mitsuba's `ptracer`
//! reference of the scene (`mesh-light-normals-ptracer`).

mod common;

use common::{reference_scene as data, z_test_against};

const SPP: u32 = 64;

fn load_with(defaults: &[(&str, &str)]) -> steradian::render::Job {
    let d: Vec<(String, String)> =
        defaults.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    steradian_mitsuba::load_file(&data("mesh-light-normals.xml"), &d)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn load(face_normals: &str) -> steradian::render::Job {
    load_with(&[("face_normals", face_normals)])
}

#[test]
fn a_mesh_light_emits_on_its_shading_normals_side() {
    let z = z_test_against(&load("false"), SPP, "mesh-light-normals", "mesh light");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn with_face_normals_the_winding_decides() {
    let z = z_test_against(&load("true"), SPP, "mesh-light-normals", "mesh light, face normals");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn the_light_tracer_starts_on_the_shading_normals_side() {
    let job = load_with(&[("integrator", "ptracer")]);
    let z = z_test_against(&job, SPP, "mesh-light-normals-ptracer", "mesh light, ptracer");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}
