//! Purpose: the `null` BSDF renders `reference/null.xml` as Mitsuba 3.9.1's `path` renders it
//! (its Z-test rule, a 4096-spp `llvm_ad_rgb` reference): null spheres are invisible to camera
//! rays but stop shadow rays, and an emitter with a null BSDF shows its emission; the same
//! scene with the null spheres made diffuse fails the test; `null` takes no parameters.

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
    let mean = read_exr(&data("null-ref.exr")).unwrap();
    let var = read_exr(&data("null-var.exr")).unwrap();
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
fn null_scene_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("null.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!(z(&job, "null").passes());
}

#[test]
fn visible_spheres_fail_the_test() {
    let xml = std::fs::read_to_string(data("null.xml")).unwrap();
    let grey = r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>"#;
    let xml = xml.replace(
        r#"<float name="radius" value="0.35"/>
        <bsdf type="null"/>"#,
        &format!("<float name=\"radius\" value=\"0.35\"/>{grey}"),
    );
    let job = steradian_mitsuba::load_string(&xml, Path::new("visible.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!z(&job, "a diffuse sphere for a null one").passes());
}

#[test]
fn null_takes_no_parameters() {
    let xml = "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sphere\">\n\
               <bsdf type=\"null\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf>\n</shape>\n</scene>";
    let e =
        steradian_mitsuba::load_string(xml, Path::new("n.xml"), Path::new("."), &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().map(|p| (p.line, p.col)), Some((4, 19)), "{e}");
    assert!(e.message.contains("reflectance"), "{e}");
}
