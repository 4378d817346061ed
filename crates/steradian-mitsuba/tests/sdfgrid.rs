//! Purpose: `sdfgrid` renders `reference/sdfgrid.xml` (a torus joined to a sphere in rough
//! gold with `smooth` shading normals, a coarse rounded box in rough plastic with `analytic`
//! ones, both scaled and moved) as Mitsuba 3.9.1 renders it (its Z-test rule, a 4096-spp
//! `scalar_rgb` reference: its `llvm_ad_rgb` variant hung on the scene); the torus's
//! `analytic` normals instead of its `smooth` ones fail the rule; what Mitsuba refuses on an
//! SDF grid (emitters, `flip_normals`, other `normals`) and files that hold no usable grid are
//! located errors.

mod common;

use std::path::Path;

use common::{reference_scene as data, z_test_against};

const SPP: u32 = 64;

fn load(normals: &str) -> steradian::render::Job {
    steradian_mitsuba::load_file(
        &data("sdfgrid.xml"),
        &[("normals".to_string(), normals.to_string())],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn sdf_grids_match_mitsuba() {
    let job = load("smooth");
    let z = z_test_against(&job, SPP, "sdfgrid", "sdfgrid");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    let mean_z = common::image_mean_z(&job, SPP, "sdfgrid", 4096);
    eprintln!("sdfgrid, image mean: z = {mean_z:.2}");
    assert!(mean_z < 4.0, "image mean off by {mean_z:.2} standard errors");
}

/// The gold torus's highlights follow its shading normals: with the interpolant's gradient
/// (`analytic`) instead of Mitsuba's default `smooth` normals, the image fails.
#[test]
fn the_smooth_shading_normals_matter() {
    let z = z_test_against(&load("analytic"), SPP, "sdfgrid", "sdfgrid, analytic normals");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn what_an_sdf_grid_cannot_do_is_refused() {
    let load = |file: &str, inner: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sdfgrid\">\n\
             <string name=\"filename\" value=\"{file}\"/>\n{inner}\n</shape>\n</scene>"
        );
        steradian_mitsuba::load_string(&xml, Path::new("s.xml"), &data(""), &[])
    };
    load("sdfgrid/rounded-box.vol", "").unwrap();
    for (inner, needle) in [
        ("<emitter type=\"area\"/>", "not supported"),
        ("<boolean name=\"flip_normals\" value=\"true\"/>", "flip_normals"),
        ("<string name=\"normals\" value=\"flat\"/>", "normals"),
        ("<float name=\"grid\" value=\"1\"/>", "grid"),
    ] {
        let e = load("sdfgrid/rounded-box.vol", inner)
            .err()
            .unwrap_or_else(|| panic!("accepted: {inner}"));
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
    // a three-channel grid is an error at the file name
    let e = load("volume-texture/rgb.vol", "")
        .err()
        .unwrap_or_else(|| panic!("a 3-channel grid was accepted"));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(4), "{e}");
    assert!(e.message.contains("3 channels"), "{e}");
    // so is a grid all of one sign, which holds no surface
    let dir = std::env::temp_dir().join("steradian-sdfgrid-test");
    std::fs::create_dir_all(&dir).unwrap();
    let mut vol = b"VOL\x03".to_vec();
    for v in [1i32, 2, 2, 2, 1] {
        vol.extend(v.to_le_bytes());
    }
    for v in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0].into_iter().chain([0.5; 8]) {
        vol.extend(v.to_le_bytes());
    }
    std::fs::write(dir.join("positive.vol"), vol).unwrap();
    let xml = "<scene version=\"3.0.0\">\n<shape type=\"sdfgrid\">\n\
               <string name=\"filename\" value=\"positive.vol\"/>\n</shape>\n</scene>";
    let e = steradian_mitsuba::load_string(xml, Path::new("s.xml"), &dir, &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(3), "{e}");
    assert!(e.message.contains("no voxel"), "{e}");
}
