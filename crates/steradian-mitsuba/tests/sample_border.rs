//! Purpose: `hdrfilm`'s `sample_border` renders `reference/sample-border.xml` (a gaussian film
//! whose edges cross an emitter and a sphere) as Mitsuba 3.9.1 does, on the whole film and on a
//! crop window (Mitsuba's Z-test rule, 4096-spp `llvm_ad_rgb` references); the same scene
//! without the margin fails against the reference at its edges; `ptracer` is unchanged by it,
//! an image with a box filter (no margin) is the same bit for bit; a `batch` refuses it.

mod common;

use common::{reference_scene as data, z_test_against};
use steradian::film::SampleBorder;
use steradian::render::{render, RenderOptions};
use steradian_mitsuba::load_file;

const SPP: u32 = 64;

fn defines(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
}

#[test]
fn the_margin_matches_mitsuba() {
    let job = load_file(&data("sample-border.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let film = &job.scene.sensors[0].film;
    assert_eq!((film.sample_border, film.sample_margin()), (SampleBorder::WithMargin, 2));
    for spp in [SPP, 4 * SPP] {
        let z = z_test_against(&job, spp, "sample-border", "sample_border");
        assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    }
}

#[test]
fn the_margin_of_a_crop_window_matches_mitsuba() {
    let d = defines(&[("crop_x", "7"), ("crop_y", "5"), ("crop_w", "30"), ("crop_h", "20")]);
    let job = load_file(&data("sample-border.xml"), &d).unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, SPP, "sample-border-crop", "sample_border, crop window");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// Without the margin the edge pixels gather their filter's support from one side: the
/// emitter beyond the left edge no longer reaches them, and the image fails against the
/// reference rendered with it (at 256 spp, where the render with the margin still passes; at 64 spp too few pixels fail).
#[test]
fn without_the_margin_the_edges_fail() {
    let d = defines(&[("border", "false")]);
    let job = load_file(&data("sample-border.xml"), &d).unwrap_or_else(|e| panic!("{e}"));
    let z = z_test_against(&job, 4 * SPP, "sample-border", "no sample_border");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

/// Light tracing splats wherever its paths land: the margin changes nothing (as in Mitsuba).
/// A box filter has no margin: its image is the same with and without `sample_border`.
#[test]
fn ptracer_and_the_box_filter_ignore_it() {
    let image = |pairs: &[(&str, &str)], box_filter: bool| {
        let mut xml = std::fs::read_to_string(data("sample-border.xml")).unwrap();
        if box_filter {
            xml = xml.replace("<rfilter type=\"gaussian\"/>", "<rfilter type=\"box\"/>");
        }
        let job = steradian_mitsuba::load_string(
            &xml,
            std::path::Path::new("sb.xml"),
            &data(""),
            &defines(pairs),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let opts = RenderOptions { spp: Some(4), seed: Some(1), ..Default::default() };
        render(&job, &opts).unwrap().film().develop()
    };
    for (integrator, box_filter) in [("ptracer", false), ("path", true)] {
        let with = image(&[("integrator", integrator)], box_filter);
        let without = image(&[("integrator", integrator), ("border", "false")], box_filter);
        assert!(with.data == without.data, "{integrator}: the images differ");
    }
    let with = image(&[], false);
    let without = image(&[("border", "false")], false);
    assert!(with.data != without.data, "path: the margin changed nothing");
}

/// A `batch` lays its cameras side by side on one film: a margin around it is refused by name.
#[test]
fn a_batch_refuses_it() {
    let xml = "<scene version=\"3.0.0\">\n<sensor type=\"batch\">\n\
               <sensor type=\"perspective\"/><sensor type=\"perspective\"/>\n\
               <film type=\"hdrfilm\"><boolean name=\"sample_border\" value=\"true\"/></film>\n\
               </sensor>\n</scene>";
    let Err(e) = steradian_mitsuba::load_string(xml, std::path::Path::new("b.xml"), &data(""), &[])
    else {
        panic!("a batch with sample_border was accepted");
    };
    assert!(e.message.contains("sample_border"), "{e}");
}
