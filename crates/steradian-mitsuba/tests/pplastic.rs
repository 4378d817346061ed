//! Purpose: `pplastic` renders `reference/pplastic.xml` (Beckmann defaults, an anisotropic GGX
//! lobe with a coloured specular reflectance, a textured base with all-normal sampling) as
//! Mitsuba 3.9.1's unpolarised RGB variant renders it (its Z-test rule, 4096-spp `llvm_ad_rgb`
//! reference); `roughplastic` with the same parameters fails the test; equal IORs are refused.

mod common;

use std::path::Path;

use common::{image_mean_z, reference_scene as data, z_test_against};

const SPP: u32 = 64;

#[test]
fn pplastic_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("pplastic.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!(z_test_against(&job, SPP, "pplastic", "pplastic").passes());
}

/// The image mean agrees with Mitsuba's within 4 standard errors; with the default sphere's
/// base 15 % brighter (as if the two refractions' (1 − F) factors were left out near normal
/// incidence) it does not, though the per-pixel rule above cannot see so small a change.
#[test]
fn image_mean_agrees_and_a_base_without_the_refractions_does_not() {
    let job =
        steradian_mitsuba::load_file(&data("pplastic.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let z = image_mean_z(&job, SPP, "pplastic", 4096);
    eprintln!("pplastic image mean: z = {z:.2}");
    assert!(z < 4.0);
    let xml = std::fs::read_to_string(data("pplastic.xml")).unwrap();
    let xml = xml.replacen(
        "<bsdf type=\"pplastic\"/>",
        "<bsdf type=\"pplastic\"><rgb name=\"diffuse_reflectance\" value=\"0.575\"/></bsdf>",
        1,
    );
    let job = steradian_mitsuba::load_string(&xml, Path::new("bright.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let z = image_mean_z(&job, SPP, "pplastic", 4096);
    eprintln!("pplastic base x 1.15, image mean: z = {z:.2}");
    assert!(z > 4.0);
}

#[test]
fn equal_iors_are_refused() {
    let xml = "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sphere\">\n\
               <bsdf type=\"pplastic\"><float name=\"int_ior\" value=\"1.000277\"/></bsdf>\n</shape>\n</scene>";
    let e =
        steradian_mitsuba::load_string(xml, Path::new("p.xml"), Path::new("."), &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(4), "{e}");
    assert!(e.message.contains("must differ"), "{e}");
}
