//! Purpose: the `hair` BSDF on curves renders `reference/hair.xml` (brown B-spline strands, a
//! blonde linear-curve zigzag, a dyed helix with `sigma_a`, `scale`, low roughness and a
//! steeper scale tilt) as Mitsuba 3.9.1 renders it (its Z-test rule, a 4096-spp `llvm_ad_rgb`
//! reference); other pigments fail the test; what Mitsuba refuses in `hair` is a located
//! error.

mod common;

use std::path::Path;

use common::{reference_scene as data, reference_scene_with, z_test_against};

const SPP: u32 = 64;

#[test]
fn hair_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("hair.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, SPP, "hair", "hair");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// The blonde zigzag made darker (eumelanin 0.2 → 0.8): the image fails.
#[test]
fn the_pigments_matter() {
    let job = reference_scene_with(
        "hair.xml",
        "<float name=\"eumelanin\" value=\"0.2\"/>",
        "<float name=\"eumelanin\" value=\"0.8\"/>",
    );
    let z = z_test_against(&job, SPP, "hair", "hair, darker blonde");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn what_mitsuba_refuses_in_hair_is_refused() {
    let load = |inner: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sphere\">\n<bsdf type=\"hair\">\n{inner}\n</bsdf>\n</shape>\n</scene>"
        );
        steradian_mitsuba::load_string(&xml, Path::new("h.xml"), Path::new("."), &[])
    };
    load("").unwrap();
    load("<rgb name=\"sigma_a\" value=\"0.2, 0.3, 0.4\"/><float name=\"scale\" value=\"3\"/>")
        .unwrap();
    for (inner, needle) in [
        (
            "<rgb name=\"sigma_a\" value=\"0.2\"/><float name=\"eumelanin\" value=\"1\"/>",
            "not both",
        ),
        ("<float name=\"longitudinal_roughness\" value=\"1.5\"/>", "longitudinal_roughness"),
        ("<float name=\"azimuthal_roughness\" value=\"-0.1\"/>", "azimuthal_roughness"),
        ("<float name=\"int_ior\" value=\"1.000277\"/>", "must differ"),
        ("<float name=\"eumelanin\" value=\"-1\"/>", "pigment"),
    ] {
        let e = load(inner).err().unwrap_or_else(|| panic!("accepted: {inner}"));
        assert!(e.pos.is_some() && e.message.contains(needle), "{inner}: {e}");
    }
}
