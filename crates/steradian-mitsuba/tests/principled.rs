//! Purpose: `principled` and `principledthin` render `reference/principled.xml` (the defaults,
//! an anisotropic clearcoated metal, a transmitting sphere, a textured sheen/flatness sphere
//! and a thin sheet that transmits a back light) as Mitsuba 3.9.1 renders them (its Z-test
//! rule and the image mean against a 4096-spp `llvm_ad_rgb` reference); the sheet without
//! its diffuse transmission, or the sphere with less transmission, fails; `eta` together
//! with `specular` is refused at the element.

mod common;

use std::path::Path;

use common::{image_mean_z, reference_scene as data, z_test_against};

const SPP: u32 = 64;

fn load(xml: &str) -> steradian::render::Job {
    steradian_mitsuba::load_string(xml, Path::new("principled.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn principled_matches_mitsuba() {
    let job = steradian_mitsuba::load_file(&data("principled.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(z_test_against(&job, SPP, "principled", "principled").passes());
    let z = image_mean_z(&job, SPP, "principled", 4096);
    eprintln!("principled image mean: z = {z:.2}");
    assert!(z < 4.0);
}

/// The image mean sees a change of the transmitting sphere (spec_trans 0.85 → 0.6) or of the
/// sheet (diff_trans 1.2 → 0).
#[test]
fn less_transmission_fails() {
    let xml = std::fs::read_to_string(data("principled.xml")).unwrap();
    for (from, to) in [
        (
            "<float name=\"spec_trans\" value=\"0.85\"/>",
            "<float name=\"spec_trans\" value=\"0.6\"/>",
        ),
        ("<float name=\"diff_trans\" value=\"1.2\"/>", "<float name=\"diff_trans\" value=\"0\"/>"),
    ] {
        let job = load(&xml.replacen(from, to, 1));
        let z = image_mean_z(&job, SPP, "principled", 4096);
        eprintln!("{to}: image mean z = {z:.2}");
        assert!(z > 4.0, "{to}: z = {z:.2}");
    }
}

#[test]
fn eta_and_specular_together_are_refused() {
    let xml = "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sphere\">\n\
               <bsdf type=\"principled\"><float name=\"eta\" value=\"1.4\"/>\
               <float name=\"specular\" value=\"0.3\"/></bsdf>\n</shape>\n</scene>";
    let e =
        steradian_mitsuba::load_string(xml, Path::new("p.xml"), Path::new("."), &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(4), "{e}");
    assert!(e.message.contains("not both"), "{e}");
}
