//! Scenes as the Mitsuba Blender add-on writes them: blender-export.xml (every transform a
//! matrix, Blender's lens shift as `principal_point_offset_x/y`, clip planes, an area light on
//! a flipped rectangle with a null BSDF, point, spot and sun lights, twosided materials by
//! reference, a mesh from Mitsuba's own PLY writer) loads and renders as Mitsuba 3.9.1 renders
//! it (Mitsuba's Z-test rule); the principal point offset is checked and located.

mod common;

use std::path::Path;

use common::reference_scene as data;
use steradian_mitsuba::{load_file, load_string};

/// Against Mitsuba at 4096 spp (64 passes for the variance), at 64 spp.
#[test]
fn blender_export_scene_matches_mitsuba() {
    const SPP: u32 = 64;
    let scene = load_file(&data("blender-export.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let z = common::z_test_against(&scene, SPP, "blender-export", "blender-export");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// The offset shifts the image: the same scene without it differs from Mitsuba's reference
/// (so the test above can fail), and a non-finite offset is an error at the property.
#[test]
fn principal_point_offset_moves_the_image_and_is_checked() {
    const SPP: u32 = 16;
    let x = "name=\"principal_point_offset_x\" value=\"0.08\"";
    let unshifted = common::reference_scene_with(
        "blender-export.xml",
        x,
        "name=\"principal_point_offset_x\" value=\"0\"",
    );
    let z = common::z_test_against(&unshifted, SPP, "blender-export", "blender-export");
    assert!(!z.passes(), "{:.4} of the pixels pass without the offset", z.pass_fraction());

    let xml = std::fs::read_to_string(data("blender-export.xml")).unwrap();
    let y = "name=\"principal_point_offset_y\" value=\"-0.05\"";
    let bad = xml.replace(y, "name=\"principal_point_offset_y\" value=\"1e39\"");
    let Err(e) = load_string(&bad, Path::new("bad.xml"), &data(""), &[]) else {
        panic!("an infinite offset was accepted")
    };
    assert!(e.message.contains("principal_point_offset_y"), "{e}");
    let line = xml.lines().position(|l| l.contains(y)).unwrap() as u32 + 1;
    assert_eq!(e.pos.as_ref().unwrap().line, line, "{e}");
}
