//! Purpose: the `volume` texture looks a volume up at the surface point's world position, as
//! Mitsuba 3.9.1 does: `reference/volume-texture.xml` (a sphere coloured by a 3-channel
//! `gridvolume` placed over it, a floor by a `constvolume`) passes Mitsuba's render-test rule;
//! the grid moved fails; a value for `volume` and a volume texture on an emitter are located
//! errors.

mod common;

use std::path::Path;

use common::{reference_scene as data, reference_scene_with, z_test_against};

const SPP: u32 = 64;

#[test]
fn volume_textures_match_mitsuba() {
    let job = steradian_mitsuba::load_file(&data("volume-texture.xml"), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, SPP, "volume-texture", "volume texture");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// The grid turned on its side (its colour gradients run along other axes): the sphere
/// changes colour and the test fails.
#[test]
fn the_world_position_matters() {
    let job = reference_scene_with(
        "volume-texture.xml",
        "<scale value=\"1.2\"/>",
        "<scale value=\"1.2\"/>\n<rotate z=\"1\" angle=\"90\"/>",
    );
    let z = z_test_against(&job, SPP, "volume-texture", "volume texture, grid rotated");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn values_and_emitters_are_refused() {
    let load = |body: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"sphere\">\n{body}\n</shape>\n</scene>"
        );
        steradian_mitsuba::load_string(&xml, Path::new("v.xml"), Path::new("."), &[])
    };
    load("<bsdf type=\"diffuse\"><texture type=\"volume\" name=\"reflectance\"/></bsdf>").unwrap();
    for (body, needle) in [
        (
            "<bsdf type=\"diffuse\"><texture type=\"volume\" name=\"reflectance\">\
             <float name=\"volume\" value=\"0.4\"/></texture></bsdf>",
            "nested <volume>",
        ),
        (
            "<emitter type=\"area\"><texture type=\"volume\" name=\"radiance\"/></emitter>",
            "not supported on emitters",
        ),
    ] {
        let e = load(body).err().unwrap_or_else(|| panic!("accepted: {body}"));
        assert!(e.pos.is_some() && e.message.contains(needle), "{e}");
    }
}
