//! `ciesky`: CIE standard skies read by an upward meter in the open: the overcast sky's
//! horizontal illuminance is 7π/9 · L_z, and a sky set by its horizontal illuminance gives it
//! back, within the meter's standard error; bad parameters are located errors.

use std::path::Path;

use steradian::emitter::LUMENS_PER_WATT;
use steradian::render::{measure, RenderOptions};

mod common;

/// A tiny upward-facing disk meter at the origin under `sky` (y up).
fn scene(sky: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  <emitter type="ciesky">{sky}</emitter>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/><rotate x="1" angle="-90"/></transform>
    <sensor type="irradiancemeter" id="meter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film>
    </sensor>
  </shape>
</scene>"#
    )
}

/// (lux, its standard error) of the meter.
fn lux(xml: &str, spp: u32) -> (f64, f64) {
    let job = steradian_mitsuba::load_string(xml, Path::new("sky.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let opts =
        RenderOptions { spp: Some(spp), seed: Some(3), threads: Some(2), ..Default::default() };
    let m = measure(&job, &opts).unwrap();
    // a white sky: every channel is the same
    let k = LUMENS_PER_WATT as f64;
    (m.value[1] * k, m.stderr[1] * k)
}

#[test]
fn overcast_sky_gives_seven_ninths_pi_zenith_luminance() {
    let (e, se) = lux(&scene(r#"<float name="zenith_luminance" value="3000"/>"#), 20_000);
    let want = 7.0 * std::f64::consts::PI / 9.0 * 3000.0;
    assert!(se > 0.0 && se < 0.01 * want, "{se}");
    assert!((e - want).abs() < 4.0 * se + 2e-5 * want, "{e} ± {se} lx vs {want}");
}

#[test]
fn a_sky_set_by_its_horizontal_illuminance_gives_it_back() {
    for sky in [
        r#"<float name="horizontal_illuminance" value="10000"/>"#,
        r#"<string name="sky" value="12"/><vector name="sun_direction" x="1" y="1" z="0.3"/><float name="horizontal_illuminance" value="10000"/>"#,
        r#"<string name="sky" value="1"/><vector name="sun_direction" x="0" y="1" z="1"/><float name="horizontal_illuminance" value="10000"/>"#,
    ] {
        let (e, se) = lux(&scene(sky), 20_000);
        assert!((e - 10_000.0).abs() < 4.0 * se + 2e-3 * 10_000.0, "{sky}: {e} ± {se} lx");
    }
}

#[test]
fn bad_skies_are_located_errors() {
    let load = |xml: &str| common::load_error(xml, "sky.xml");
    let e = load(&scene(
        r#"<string name="sky" value="16"/><float name="zenith_luminance" value="1"/>"#,
    ));
    assert!(e.contains("sky.xml:") && e.contains("1 to 15"), "{e}");
    let e =
        load(&scene(r#"<string name="sky" value="7"/><float name="zenith_luminance" value="1"/>"#));
    assert!(e.contains("needs 'sun_direction'"), "{e}");
    let e = load(&scene(""));
    assert!(e.contains("exactly one of"), "{e}");
    let e = load(&scene(r#"<float name="zenith_luminance" value="-1"/>"#));
    assert!(e.contains("non-negative"), "{e}");
    let e = load(&scene(
        r#"<float name="zenith_luminance" value="1"/><float name="scale" value="2"/>"#,
    ));
    assert!(e.contains("scale"), "unused parameter: {e}");
}
