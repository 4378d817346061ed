//! Purpose: a `spot` light's projected `texture` renders `reference/spot-texture.xml` as
//! Mitsuba 3.9.1 renders it (its Z-test rule, a 4096-spp `llvm_ad_rgb` reference): the image's
//! uv follows the light's frame and spans tan(cutoff) at unit distance; the same slide flipped
//! in v fails the test.

mod common;

use std::path::Path;

use common::{reference_scene as data, z_test_against};
use steradian::film::ZTest;
use steradian::render::Job;

const SPP: u32 = 64;

fn z(job: &Job, what: &str) -> ZTest {
    z_test_against(job, SPP, "spot-texture", what)
}

#[test]
fn projected_texture_matches_mitsuba() {
    let job = steradian_mitsuba::load_file(&data("spot-texture.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(z(&job, "spot texture").passes());
    let mean_z = common::image_mean_z(&job, SPP, "spot-texture", 4096);
    eprintln!("spot-texture image mean: z = {mean_z:.2}");
    assert!(mean_z < 4.0, "image mean off by {mean_z:.2} standard errors");
}

#[test]
fn a_flipped_slide_fails_the_test() {
    let xml = std::fs::read_to_string(data("spot-texture.xml")).unwrap();
    let xml = xml.replace(
        r#"<string name="filename" value="textures/wall.png"/>"#,
        r#"<string name="filename" value="textures/wall.png"/><transform name="to_uv"><scale y="-1"/></transform>"#,
    );
    let job = steradian_mitsuba::load_string(&xml, Path::new("flipped.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!z(&job, "spot texture flipped in v").passes());
}
