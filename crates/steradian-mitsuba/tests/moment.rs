//! Purpose: `moment` renders `reference/moment.xml` (a named `path` and an unnamed `direct`
//! inside it) as Mitsuba 3.9.1 does: the image (the path tracer's) passes Mitsuba's Z-test
//! rule; its layers are named as Mitsuba names them; each mean layer is the XYZ of that
//! integrator's image; and the per-sample variance m2 − m1² agrees with Mitsuba's, which it
//! would not if a sample were steradian's usual average of several paths.

mod common;

use std::path::Path;

use common::{reference_scene as data, z_test_against};
use steradian::film::{read_exr_channels, Image};
use steradian::render::{render, RenderOptions, RenderOutput};

const SPP: u32 = 64;

fn job() -> steradian::render::Job {
    steradian_mitsuba::load_file(&data("moment.xml"), &[]).unwrap_or_else(|e| panic!("{e}"))
}

fn output(job: &steradian::render::Job, spp: u32) -> RenderOutput {
    render(job, &RenderOptions { spp: Some(spp), seed: Some(3), ..Default::default() }).unwrap()
}

/// Our layer `name` and Mitsuba's (moment-aov.exr, 4096 spp).
fn layers(out: &RenderOutput, name: &str) -> (Image, Image) {
    let ours = out.aov_images().into_iter().find(|(l, _)| l.name == name).expect(name).1;
    let ch = ["X", "Y", "Z"].map(|c| format!("{name}.{c}"));
    let path = data("moment-aov.exr");
    let theirs = read_exr_channels(&path, &[&ch[0], &ch[1], &ch[2]]).unwrap();
    (ours, theirs)
}

/// Mean over the pixels of channel Y.
fn mean_y(img: &Image) -> f64 {
    img.data.iter().skip(1).step_by(3).map(|&v| v as f64).sum::<f64>() / (img.data.len() / 3) as f64
}

/// Mean over the pixels of the per-sample variance m2 − m1² of channel Y.
fn per_sample_variance(m1: &Image, m2: &Image) -> f64 {
    let n = m1.data.len() / 3;
    let v = (0..n).map(|i| (m2.data[3 * i + 1] - m1.data[3 * i + 1].powi(2)).max(0.0) as f64);
    v.sum::<f64>() / n as f64
}

#[test]
fn image_matches_mitsuba_and_layers_are_mitsubas() {
    let job = job();
    assert!(z_test_against(&job, SPP, "moment", "moment").passes());
    let out = output(&job, SPP);
    let names: Vec<String> = out.aov_images().iter().map(|(l, _)| l.name.clone()).collect();
    assert_eq!(names, ["pp", "_arg_0", "m2_pp", "m2__arg_0"]);
    // the path tracer's mean layer is its image in XYZ
    let (image, pp) = (out.image(), layers(&out, "pp").0);
    for (rgb, xyz) in image.data.chunks(3).zip(pp.data.chunks(3)) {
        let y = 0.212671 * rgb[0] + 0.715160 * rgb[1] + 0.072169 * rgb[2];
        assert!((xyz[1] - y).abs() <= 1e-5 * y.abs().max(1e-3), "{xyz:?} vs {rgb:?}");
    }
}

/// Image means of the layers against Mitsuba's: the direct integrator's mean (tolerance from
/// both renders' standard errors, from their own second moments) and the per-sample variance
/// of both integrators (within 20 %: a one-path sample's variance, not that of an average).
#[test]
fn moments_agree_with_mitsubas() {
    let spp = 256;
    let out = output(&job(), spp);
    for name in ["pp", "_arg_0"] {
        let (m1, m1_ref) = layers(&out, name);
        let (m2, m2_ref) = layers(&out, &format!("m2_{name}"));
        let var = |m1: &Image, m2: &Image| -> f64 {
            let n = m1.data.len() / 3;
            (0..n)
                .map(|i| (m2.data[3 * i + 1] - m1.data[3 * i + 1].powi(2)).max(0.0) as f64)
                .sum::<f64>()
                / n as f64
        };
        let (v, v_ref) = (var(&m1, &m2), var(&m1_ref, &m2_ref));
        eprintln!(
            "{name}: mean Y {:.5} vs {:.5}; per-sample variance {v:.5} vs {v_ref:.5}",
            mean_y(&m1),
            mean_y(&m1_ref)
        );
        assert!((v / v_ref - 1.0).abs() < 0.2, "{name}: variance {v} vs Mitsuba's {v_ref}");
        // the image mean's standard error: pixel variances / spp, over n pixels
        let n = (m1.data.len() / 3) as f64;
        let se = ((v / spp as f64 + v_ref / 4096.0) / n).sqrt();
        let z = (mean_y(&m1) - mean_y(&m1_ref)) / se;
        assert!(z.abs() < 4.0, "{name}: image mean z = {z:.2}");
    }
}

/// With `branches` 4 given, a sample averages four paths from the first hit and its variance
/// falls well below Mitsuba's: the test above would see it.
#[test]
fn branched_samples_have_a_smaller_variance() {
    let xml = std::fs::read_to_string(data("moment.xml")).unwrap().replacen(
        "<integer name=\"max_depth\" value=\"4\"/>",
        "<integer name=\"max_depth\" value=\"4\"/><integer name=\"branches\" value=\"4\"/>",
        1,
    );
    let job = steradian_mitsuba::load_string(&xml, Path::new("b.xml"), &data(""), &[]).unwrap();
    let out = output(&job, 64);
    let (m1, m1_ref) = layers(&out, "pp");
    let (m2, m2_ref) = layers(&out, "m2_pp");
    let ratio = per_sample_variance(&m1, &m2) / per_sample_variance(&m1_ref, &m2_ref);
    eprintln!("branches 4: per-sample variance ratio {ratio:.3}");
    assert!(ratio < 0.8, "ratio {ratio}");
}

#[test]
fn moment_needs_an_integrator_and_cannot_nest_itself() {
    for (inner, needle) in [
        ("", "at least one"),
        ("<integrator type=\"moment\"><integrator type=\"path\"/></integrator>", "cannot nest"),
    ] {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"moment\">{inner}</integrator>\n</scene>"
        );
        let e = steradian_mitsuba::load_string(&xml, Path::new("m.xml"), Path::new("."), &[])
            .unwrap_err();
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(2), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
}
