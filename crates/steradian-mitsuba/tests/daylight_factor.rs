//! The daylight factor of a `workplane` (`quantity` `daylight_factor`): under the CIE overcast
//! sky, a point at the bottom of a black open tube sees the cone of half-angle α around the
//! zenith, and DF = 100 · [sin²α/3 + 4(1 − cos³α)/9] / (7/9) (the sky's L_z (1 + 2 cos Z)/3
//! integrated over the cone, over its 7π/9 L_z on an open plane), within four standard errors,
//! whatever the sky's level; a scene without a `ciesky` has no daylight factor.

use std::path::Path;

use steradian::render::{render, GridReading, RenderOptions};
use steradian::sensor::{SensorKind, WorkplaneUnit};

mod common;

/// A tube of radius 1 and height `h` (y up) with a one-point work plane at its bottom centre,
/// under `sky`.
fn scene(h: f64, sky: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  {sky}
  <shape type="cylinder">
    <point name="p0" x="0" y="0" z="0"/><point name="p1" x="0" y="{h}" z="0"/>
    <float name="radius" value="1"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
  </shape>
  <sensor type="workplane" id="grid">
    <transform name="to_world"><scale value="1e-3"/><rotate x="1" angle="-90"/></transform>
    <integer name="nx" value="1"/><integer name="ny" value="1"/>
    <string name="quantity" value="daylight_factor"/>
  </sensor>
</scene>"#
    )
}

fn read(xml: &str) -> GridReading {
    let job = steradian_mitsuba::load_string(xml, Path::new("df.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let sensor = job.scene.sensor_index("grid").unwrap();
    let SensorKind::Workplane(w) = &job.scene.sensors[sensor].kind else { panic!("not a grid") };
    let unit = w.unit;
    let opts = RenderOptions {
        spp: Some(1 << 16),
        seed: Some(7),
        sensor: Some(sensor),
        threads: Some(2),
        ..Default::default()
    };
    GridReading::from_render(&render(&job, &opts).unwrap(), unit)
}

#[test]
fn daylight_factor_at_the_bottom_of_a_tube_is_the_overcast_closed_form() {
    let overcast = |level: &str| format!(r#"<emitter type="ciesky">{level}</emitter>"#);
    for h in [0.5f64, 1.0, 3.0] {
        let alpha = (1.0 / h).atan();
        let (s, c) = alpha.sin_cos();
        let want = 100.0 * (s * s / 3.0 + 4.0 * (1.0 - c * c * c) / 9.0) / (7.0 / 9.0);
        let by_zenith =
            read(&scene(h, &overcast(r#"<float name="zenith_luminance" value="4000"/>"#)));
        assert_eq!(by_zenith.unit, "%");
        let (got, se) = (by_zenith.values[0], by_zenith.stderr[0]);
        assert!(se > 0.0 && se < 0.02 * want, "h = {h}: {got} ± {se} %");
        assert!((got - want).abs() <= 4.0 * se, "h = {h}: {got} ± {se} % vs {want} %");
        // the level cancels: a sky given by its horizontal illuminance reads the same
        let by_illuminance =
            read(&scene(h, &overcast(r#"<float name="horizontal_illuminance" value="10000"/>"#)));
        assert!((by_illuminance.values[0] / got - 1.0).abs() < 1e-4, "h = {h}");
    }
}

#[test]
fn a_daylight_factor_needs_a_sky() {
    let point = r#"<emitter type="point"><point name="position" x="0" y="2" z="0"/></emitter>"#;
    let e = common::load_error(&scene(1.0, point), "df.xml");
    assert!(e.contains("df.xml:") && e.contains("ciesky"), "{e}");
    // and the unit is resolved to the sky's horizontal illuminance
    let sky = r#"<emitter type="ciesky"><float name="zenith_luminance" value="900"/></emitter>"#;
    let job =
        steradian_mitsuba::load_string(&scene(1.0, sky), Path::new("df.xml"), Path::new("."), &[])
            .unwrap();
    let SensorKind::Workplane(w) = &job.scene.sensors[0].kind else { panic!("not a grid") };
    let WorkplaneUnit::DaylightFactor { outdoor_lux } = w.unit else { panic!("{:?}", w.unit) };
    assert!((outdoor_lux / (700.0 * std::f64::consts::PI) - 1.0).abs() < 1e-12, "{outdoor_lux}");
}
