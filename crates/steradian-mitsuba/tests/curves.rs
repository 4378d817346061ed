//! Purpose: `linearcurve` renders `reference/curves.xml` (a thin textured helix, a tapered
//! zigzag with spherical joints, a straight bar) and `bsplinecurve` renders
//! `reference/bspline-curves.xml` (tapering textured strands, a thick arch with an open end) as
//! Mitsuba 3.9.1 renders them (its Z-test rule, 4096-spp `llvm_ad_rgb` references); the
//! checkerboard's uv along and around the tube matters (its scales swapped, the tests fail);
//! what Mitsuba refuses on curves (emitters, `flip_normals`) and bad curve files are located
//! errors.

mod common;

use std::path::Path;

use common::{reference_scene as data, reference_scene_with, z_test_against};

const SPP: u32 = 64;

#[test]
fn curves_match_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("curves.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    // 40 helix segments, 4 zigzag segments and the bar are the analytic primitives, with the
    // light's sphere
    let stats = job.scene.accel_stats();
    assert_eq!(stats.analytic_prims, 40 + 4 + 1 + 1, "{stats:?}");
    let z = z_test_against(&job, SPP, "curves", "curves");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn bspline_curves_match_mitsuba() {
    let job = steradian_mitsuba::load_file(&data("bspline-curves.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, SPP, "bspline-curves", "bspline curves");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    let job = reference_scene_with(
        "bspline-curves.xml",
        "<scale x=\"2\" y=\"50\"/>",
        "<scale x=\"50\" y=\"2\"/>",
    );
    let z = z_test_against(&job, SPP, "bspline-curves", "bspline curves, uv scales swapped");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// The texture's scales swapped (u around the tube, v along the curve): the helix's pattern
/// changes and the image fails.
#[test]
fn the_curve_uv_matters() {
    let job = reference_scene_with(
        "curves.xml",
        "<scale x=\"2\" y=\"20\"/>",
        "<scale x=\"20\" y=\"2\"/>",
    );
    let z = z_test_against(&job, SPP, "curves", "curves, uv scales swapped");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn what_curves_cannot_do_is_refused() {
    let load = |inner: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"linearcurve\">\n\
             <string name=\"filename\" value=\"curves/helix.txt\"/>\n{inner}\n</shape>\n</scene>"
        );
        steradian_mitsuba::load_string(&xml, Path::new("c.xml"), &data(""), &[])
    };
    load("").unwrap();
    for (inner, needle) in [
        ("<emitter type=\"area\"/>", "not supported"),
        ("<boolean name=\"flip_normals\" value=\"true\"/>", "flip_normals"),
    ] {
        let e = load(inner).err().unwrap_or_else(|| panic!("accepted: {inner}"));
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
    // a curve file's error names the file and its line
    let dir = std::env::temp_dir().join("steradian-curves-test");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bad.txt"), "0 0 0 0.1\n1 0 0 0.1\n\n2 0 0 0.1\n").unwrap();
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"linearcurve\">\n\
               <string name=\"filename\" value=\"bad.txt\"/>\n</shape>\n</scene>";
    let e = steradian_mitsuba::load_string(xml, Path::new("c.xml"), &dir, &[]).unwrap_err();
    assert!(e.message.contains("bad.txt") && e.message.contains("line 4"), "{e}");
}
