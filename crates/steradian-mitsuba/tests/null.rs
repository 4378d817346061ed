//! Purpose: the `null` BSDF renders `reference/null.xml` as Mitsuba 3.9.1's `path` renders it
//! (its Z-test rule, a 4096-spp `llvm_ad_rgb` reference): null spheres are invisible to camera
//! rays but stop shadow rays, and an emitter with a null BSDF shows its emission; the same
//! scene with the null spheres made diffuse fails the test; `null` takes no parameters.
//! `reference/null-path.xml`: Mitsuba's `path` counts a sample only once its path scatters
//! off a lobe that is not null, so a null-BSDF emitter shows only where something lies behind
//! it and a mask of opacity 0.4 renders about 0.4² as bright; steradian's `path` matches, and
//! its `volpath` and `prb`, which have no such rule (as Mitsuba's have none), fail that
//! reference.

mod common;

use std::path::Path;

use common::{reference_scene as data, z_test_against};
use steradian::film::ZTest;
use steradian::render::Job;

const SPP: u32 = 64;

fn z(job: &Job, what: &str) -> ZTest {
    z_test_against(job, SPP, "null", what)
}

#[test]
fn null_scene_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("null.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!(z(&job, "null").passes());
    let mean_z = common::image_mean_z(&job, SPP, "null", 4096);
    eprintln!("null image mean: z = {mean_z:.2}");
    assert!(mean_z < 4.0, "image mean off by {mean_z:.2} standard errors");
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

#[test]
fn path_counts_only_paths_that_scatter_as_mitsuba_does() {
    let job =
        steradian_mitsuba::load_file(&data("null-path.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, SPP, "null-path", "null-path");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    let volpath = common::reference_scene_with(
        "null-path.xml",
        "<integrator type=\"path\"/>",
        "<integrator type=\"volpath\"/>",
    );
    let z = z_test_against(&volpath, SPP, "null-path", "null-path under volpath");
    assert!(!z.passes(), "{:.4} of the pixels pass under volpath", z.pass_fraction());
    // Mitsuba's prb keeps those paths too: its image is path's without the rule
    let prb = common::reference_scene_with(
        "null-path.xml",
        "<integrator type=\"path\"/>",
        "<integrator type=\"prb\"><integer name=\"max_depth\" value=\"-1\"/></integrator>",
    );
    let z = z_test_against(&prb, SPP, "null-path", "null-path under prb");
    assert!(!z.passes(), "{:.4} of the pixels pass under prb", z.pass_fraction());
}
