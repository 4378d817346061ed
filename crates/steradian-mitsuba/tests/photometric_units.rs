//! Photometric units on the standard lights (`luminous_intensity`, `luminous_flux`,
//! `luminance`, `illuminance`, with `color`): an illuminance meter reads back the closed forms in
//! lux (point and directional lights exactly; a constant sky and an area disk within four
//! standard errors), and misuse is a located error.

use std::f64::consts::PI;
use std::path::Path;

use steradian::emitter::LUMENS_PER_WATT;
use steradian::render::{render, RenderOptions};
use steradian::spectrum::luminance_f64;

mod common;

/// `lights` and an upward-facing tiny disk meter at the origin.
fn scene(lights: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  {lights}
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/></transform>
    <sensor type="irradiancemeter" id="meter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>
  </shape>
</scene>"#
    )
}

/// The meter's illuminance (lx) and its standard error, at `spp` samples: 683 × Y, and for
/// the error the bound Σ w_c σ_c of `luminance_f64` (the channels' errors are correlated: one
/// path per sample).
fn lux(lights: &str, spp: u32) -> (f64, f64) {
    let job =
        steradian_mitsuba::load_string(&scene(lights), Path::new("units.xml"), Path::new("."), &[])
            .unwrap_or_else(|e| panic!("{e}"));
    let sensor = job.scene.sensor_index("meter").unwrap();
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(3),
        sensor: Some(sensor),
        threads: Some(1),
        ..Default::default()
    };
    let out = render(&job, &opts).unwrap();
    let k = LUMENS_PER_WATT as f64;
    let (value, error) = (out.film().develop(), out.film().develop_stderr());
    (k * luminance_f64(&value.data[..3]), k * luminance_f64(&error.data[..3]))
}

#[test]
fn meters_read_back_the_photometric_values_in_lux() {
    // 100 cd, 2 m overhead: E = I/d² = 25 lx, whatever the colour
    for color in ["", r#"<rgb name="color" value="1, 0.5, 0.2"/>"#] {
        let light = format!(
            r#"<emitter type="point"><point name="position" x="0" y="0" z="2"/>
                 <float name="luminous_intensity" value="100"/>{color}</emitter>"#
        );
        let (e, _) = lux(&light, 4);
        assert!((e / 25.0 - 1.0).abs() < 1e-5, "{color}: {e} lx");
    }
    // 1000 lm isotropic, 1 m overhead: E = Φ/4π
    let (e, _) = lux(
        r#"<emitter type="point"><point name="position" x="0" y="0" z="1"/>
             <float name="luminous_flux" value="1000"/></emitter>"#,
        4,
    );
    assert!((e / (1000.0 / (4.0 * PI)) - 1.0).abs() < 1e-5, "{e} lx");
    // a spot's candela are on its axis (pointing down from 1 m)
    let (e, _) = lux(
        r#"<emitter type="spot"><float name="luminous_intensity" value="500"/>
             <rgb name="color" value="0.2, 0.4, 1"/>
             <transform name="to_world"><lookat origin="0, 0, 1" target="0, 0, 0" up="0, 1, 0"/></transform>
           </emitter>"#,
        4,
    );
    assert!((e / 500.0 - 1.0).abs() < 1e-5, "{e} lx");
    // the sun at 60° from the zenith: E = E⊥ cos 60°
    let (e, _) = lux(
        r#"<emitter type="directional"><vector name="direction" x="0" y="0.8660254" z="-0.5"/>
             <float name="illuminance" value="100000"/></emitter>"#,
        4,
    );
    assert!((e / 50000.0 - 1.0).abs() < 1e-5, "{e} lx");
    // a uniform sky of 1000 cd/m²: E = π L (cosine-weighted directions make it exact, up to
    // single-precision rounding)
    let (e, se) =
        lux(r#"<emitter type="constant"><float name="luminance" value="1000"/></emitter>"#, 4096);
    let want = PI * 1000.0;
    assert!((e - want).abs() <= 4.0 * se.max(1e-6 * want), "{e} ± {se} lx vs {want}");
    // a downward disk of radius 1 and 2000 cd/m², 1 m overhead: E = π L R²/(h² + R²)
    let (e, se) = lux(
        r#"<shape type="disk">
             <transform name="to_world"><rotate x="1" angle="180"/><translate z="1"/></transform>
             <emitter type="area"><float name="luminance" value="2000"/></emitter>
           </shape>"#,
        4096,
    );
    let want = PI * 2000.0 * 0.5;
    assert!(se > 0.0 && se < 0.01 * want, "{se}");
    assert!((e - want).abs() <= 4.0 * se, "{e} ± {se} lx vs {want}");
}

#[test]
fn photometric_misuse_is_a_located_error() {
    let point = |params: &str| {
        common::load_error(
            &scene(&format!(
                "<emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"0\" z=\"2\"/>\n{params}</emitter>"
            )),
            "units.xml",
        )
    };
    let e =
        point(r#"<float name="luminous_intensity" value="100"/><rgb name="intensity" value="1"/>"#);
    assert!(e.contains("units.xml:") && e.contains("not both"), "{e}");
    let e = point(
        r#"<float name="luminous_intensity" value="100"/><float name="luminous_flux" value="1"/>"#,
    );
    assert!(e.contains("give only one of"), "{e}");
    let e = point(r#"<float name="luminous_intensity" value="-5"/>"#);
    assert!(e.contains("luminous_intensity must be finite and non-negative"), "{e}");
    let e = point(r#"<float name="luminous_flux" value="5"/><rgb name="color" value="0, 0, 0"/>"#);
    assert!(e.contains("positive luminance"), "{e}");
    // `color` belongs to the photometric parameters only
    let e = point(r#"<rgb name="intensity" value="1"/><rgb name="color" value="1, 0, 0"/>"#);
    assert!(e.contains("color"), "{e}");
    let e = common::load_error(
        &scene(
            r#"<shape type="disk"><emitter type="area"><float name="luminance" value="1"/>
             <rgb name="radiance" value="1"/></emitter></shape>"#,
        ),
        "units.xml",
    );
    assert!(e.contains("not both") && e.contains("cd/m²"), "{e}");
}
