//! `hdrfilm`'s `pixel_format`: an `rgba` film (pixel-format.xml) renders the image and the
//! alpha channel as Mitsuba 3.9.1 does (Mitsuba's Z-test rule on both), under `volpath` (null
//! and mask surfaces let the coverage through, as under `path`) and `direct` (any surface
//! covers); the alpha channel
//! leaves the image unchanged bit for bit; `ptracer` refuses it.

mod common;

use std::path::Path;

use common::reference_scene as data;
use steradian::film::{read_exr, z_test, Image};
use steradian::render::{render, Job, RenderOptions};
use steradian_mitsuba::{load_file, load_string};

const SPP: u32 = 64;

fn rendered(job: &Job) -> (Image, Image) {
    let out = render(job, &RenderOptions { spp: Some(SPP), seed: Some(1), ..Default::default() })
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.dropped_samples, 0);
    let aovs = out.aov_images();
    let (layer, alpha) = aovs.last().expect("an alpha layer");
    assert_eq!((layer.name.as_str(), layer.channels.as_slice()), ("", &["A"][..]));
    (out.film().develop(), alpha.clone())
}

/// Both the image and the alpha channel pass Mitsuba's rule against `reference`.
fn matches_mitsuba(job: &Job, reference: &str) {
    let (image, alpha) = rendered(job);
    for (img, r) in [(&image, reference.to_string()), (&alpha, format!("{reference}-alpha"))] {
        let mean = read_exr(&data(&format!("{r}-ref.exr"))).unwrap();
        let var = read_exr(&data(&format!("{r}-var.exr"))).unwrap();
        let z = z_test(img, SPP, &mean, &var);
        eprintln!("{r} @ {SPP} spp: {:.4} of {} pixels pass", z.pass_fraction(), z.pixels);
        assert!(z.passes(), "{r}: {:.4} of the pixels pass", z.pass_fraction());
    }
    // partly covered: the frame holds empty, covered and in-between pixels
    let a: Vec<f32> = alpha.data.iter().step_by(3).copied().collect();
    assert!(a.contains(&0.0) && a.contains(&1.0));
    assert!(a.iter().any(|&v| v > 0.2 && v < 0.8));
}

#[test]
fn rgba_volpath_matches_mitsuba() {
    let job = load_file(&data("pixel-format.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    matches_mitsuba(&job, "pixel-format");
}

#[test]
fn rgba_direct_matches_mitsuba() {
    let defines = [("integrator".to_string(), "direct".to_string())];
    let job = load_file(&data("pixel-format.xml"), &defines).unwrap_or_else(|e| panic!("{e}"));
    matches_mitsuba(&job, "pixel-format-direct");
}

/// The alpha rules differ where they should: `direct`'s covers the null sphere, `path`'s does
/// not, so `path`'s alpha fails against `direct`'s reference (the test can fail).
#[test]
fn the_rules_differ_and_the_test_can_fail() {
    let defines = [("integrator".to_string(), "path".to_string())];
    let job = load_file(&data("pixel-format.xml"), &defines).unwrap();
    let (_, alpha) = rendered(&job);
    let mean = read_exr(&data("pixel-format-direct-alpha-ref.exr")).unwrap();
    let var = read_exr(&data("pixel-format-direct-alpha-var.exr")).unwrap();
    assert!(!z_test(&alpha, SPP, &mean, &var).passes());
}

/// With `rgb` the render is the same bit for bit, and has no AOV layer.
#[test]
fn alpha_leaves_the_image_unchanged() {
    let rgba = load_file(&data("pixel-format.xml"), &[]).unwrap();
    let rgb = common::reference_scene_with(
        "pixel-format.xml",
        "<string name=\"pixel_format\" value=\"rgba\"/>",
        "<string name=\"pixel_format\" value=\"rgb\"/>",
    );
    let opts = RenderOptions { spp: Some(16), seed: Some(3), ..Default::default() };
    let (a, b) = (render(&rgba, &opts).unwrap(), render(&rgb, &opts).unwrap());
    assert_eq!(a.film().develop().data, b.film().develop().data);
    assert!(b.aov_images().is_empty() && a.aov_images().len() == 1);
}

#[test]
fn formats_parse_and_ptracer_refuses_alpha() {
    let load = |format: &str, integrator: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"{integrator}\"/>\n<sensor type=\"perspective\">\n\
             <film type=\"hdrfilm\">\n<string name=\"pixel_format\" value=\"{format}\"/>\n</film>\n\
             </sensor>\n<shape type=\"sphere\"/>\n</scene>"
        );
        load_string(&xml, Path::new("f.xml"), Path::new("."), &[])
    };
    for f in ["rgb", "rgba", "luminance", "luminance_alpha", "xyz", "xyza"] {
        load(f, "path").unwrap_or_else(|e| panic!("{f}: {e}"));
    }
    load("xyz", "ptracer").unwrap();
    let Err(e) = load("spectrum", "path") else { panic!("spectrum accepted") };
    assert!(e.message.contains("pixel_format \"spectrum\""), "{e}");
    assert_eq!(e.pos.as_ref().unwrap().line, 5, "{e}");
    let Err(e) = load("rgba", "ptracer") else { panic!("ptracer with alpha accepted") };
    assert!(e.message.contains("alpha channel"), "{e}");
    assert_eq!(e.pos.as_ref().unwrap().line, 2, "{e}");
}
