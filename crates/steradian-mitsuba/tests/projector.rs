//! Purpose: `projector` renders `reference/projector.xml` (a projected sRGB image on a wall,
//! a floor and a sphere; a constant projector with `scale` and a vertical field of view) as
//! Mitsuba 3.9.1 renders it (its Z-test rule and the image mean against a 4096-spp
//! `llvm_ad_rgb` reference), and the image flipped upside down fails; a `directionalarea`
//! shape loads with a warning and adds no light, as in Mitsuba's path tracer.

mod common;

use std::path::Path;

use common::{image_mean_z, reference_scene as data, z_test_against};

const SPP: u32 = 64;

#[test]
fn projector_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("projector.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!(z_test_against(&job, SPP, "projector", "projector").passes());
    let z = image_mean_z(&job, SPP, "projector", 4096);
    eprintln!("projector image mean: z = {z:.2}");
    assert!(z < 4.0);
    assert!(
        job.warnings.iter().any(|w| w.contains("directionalarea") && w.contains("no light")),
        "{:?}",
        job.warnings
    );
}

/// The image's orientation is Mitsuba's: flipped vertically (up = −y), it fails the rule.
#[test]
fn flipped_image_fails() {
    let xml = std::fs::read_to_string(data("projector.xml")).unwrap();
    let xml = xml.replacen(
        "<lookat origin=\"1.5, 2.0, 3.0\" target=\"-0.2, 0.8, 0\" up=\"0, 1, 0\"/>",
        "<lookat origin=\"1.5, 2.0, 3.0\" target=\"-0.2, 0.8, 0\" up=\"0, -1, 0\"/>",
        1,
    );
    let job = steradian_mitsuba::load_string(&xml, Path::new("flip.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!z_test_against(&job, SPP, "projector", "projector (image flipped)").passes());
}

#[test]
fn projector_needs_an_image() {
    let xml = "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n\
               <emitter type=\"projector\"/>\n</scene>";
    let e =
        steradian_mitsuba::load_string(xml, Path::new("p.xml"), Path::new("."), &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(3), "{e}");
    assert!(e.message.contains("irradiance"), "{e}");
}
