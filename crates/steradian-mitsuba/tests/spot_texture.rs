//! Purpose: a `spot` light's projected `texture` renders `reference/spot-texture.xml` as
//! Mitsuba 3.9.1 renders it (its Z-test rule, a 4096-spp `llvm_ad_rgb` reference): the image's
//! uv follows the light's frame and spans tan(cutoff) at unit distance; the same slide flipped
//! in v fails the test.

use std::path::{Path, PathBuf};

use steradian::film::{read_exr, z_test, ZTest};
use steradian::render::{render, Job, RenderOptions};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference").join(name)
}

const SPP: u32 = 64;

fn z(job: &Job, what: &str) -> ZTest {
    let out = render(job, &RenderOptions { spp: Some(SPP), seed: Some(1), ..Default::default() })
        .unwrap();
    assert_eq!(out.dropped_samples, 0);
    let img = out.film.develop();
    let mean = read_exr(&data("spot-texture-ref.exr")).unwrap();
    let var = read_exr(&data("spot-texture-var.exr")).unwrap();
    let z = z_test(&img, SPP, &mean, &var);
    eprintln!(
        "{what} @ {SPP} spp: {:.4} of {} pixels pass (min p {:.2e})",
        z.pass_fraction(),
        z.pixels,
        z.min_p
    );
    z
}

#[test]
fn projected_texture_matches_mitsuba() {
    let job = steradian_mitsuba::load_file(&data("spot-texture.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(z(&job, "spot texture").passes());
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
