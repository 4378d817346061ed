//! Purpose: `hide_emitters` lets camera rays pass through the area lights they meet, to what
//! lies behind them, as Mitsuba 3.9.1 does: `reference/hide-emitters.xml` (two stacked lights,
//! one with a white diffuse BSDF, half over a wall and half over the hidden sky, an `rgba`
//! film) passes Mitsuba's rule on the image and the alpha channel under `path` and under
//! `direct`; the lights drawn black where they stand (steradian's rule before) fails. So do
//! `directionalarea` shapes, which add no light but are emitter shapes.

mod common;

use common::reference_scene as data;
use steradian::film::{read_exr, z_test, Image, ZTest};
use steradian::render::{render, Job, RenderOptions};
use steradian_mitsuba::load_file;

const SPP: u32 = 64;

fn load(integrator: &str) -> Job {
    let d = [("integrator".to_string(), integrator.to_string())];
    load_file(&data("hide-emitters.xml"), &d).unwrap_or_else(|e| panic!("{e}"))
}

/// The image and the alpha channel at `SPP`.
fn rendered(job: &Job) -> (Image, Image) {
    let out = render(job, &RenderOptions { spp: Some(SPP), seed: Some(1), ..Default::default() })
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.dropped_samples, 0);
    let alpha = out.aov_images().last().expect("an alpha layer").1.clone();
    (out.film().develop(), alpha)
}

fn z(img: &Image, reference: &str) -> ZTest {
    let mean = read_exr(&data(&format!("{reference}-ref.exr"))).unwrap();
    let var = read_exr(&data(&format!("{reference}-var.exr"))).unwrap();
    let z = z_test(img, SPP, &mean, &var);
    eprintln!("{reference} @ {SPP} spp: {:.4} of {} pixels pass", z.pass_fraction(), z.pixels);
    z
}

#[test]
fn path_sees_through_hidden_lights() {
    let (image, alpha) = rendered(&load("path"));
    assert!(z(&image, "hide-emitters").passes());
    assert!(z(&alpha, "hide-emitters-alpha").passes());
}

#[test]
fn direct_sees_through_hidden_lights() {
    let (image, alpha) = rendered(&load("direct"));
    assert!(z(&image, "hide-emitters-direct").passes());
    assert!(z(&alpha, "hide-emitters-direct-alpha").passes());
}

/// Camera rays that stop at the lights, black there (steradian's rule before): a black
/// non-emitting copy of each light just in front of it shows that rule, and it fails.
#[test]
fn stopping_at_the_lights_fails() {
    let xml = std::fs::read_to_string(data("hide-emitters.xml")).unwrap();
    let black = |scale: f32, z: f32| {
        format!(
            "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"{scale}\"/>\
             <translate x=\"0.3\" z=\"{z}\"/></transform><bsdf type=\"diffuse\">\
             <rgb name=\"reflectance\" value=\"0\"/></bsdf></shape>\n"
        )
    };
    let mutant = xml.replace(
        "    <emitter type=\"constant\">",
        &format!("{}{}    <emitter type=\"constant\">", black(0.3, 1.501), black(0.5, 1.001)),
    );
    assert_ne!(mutant, xml);
    let job =
        steradian_mitsuba::load_string(&mutant, std::path::Path::new("h.xml"), &data(""), &[])
            .unwrap_or_else(|e| panic!("{e}"));
    let (image, _) = rendered(&job);
    assert!(!z(&image, "hide-emitters").passes());
}

/// A `directionalarea` light adds nothing to a path tracer's image, but its disk is an
/// emitter shape, which hidden camera rays pass through as Mitsuba's do
/// (`reference/directionalarea-hidden.xml`); drawn as a surface (the scene without
/// `hide_emitters`), it fails.
#[test]
fn hidden_camera_rays_pass_through_a_directionalarea_shape() {
    let load = |hide: &str| {
        let d = [("hide".to_string(), hide.to_string())];
        load_file(&data("directionalarea-hidden.xml"), &d).unwrap_or_else(|e| panic!("{e}"))
    };
    let image = |job: &Job| {
        render(job, &RenderOptions { spp: Some(SPP), seed: Some(1), ..Default::default() })
            .unwrap_or_else(|e| panic!("{e}"))
            .film()
            .develop()
    };
    assert!(z(&image(&load("true")), "directionalarea-hidden").passes());
    assert!(!z(&image(&load("false")), "directionalarea-hidden").passes());
}
