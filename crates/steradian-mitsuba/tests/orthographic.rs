//! The `orthographic` sensor: orthographic.xml (scaled sensor plane, a near clip that hides a
//! sphere, a far clip that blacks out the back of the scene) renders as Mitsuba 3.9.1 renders
//! it (Mitsuba's Z-test rule), and the loader refuses what the plugin does not read.

mod common;

use std::path::Path;

use common::reference_scene as data;
use steradian_mitsuba::{load_file, load_string};

/// Against Mitsuba at 4096 spp (64 passes for the variance), at 64 spp.
#[test]
fn orthographic_scene_matches_mitsuba() {
    const SPP: u32 = 64;
    let scene = load_file(&data("orthographic.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let z = common::z_test_against(&scene, SPP, "orthographic", "orthographic");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn loader_refuses_what_the_plugin_does_not_read() {
    let load = |body: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n\
             <sensor type=\"orthographic\">\n{body}\n</sensor>\n</scene>"
        );
        load_string(&xml, Path::new("bad.xml"), Path::new("."), &[])
    };
    load("<float name=\"near_clip\" value=\"0.5\"/>").unwrap();
    for (body, needle) in [
        ("<float name=\"fov\" value=\"30\"/>", "fov"),
        ("<float name=\"near_clip\" value=\"0\"/>", "near_clip must be positive"),
        ("<float name=\"far_clip\" value=\"0.001\"/>", "far_clip"),
    ] {
        let e = load(body).err().unwrap_or_else(|| panic!("{body} was accepted"));
        let pos = e.pos.as_ref().unwrap();
        assert_eq!((pos.line, pos.col), (4, 1), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
}
