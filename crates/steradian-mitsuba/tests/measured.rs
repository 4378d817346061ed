//! Purpose: the `measured` BSDF renders `reference/measured.xml` (an isotropic and an
//! anisotropic RGL-layout material on spheres, the anisotropic one two-sided on a tilted
//! plate) as Mitsuba 3.9.1 renders it (its Z-test rule and the image mean against a
//! 4096-spp `llvm_ad_rgb` reference); swapping the two materials fails; a spectral file and a
//! damaged one are located errors.

mod common;

use std::path::Path;

use common::{image_mean_z, reference_scene as data, reference_scene_with, z_test_against};

const SPP: u32 = 64;

#[test]
fn measured_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("measured.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, SPP, "measured", "measured");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    let z = image_mean_z(&job, SPP, "measured", 4096);
    eprintln!("measured image mean: z = {z:.2}");
    assert!(z < 4.0);
}

/// The left sphere with the anisotropic table instead of the isotropic one: the image mean
/// moves far outside its error.
#[test]
fn the_table_matters() {
    let job =
        reference_scene_with("measured.xml", "measured_iso_rgb.bsdf", "measured_aniso_rgb.bsdf");
    let z = image_mean_z(&job, SPP, "measured", 4096);
    eprintln!("measured, tables swapped: image mean z = {z:.2}");
    assert!(z > 4.0, "z = {z:.2}");
}

#[test]
fn bad_files_are_located_errors() {
    let dir = std::env::temp_dir().join(format!("steradian-measured-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("short.bsdf"), b"tensor_file\0\x01\x00\x05\x00\x00\x00").unwrap();
    let xml = |file: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sphere\">\n\
             <bsdf type=\"measured\">\n<string name=\"filename\" value=\"{file}\"/>\n</bsdf>\n\
             </shape>\n</scene>"
        )
    };
    for (file, want) in [("short.bsdf", "truncated"), ("missing.bsdf", "cannot read")] {
        let e =
            steradian_mitsuba::load_string(&xml(file), Path::new("m.xml"), &dir, &[]).unwrap_err();
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
        assert!(e.message.contains(want), "{e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
