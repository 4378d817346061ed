//! The `envmap` emitter end to end: Mitsuba 3.9.1 reference images under a high-dynamic-range
//! sky (`path` and `direct`, checked with Mitsuba's render-test rule), closed forms under a
//! uniform map (a `constant` sky of the same radiance; irradiance π L), RGBE files read as
//! Mitsuba reads them, and located errors.

mod common;

use std::path::PathBuf;

use steradian::film::{read_exr, z_test, Image};
use steradian::render::{render, Job, PixelQuantity, RenderOptions};
use steradian::sampling::SamplerKind;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference").join(name)
}

fn load(name: &str, defines: &[(&str, &str)]) -> Job {
    let defines: Vec<(String, String)> =
        defines.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    steradian_mitsuba::load_file(&data(&format!("{name}.xml")), &defines)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Renders `job` at `spp` (seed 1) and applies Mitsuba's render-test rule against the
/// reference `reference`-ref.exr / -var.exr.
fn z_test_against(job: &Job, reference: &str, spp: u32) -> steradian::film::ZTest {
    let out = render(job, &RenderOptions { spp: Some(spp), seed: Some(1), ..Default::default() })
        .unwrap();
    assert_eq!(out.dropped_samples, 0, "NaN/Inf samples");
    let img = out.film().develop();
    let r = read_exr(&data(&format!("{reference}-ref.exr"))).unwrap();
    let v = read_exr(&data(&format!("{reference}-var.exr"))).unwrap();
    let z = z_test(&img, spp, &r, &v);
    let (m, rm) = (img.channel_means(), r.channel_means());
    eprintln!(
        "{reference} @ {spp} spp: {:.2} % of pixels pass (min p {:.1e}), mean ratios {:.4?}",
        100.0 * z.pass_fraction(),
        z.min_p,
        (0..3).map(|c| m[c] / rm[c]).collect::<Vec<_>>()
    );
    z
}

/// A diffuse and a rough gold sphere on a plane under a sky with a sun ~2000× brighter than
/// the sky, the map turned by `to_world`: the lit sides, the shadows and the sky behind show
/// the orientation, the glossy sphere the sun's highlight (reference: 16384 spp, llvm_ad_rgb).
#[test]
fn envmap_scene_matches_mitsuba() {
    let z = z_test_against(&load("envmap", &[]), "envmap", 64);
    assert!(z.passes(), "{z:?}");
}

#[test]
fn envmap_scene_with_direct_matches_mitsuba() {
    let z = z_test_against(&load("envmap-direct", &[]), "envmap-direct", 64);
    assert!(z.passes(), "{z:?}");
}

/// MIS compensation only moves samples: the image stays Mitsuba's.
#[test]
fn mis_compensation_keeps_the_image() {
    let z = z_test_against(&load("envmap", &[("mis", "true")]), "envmap", 64);
    assert!(z.passes(), "{z:?}");
}

/// Unset, `mis_compensation` is on under `path`, which weighs every light sample against a
/// BSDF sample (the sky's darker half then has no light-sampling density), and off under
/// `direct`, as in Mitsuba; the scene's word overrides either.
#[test]
fn mis_compensation_defaults_on_under_path_only() {
    use steradian::emitter::Emitter;
    use steradian::Vec3;
    let sensor = common::SENSOR;
    for (integrator, setting, compensated) in [
        ("path", "", true),
        ("direct", "", false),
        ("path", r#"<boolean name="mis_compensation" value="false"/>"#, false),
        ("direct", r#"<boolean name="mis_compensation" value="true"/>"#, true),
    ] {
        let xml = format!(
            r#"<scene version="3.0.0"><integrator type="{integrator}"/>
            <emitter type="envmap"><string name="filename" value="envmap/sky.exr"/>{setting}</emitter>
            {sensor}</scene>"#
        );
        let job = load_inline(&xml);
        let Emitter::EnvMap(env) = &job.scene.emitters[0] else { panic!("not an envmap") };
        // directions over the sphere (a Fibonacci lattice) without light-sampling density
        let n = 4096;
        let unsampled = (0..n)
            .filter(|&i| {
                let z = 1.0 - (2 * i + 1) as f32 / n as f32;
                let phi = i as f32 * 2.399_963;
                let r = (1.0 - z * z).sqrt();
                env.pdf_direction(Vec3::new(r * phi.cos(), r * phi.sin(), z)) == 0.0
            })
            .count();
        assert_eq!(unsampled > n / 10, compensated, "{integrator} {setting}: {unsampled} of {n}");
    }
}

/// A rough mirror sphere on a diffuse plane under `sky`, seen by the 24 × 24 box-filtered
/// camera of `common::SENSOR`.
fn uniform_scene(sky: &str) -> String {
    let sensor = common::SENSOR;
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="4"/></integrator>
  {sky}
  {sensor}
  <shape type="sphere"><float name="radius" value="0.8"/>
    <bsdf type="roughconductor"><float name="alpha" value="0.3"/></bsdf></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/><translate y="-0.8"/></transform>
    <bsdf type="diffuse"/></shape>
</scene>"#
    )
}

const UNIFORM_ENVMAP: &str = r#"<emitter type="envmap"><string name="filename" value="envmap/uniform.exr"/>
    <transform name="to_world"><rotate x="0.70710678" y="0.70710678" angle="50"/></transform></emitter>"#;
const UNIFORM_CONSTANT: &str =
    r#"<emitter type="constant"><rgb name="radiance" value="0.6, 0.8, 1.0"/></emitter>"#;

fn load_inline(xml: &str) -> Job {
    steradian_mitsuba::load_string(xml, &data("inline.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Per-pixel and per-channel z of two independent renders, |a − b| / √(σa² + σb²).
fn max_z_and_outliers(a: (&Image, &Image), b: (&Image, &Image)) -> (f64, usize) {
    let mut worst = 0f64;
    let mut outliers = 0;
    for i in 0..a.0.data.len() {
        let d = (a.0.data[i] - b.0.data[i]) as f64;
        let s = ((a.1.data[i] as f64).powi(2) + (b.1.data[i] as f64).powi(2)).sqrt();
        let z = if s > 0.0 {
            d.abs() / s
        } else if d == 0.0 {
            0.0
        } else {
            f64::INFINITY
        };
        worst = worst.max(z);
        outliers += (z > 4.0) as usize;
    }
    (worst, outliers)
}

/// A uniform-valued envmap is a `constant` sky of that radiance: images and irradiance maps
/// of the same scene agree pixel by pixel within their error bars (independent seeds).
#[test]
fn uniform_envmap_renders_like_constant() {
    for quantity in [PixelQuantity::Sensor, PixelQuantity::SurfaceIrradiance] {
        let run = |sky: &str, seed: u64| {
            let out = render(
                &load_inline(&uniform_scene(sky)),
                &RenderOptions {
                    spp: Some(256),
                    seed: Some(seed),
                    sampler: Some(SamplerKind::Independent),
                    quantity,
                    ..Default::default()
                },
            )
            .unwrap();
            (out.film().develop(), out.film().develop_stderr())
        };
        let (env, constant) = (run(UNIFORM_ENVMAP, 1), run(UNIFORM_CONSTANT, 2));
        let (worst, outliers) = max_z_and_outliers((&env.0, &env.1), (&constant.0, &constant.1));
        let n = env.0.data.len();
        eprintln!("{quantity:?}: max z {worst:.2}, {outliers} of {n} values beyond 4σ");
        // 24 × 24 × 3 values: beyond 4σ has probability 6e-5 each
        assert!(outliers <= 1 && worst < 6.0, "{quantity:?}: max z {worst}, {outliers} outliers");
        let (em, cm) = (env.0.channel_means(), constant.0.channel_means());
        for c in 0..3 {
            assert!(
                (em[c] / cm[c] - 1.0).abs() < 0.01,
                "{quantity:?} channel {c}: {em:?} vs {cm:?}"
            );
        }
    }
}

/// An irradiance meter tilted 60° from the zenith, alone under a uniform envmap: its reading,
/// light-sampled from the map and cosine-sampled under MIS, is π L within a few standard
/// errors.
#[test]
fn irradiance_under_a_uniform_envmap_is_pi_l() {
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="path"/>
  {UNIFORM_ENVMAP}
  <shape type="disk">
    <transform name="to_world"><scale value="1e-3"/><rotate x="1" angle="-60"/></transform>
    <sensor type="irradiancemeter" id="meter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>
  </shape>
</scene>"#
    );
    let job = load_inline(&xml);
    let out = render(
        &job,
        &RenderOptions {
            spp: Some(4096),
            seed: Some(3),
            sampler: Some(SamplerKind::Independent),
            ..Default::default()
        },
    )
    .unwrap();
    let (v, e) = (out.film().develop().get(0, 0), out.film().develop_stderr().get(0, 0));
    let want = glam::Vec3A::new(0.6, 0.8, 1.0) * std::f32::consts::PI;
    eprintln!("irradiance {v} ± {e}, π L = {want}");
    for c in 0..3 {
        assert!(e[c] > 0.0 && e[c] < 0.01 * want[c], "channel {c}: error bar {e}");
        assert!((v[c] - want[c]).abs() < 4.0 * e[c], "channel {c}: {v} ± {e} vs {want}");
    }
}

/// With another light, `light_selection` by power (which gives the envmap a flux from its
/// integral) keeps the expectation of the uniform rule.
#[test]
fn power_selection_with_an_envmap_keeps_the_expectation() {
    let scene = |rule: &str| {
        let xml = uniform_scene(
            r#"<emitter type="envmap"><string name="filename" value="envmap/sky.exr"/><float name="scale" value="0.1"/></emitter>
               <emitter type="point"><point name="position" x="1" y="2" z="2"/><rgb name="intensity" value="5"/></emitter>"#,
        )
        .replace(
            r#"<integrator type="path"><integer name="max_depth" value="4"/></integrator>"#,
            &format!(
                r#"<integrator type="path"><integer name="max_depth" value="4"/><string name="light_selection" value="{rule}"/></integrator>"#
            ),
        );
        common::scene_mean_and_error(&load_inline(&xml), 4)
    };
    let ((a, ea), (b, eb)) = (scene("uniform"), scene("power"));
    eprintln!("uniform {a} ± {ea}, power {b} ± {eb}");
    assert!((a - b).abs() < 4.0 * (ea * ea + eb * eb).sqrt(), "{a} ± {ea} vs {b} ± {eb}");
}

/// steradian's RGBE reader gives the values Mitsuba's does (`sky_small-mitsuba.exr` is Mitsuba's
/// read of `sky_small.hdr`, written by Mitsuba with its run-length encoding).
#[test]
fn rgbe_file_reads_as_mitsuba_reads_it() {
    let hdr = steradian::texture::read_image(&data("envmap/sky_small.hdr")).unwrap();
    let mitsuba = read_exr(&data("envmap/sky_small-mitsuba.exr")).unwrap();
    assert_eq!((hdr.width, hdr.height), (mitsuba.width as usize, mitsuba.height as usize));
    assert_eq!(hdr.data, mitsuba.data);
    // and it renders as an envmap
    let xml = uniform_scene(
        r#"<emitter type="envmap"><string name="filename" value="envmap/sky_small.hdr"/></emitter>"#,
    );
    let (mean, _) = common::scene_mean_and_error(&load_inline(&xml), 1);
    assert!(mean.is_finite() && mean > 0.0);
}

fn load_error(emitter: &str) -> String {
    let xml =
        format!("<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n{emitter}\n</scene>");
    match steradian_mitsuba::load_string(&xml, &data("bad.xml"), &data(""), &[]) {
        Ok(_) => panic!("loaded: {emitter}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_envmaps_are_located_errors() {
    let cases = [
        (r#"<emitter type="envmap"/>"#, "missing parameter 'filename'"),
        (
            r#"<emitter type="envmap"><string name="filename" value="envmap/none.exr"/></emitter>"#,
            "none.exr",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="envmap/uniform.exr"/>
               <string name="filter_type" value="nearest"/></emitter>"#,
            "filter_type",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="envmap/uniform.exr"/>
               <float name="scale" value="-2"/></emitter>"#,
            "scale",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="envmap/uniform.exr"/>
               <transform name="to_world"><scale value="2"/></transform></emitter>"#,
            "rotation",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="envmap/make_assets.py"/></emitter>"#,
            "not a PNG, JPEG, OpenEXR, Radiance RGBE",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="envmap/uniform.exr"/></emitter>
               <emitter type="constant"/>"#,
            "only one environment emitter",
        ),
    ];
    for (emitter, want) in cases {
        let e = load_error(emitter);
        assert!(e.contains(want) && e.contains("bad.xml:"), "{emitter}: {e}");
    }
    // a truncated RGBE file
    let dir = std::env::temp_dir().join(format!("steradian-envmap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bytes = std::fs::read(data("envmap/sky_small.hdr")).unwrap();
    let cut = dir.join("cut.hdr");
    std::fs::write(&cut, &bytes[..bytes.len() - 20]).unwrap();
    let e = load_error(&format!(
        r#"<emitter type="envmap"><string name="filename" value="{}"/></emitter>"#,
        cut.display()
    ));
    assert!(e.contains("truncated RGBE"), "{e}");
}
