//! Purpose: the `sun` emitter is a disk of the stated solid angle and direct normal
//! irradiance: a horizontal meter reads E_n sin(altitude) under `path`, `direct` and `volpath`;
//! a mirror shows the disk's radiance L = E_n/(π sin²δ) times its reflectance, which only a
//! hittable sun (not a delta light) can give; its parameters are checked, with located errors.

mod common;

use std::path::Path;

use common::METER_FILM;

fn read(xml: &str, id: &str, spp: u32) -> ([f64; 3], [f64; 3]) {
    common::read_meter(xml, id, spp, 3)
}

/// The sun at altitude `alt` (degrees) in the x–y plane (y up).
fn towards(alt: f64) -> (f64, f64) {
    let a = alt.to_radians();
    (a.cos(), a.sin())
}

#[test]
fn horizontal_irradiance_under_each_integrator() {
    let (x, y) = towards(40.0);
    for integrator in ["path", "direct", "volpath"] {
        let xml = format!(
            r#"<scene version="3.0.0">
  <integrator type="{integrator}"/>
  <emitter type="sun"><vector name="sun_direction" x="{x}" y="{y}" z="0"/><rgb name="irradiance" value="800, 900, 1000"/><float name="angular_radius" value="2"/></emitter>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-5"/><rotate x="1" angle="-90"/></transform>
    <sensor type="irradiancemeter" id="meter">{METER_FILM}</sensor>
  </shape>
</scene>"#
        );
        let (v, se) = read(&xml, "meter", 4096);
        for (c, e_n) in [800.0, 900.0, 1000.0].into_iter().enumerate() {
            let want = e_n * y;
            let tol = 3.0 * se[c] + 1e-4 * want;
            assert!((v[c] - want).abs() <= tol, "{integrator} channel {c}: {} vs {want}", v[c]);
        }
    }
}

/// A radiance meter looking into a smooth mirror (`conductor`, a perfect one) at the sun's
/// reflection reads the disk's radiance; one aimed beside the disk reads nothing.
#[test]
fn a_mirror_shows_the_disk() {
    let (x, y) = towards(30.0);
    let delta = 1.5f64.to_radians();
    let radiance = 1000.0 / (std::f64::consts::PI * delta.sin().powi(2));
    for (dx, want) in [(0.0, radiance), (0.1, 0.0)] {
        let xml = format!(
            r#"<scene version="3.0.0">
  <integrator type="path"/>
  <emitter type="sun"><vector name="sun_direction" x="{x}" y="{y}" z="0"/><rgb name="irradiance" value="1000"/><float name="angular_radius" value="1.5"/></emitter>
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="conductor"><string name="material" value="none"/></bsdf>
  </shape>
  <sensor type="radiancemeter" id="meter">
    <point name="origin" x="{}" y="{}" z="0"/><vector name="direction" x="{}" y="{}" z="0"/>
    {METER_FILM}
  </sensor>
</scene>"#,
            -x * 2.0,
            y * 2.0,
            x + dx,
            -y
        );
        let (v, _) = read(&xml, "meter", 64);
        for (c, value) in v.iter().enumerate() {
            assert!(
                (value - want).abs() <= 1e-3 * radiance,
                "offset {dx} channel {c}: {value} vs {want}"
            );
        }
    }
}

#[test]
fn bad_parameters_are_located_errors() {
    let scene = |body: &str| {
        format!("<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<emitter type=\"sun\">\n{body}\n</emitter>\n</scene>")
    };
    let load = |xml: &str| {
        steradian_mitsuba::load_string(xml, Path::new("sun.xml"), Path::new("."), &[]).unwrap_err()
    };
    let e = load(&scene(""));
    assert!(e.message.contains("sun_direction"), "{e}");
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(3), "{e}");
    let e = load(&scene(
        "<vector name=\"sun_direction\" x=\"0\" y=\"1\" z=\"0\"/>\n<float name=\"angular_radius\" value=\"-1\"/>",
    ));
    assert!(e.message.contains("angular_radius"), "{e}");
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
    let e = load(&scene("<vector name=\"sun_direction\" x=\"0\" y=\"0\" z=\"0\"/>"));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(4), "{e}");
    let e = load(&scene(
        "<vector name=\"sun_direction\" x=\"0\" y=\"1\" z=\"0\"/>\n<rgb name=\"irradiance\" value=\"-5\"/>",
    ));
    assert!(e.message.contains("irradiance"), "{e}");
    // two suns
    let two = "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<emitter type=\"sun\"><vector name=\"sun_direction\" x=\"0\" y=\"1\" z=\"0\"/></emitter>\n<emitter type=\"sun\"><vector name=\"sun_direction\" x=\"1\" y=\"1\" z=\"0\"/></emitter>\n</scene>";
    let e = load(two);
    assert!(e.message.contains("one `sun`"), "{e}");
    // the daylight factor leaves the direct sun out: a scene with a sun is refused
    let df = String::from(
        "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<emitter type=\"ciesky\"><float name=\"zenith_luminance\" value=\"1000\"/></emitter>\n<emitter type=\"sun\"><vector name=\"sun_direction\" x=\"0\" y=\"1\" z=\"0\"/></emitter>\n<sensor type=\"workplane\" id=\"p\"><string name=\"quantity\" value=\"daylight_factor\"/></sensor>\n</scene>"
    );
    let e = load(&df);
    assert!(e.message.contains("sun"), "{e}");
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
}
