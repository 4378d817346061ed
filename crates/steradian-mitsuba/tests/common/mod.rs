//! Helpers shared by the loader's integration tests (`mod common;`): where the test scenes
//! are, how a load error must read, and the image mean of a small scene. Helpers that do not
//! need the loader are in `steradian::testkit`.

// Each test binary compiles this module and uses part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use steradian::film::{read_exr, z_test, ZTest};
use steradian::render::Job;
use steradian::render::{render, RenderOptions};
use steradian::sampling::SamplerKind;
use steradian_mitsuba::LoadError;

/// A scene of `tests/reference/` (the scenes with Mitsuba reference images), by file name.
pub fn reference_scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference").join(name)
}

/// A scene of `scenes/validation/` (the closed-form radiometry cases), by file name.
pub fn validation_scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/validation").join(name)
}

/// Every scene file of `tests/reference/` and `scenes/validation/`, sorted by path.
pub fn all_scenes() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = [reference_scene(""), validation_scene("")]
        .iter()
        .flat_map(|dir| std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    v.sort();
    v
}

/// The reference scene `name` loaded with every `from` in its text replaced by `to` (a
/// mutation the tests expect to fail); `from` must occur.
pub fn reference_scene_with(name: &str, from: &str, to: &str) -> Job {
    let xml = std::fs::read_to_string(reference_scene(name)).unwrap();
    assert!(xml.contains(from), "{name} has no {from}");
    steradian_mitsuba::load_string(
        &xml.replace(from, to),
        Path::new("mutant.xml"),
        &reference_scene(""),
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Mitsuba's render-test rule for `job` rendered at `spp` camera samples (seed 1) against
/// `tests/reference/{reference}-ref.exr` and its per-sample variance `{reference}-var.exr`;
/// prints the pass fraction under `what`. The render must drop no NaN/Inf sample.
pub fn z_test_against(job: &Job, spp: u32, reference: &str, what: &str) -> ZTest {
    let out = render(job, &RenderOptions { spp: Some(spp), seed: Some(1), ..Default::default() })
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(out.dropped_samples, 0, "{what}: NaN/Inf samples");
    let img = out.film().develop();
    let mean = read_exr(&reference_scene(&format!("{reference}-ref.exr"))).unwrap();
    let var = read_exr(&reference_scene(&format!("{reference}-var.exr"))).unwrap();
    let z = z_test(&img, spp, &mean, &var);
    eprintln!(
        "{what} @ {spp} spp: {:.4} of {} pixels pass (min p {:.2e})",
        z.pass_fraction(),
        z.pixels,
        z.min_p
    );
    z
}

/// The largest z-score over the RGB channels of the image mean of `job` at `spp` (seed 1)
/// against the mean of `tests/reference/{reference}-ref.exr`, with the standard error from
/// both: steradian's per-pixel standard errors and the reference's per-sample variance over
/// its `ref_spp` samples (pixels independent: a box filter). Catches a bias too small for the
/// per-pixel rule but spread over many pixels.
pub fn image_mean_z(job: &Job, spp: u32, reference: &str, ref_spp: u32) -> f64 {
    let out = render(job, &RenderOptions { spp: Some(spp), seed: Some(1), ..Default::default() })
        .unwrap();
    let (img, se) = (out.film().develop(), out.film().develop_stderr());
    let mean = read_exr(&reference_scene(&format!("{reference}-ref.exr"))).unwrap();
    let var = read_exr(&reference_scene(&format!("{reference}-var.exr"))).unwrap();
    let n = (img.data.len() / 3) as f64;
    (0..3)
        .map(|c| {
            fn channel(v: &[f32], c: usize, f: impl Fn(f64) -> f64) -> f64 {
                v.iter().skip(c).step_by(3).map(|&x| f(x as f64)).sum()
            }
            let d = (channel(&img.data, c, |x| x) - channel(&mean.data, c, |x| x)) / n;
            let var_ours = channel(&se.data, c, |s| s * s) / (n * n);
            let var_ref = channel(&var.data, c, |x| x) / ref_spp as f64 / (n * n);
            d.abs() / (var_ours + var_ref).sqrt()
        })
        .fold(0.0, f64::max)
}

/// The message of the error loading the scene text `xml` (called `file` in it, relative files
/// beside the working directory); empty when it loads.
pub fn load_error(xml: &str, file: &str) -> String {
    steradian_mitsuba::load_string(xml, Path::new(file), Path::new("."), &[])
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default()
}

/// The error is at `file:line:col`, reads `file:line:col: error: message`, and its message
/// contains every needle.
#[track_caller]
pub fn check_error(e: &LoadError, file: &Path, line: u32, col: u32, needles: &[&str]) {
    let pos = e.pos.as_ref().unwrap_or_else(|| panic!("no position in: {e}"));
    assert_eq!(*pos.file, file, "wrong file in: {e}");
    assert_eq!((pos.line, pos.col), (line, col), "wrong position in: {e}");
    for needle in needles {
        assert!(
            e.message.contains(needle),
            "message {:?} does not contain {:?}",
            e.message,
            needle
        );
    }
    let start = format!("{}:{line}:{col}: error: ", file.display());
    assert!(e.to_string().starts_with(&start), "{e}");
}

/// The camera of the small integration-test scenes (`branches.rs`, `last_vertex.rs`): 60° from
/// (0, 0, 4) towards the origin, a 24 × 24 film with a box filter, so each pixel's error comes
/// from its own samples.
pub const SENSOR: &str = r#"<sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/><rfilter type="box"/></film></sensor>"#;

/// The red channel's image mean of scene `xml` (named `file` in errors) at 256 i.i.d. samples
/// per pixel, and its standard error (see [`scene_mean_and_error`]).
pub fn mean_and_error(xml: &str, file: &str, seed: u64) -> (f64, f64) {
    scene_mean_and_error(&load_scene(xml, file), seed)
}

/// The scene text `xml` loaded (called `file` in messages, relative files beside the working
/// directory); panics with the load error.
pub fn load_scene(xml: &str, file: &str) -> Job {
    steradian_mitsuba::load_string(xml, Path::new(file), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The red channel's image mean of a loaded scene at 256 i.i.d. samples per pixel, and its
/// standard error: pixels are independent, and each pixel's error comes from the film, which
/// sees one value per camera sample; i.i.d. numbers keep it honest.
pub fn scene_mean_and_error(s: &Job, seed: u64) -> (f64, f64) {
    let out = render(
        s,
        &RenderOptions {
            spp: Some(256),
            seed: Some(seed),
            sampler: Some(SamplerKind::Independent),
            ..Default::default()
        },
    )
    .unwrap();
    let (img, err) = (out.film().develop(), out.film().develop_stderr());
    let n = (img.width * img.height) as f64;
    let mean = img.data.iter().step_by(3).map(|&v| v as f64).sum::<f64>() / n;
    let se = err.data.iter().step_by(3).map(|&e| (e as f64).powi(2)).sum::<f64>().sqrt() / n;
    (mean, se)
}

/// A floor and a wall lit by a disk, seen by a `width` × `height` camera with a gaussian
/// filter (blocks overlap across tile borders, so the order in which they are added shows in
/// the bits), rendered by `integrator` (an `<integrator>` element).
pub fn lit_corner(integrator: &str, width: u32, height: u32) -> Job {
    let xml = format!(
        r#"<scene version="3.0.0">
        {integrator}
        <sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="{width}"/><integer name="height" value="{height}"/></film></sensor>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate y="1" angle="80"/><translate x="-2"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.2"/></bsdf></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate x="1" z="1"/></transform>
            <emitter type="area"><rgb name="radiance" value="20"/></emitter></shape>
        </scene>"#
    );
    steradian_mitsuba::load_string(&xml, Path::new("lit-corner.xml"), Path::new("."), &[])
        .expect("the lit corner loads")
}

/// A 1 × 1 box-filtered film, as a meter in an inline scene needs.
pub const METER_FILM: &str = r#"<film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>"#;

/// (value, stderr) per RGB channel of meter `id` in the inline scene `xml`, measured at `spp`
/// samples with `seed`.
pub fn read_meter(xml: &str, id: &str, spp: u32, seed: u64) -> ([f64; 3], [f64; 3]) {
    let job = steradian_mitsuba::load_string(xml, Path::new("meter.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let sensor = job.scene.find_sensor(id).unwrap();
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(seed),
        sensor: Some(sensor),
        ..Default::default()
    };
    let m = steradian::render::measure(&job, &opts).unwrap();
    (m.value, m.stderr)
}
