//! `hdrfilm`'s crop window: crop.xml renders only its 48×40 window of a 96×72 frame, as
//! Mitsuba 3.9.1 does (Mitsuba's Z-test rule), under `path` (camera samples over the window)
//! and `ptracer` (light paths splatted into it, normalised over the full frame); a window
//! that leaves the film is a located error.

mod common;

use std::path::Path;

use common::reference_scene as data;
use steradian_mitsuba::{load_file, load_string};

const SPP: u32 = 64;

#[test]
fn cropped_path_render_matches_mitsuba() {
    let job = load_file(&data("crop.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let film = &job.scene.sensors[0].film;
    assert_eq!((film.width, film.height), (48, 40));
    let z = common::z_test_against(&job, SPP, "crop", "crop");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn cropped_light_tracing_matches_mitsuba() {
    let defines = [("integrator".to_string(), "ptracer".to_string())];
    let job = load_file(&data("crop.xml"), &defines).unwrap_or_else(|e| panic!("{e}"));
    let z = common::z_test_against(&job, SPP, "crop-ptracer", "crop-ptracer");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// The window matters: rendered at another offset, the image fails against the reference.
#[test]
fn the_window_is_where_it_says() {
    let job = common::reference_scene_with(
        "crop.xml",
        "<integer name=\"crop_offset_x\" value=\"20\"/>",
        "<integer name=\"crop_offset_x\" value=\"24\"/>",
    );
    let z = common::z_test_against(&job, SPP, "crop", "crop, moved");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn windows_outside_the_film_are_errors() {
    let load = |crop: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<sensor type=\"perspective\">\n\
             <film type=\"hdrfilm\"><integer name=\"width\" value=\"20\"/><integer name=\"height\" value=\"10\"/>\n\
             {crop}\n</film>\n</sensor>\n</scene>"
        );
        load_string(&xml, Path::new("c.xml"), Path::new("."), &[])
    };
    load(
        "<integer name=\"crop_offset_x\" value=\"5\"/><integer name=\"crop_width\" value=\"15\"/>",
    )
    .unwrap();
    for crop in [
        "<integer name=\"crop_offset_x\" value=\"20\"/>",
        "<integer name=\"crop_offset_x\" value=\"5\"/><integer name=\"crop_width\" value=\"16\"/>",
        "<integer name=\"crop_height\" value=\"0\"/>",
        "<integer name=\"crop_offset_y\" value=\"-1\"/>",
    ] {
        let Err(e) = load(crop) else { panic!("{crop} was accepted") };
        assert!(e.message.contains("leaves the 20×10 film"), "{crop}: {e}");
        assert_eq!(e.pos.as_ref().unwrap().line, 5, "{crop}: {e}");
    }
}
