//! Helpers shared by integration tests (`mod common;`).

use std::path::Path;

use steradian::render::Job;
use steradian::render::{render, RenderOptions};
use steradian::sampling::SamplerKind;

/// The camera of the small integration-test scenes (`branches.rs`, `last_vertex.rs`): 60° from
/// (0, 0, 4) towards the origin, a 24 × 24 film with a box filter, so each pixel's error comes
/// from its own samples.
#[allow(dead_code)] // not every test scene uses it
pub const SENSOR: &str = r#"<sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/><rfilter type="box"/></film></sensor>"#;

/// The red channel's image mean of scene `xml` (named `file` in errors) at 256 i.i.d. samples
/// per pixel, and its standard error (see [`scene_mean_and_error`]).
#[allow(dead_code)] // `last_vertex.rs` loads its scenes itself
pub fn mean_and_error(xml: &str, file: &str, seed: u64) -> (f64, f64) {
    let s = steradian_mitsuba::load_string(xml, Path::new(file), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    scene_mean_and_error(&s, seed)
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
    let (img, err) = (out.film.develop(), out.film.develop_stderr());
    let n = (img.width * img.height) as f64;
    let mean = img.data.iter().step_by(3).map(|&v| v as f64).sum::<f64>() / n;
    let se = err.data.iter().step_by(3).map(|&e| (e as f64).powi(2)).sum::<f64>().sqrt() / n;
    (mean, se)
}
