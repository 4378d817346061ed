//! `workplane`: a grid of illuminance readings over a plane, against the closed forms of a
//! point source (exact) and a uniform sky (within the standard error), with honest errors.

use std::path::Path;

use steradian::render::{render, GridReading, RenderOptions};
use steradian::sensor::{SensorKind, WorkplaneUnit};

mod common;

/// A 4 × 3 work plane over [−2, 2] × [−1.5, 1.5] at z = 0.8 (normal +z) with `lights`.
fn scene(lights: &str, mode: &str, depth: i32) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="{depth}"/></integrator>
  {lights}
  <sensor type="workplane" id="grid">
    <transform name="to_world"><scale x="2" y="1.5"/><translate z="0.8"/></transform>
    <integer name="nx" value="4"/><integer name="ny" value="3"/>
    <string name="mode" value="{mode}"/>
  </sensor>
</scene>"#
    )
}

fn read(xml: &str, spp: u32, seed: u64) -> GridReading {
    let job = steradian_mitsuba::load_string(xml, Path::new("grid.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let sensor = job.scene.sensor_index("grid").unwrap();
    let SensorKind::Workplane(w) = &job.scene.sensors[sensor].kind else { panic!("not a grid") };
    let unit = w.unit;
    assert_eq!(unit, WorkplaneUnit::Illuminance);
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(seed),
        sensor: Some(sensor),
        threads: Some(2),
        ..Default::default()
    };
    GridReading::from_render(&render(&job, &opts).unwrap(), unit)
}

/// An isotropic point source of I = 1000 cd (1000/683 W/sr) 2 m above the plane: every cell's
/// centre reads E = I h / d³ exactly (the meter samples the light, a delta, at the point).
#[test]
fn point_source_illuminance_at_the_cell_centres() {
    let (i, h, lz) = (1000.0f64, 2.0f64, 2.8f64);
    let w = i / 683.0;
    let light = format!(
        r#"<emitter type="point"><point name="position" x="0.3" y="-0.2" z="{lz}"/><rgb name="intensity" value="{w}, {w}, {w}"/></emitter>"#
    );
    let g = read(&scene(&light, "point", 1), 4, 1);
    assert_eq!((g.nx, g.ny, g.unit), (4, 3, "lx"));
    for j in 0..3 {
        for k in 0..4 {
            // plan view: column k at x = −2 + 1 (k + ½), row j at y = 1.5 − (j + ½)
            let (x, y) = (-2.0 + (k as f64 + 0.5), 1.5 - (j as f64 + 0.5));
            let d2 = (x - 0.3).powi(2) + (y + 0.2).powi(2) + h * h;
            let want = i * h / d2.powf(1.5);
            let got = g.values[j * 4 + k];
            assert!((got / want - 1.0).abs() < 1e-4, "cell ({k}, {j}): {got} lx vs {want}");
            assert!(g.stderr[j * 4 + k] < 1e-5 * want);
        }
    }
    let s = g.stats;
    let max = g.values.iter().copied().fold(0.0, f64::max);
    assert_eq!(s.max.value, max);
    assert!((s.u0.value - s.min.value / s.avg.value).abs() < 1e-12);
}

/// Under a uniform sky of luminance L every cell reads E = π L (lx) in either mode; a black
/// disk of radius R at height h above one cell's centre hides the fraction R²/(R² + h²) of it
/// (the configuration factor of a coaxial disk), which the reading finds within its standard
/// error.
#[test]
fn sky_and_an_occluding_disk_read_their_configuration_factors() {
    let l = 1.0 / 683.0; // 1 cd/m² in each channel
    let sky = format!(
        r#"<emitter type="constant"><rgb name="radiance" value="{l}, {l}, {l}"/></emitter>"#
    );
    let pi = std::f64::consts::PI;
    for mode in ["point", "cell"] {
        // open sky: cosine samples weigh π L each, whatever they draw
        let g = read(&scene(&sky, mode, 2), 16, 7);
        for v in &g.values {
            assert!((v / pi - 1.0).abs() < 1e-4, "{mode}: {v} lx");
        }
        assert!((g.stats.u0.value - 1.0).abs() < 1e-4);
    }
    // cell (1, 1) has its centre at (−0.5, 0, 0.8); the disk (R = 0.5) 1 m above it
    let disk = r#"<shape type="disk"><transform name="to_world"><scale value="0.5"/><translate x="-0.5" z="1.8"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf></shape>"#;
    let g = read(&scene(&format!("{sky}{disk}"), "point", 2), 4096, 11);
    let (v, e) = (g.values[4 + 1], g.stderr[4 + 1]);
    let want = pi * (1.0 - 0.25 / 1.25);
    assert!(e > 0.0 && e < 0.01 * want, "stderr {e}");
    assert!((v - want).abs() < 4.0 * e, "{v} ± {e} lx vs {want}");
    // the far cells see a little of the disk, the near one most
    assert!(g.values[4 + 1] < g.values[4 + 3] && g.stats.min.value == v);
}

#[test]
fn bad_work_planes_are_located_errors() {
    let load = |xml: &str| common::load_error(xml, "grid.xml");
    let e = load(&scene("", "corner", 1));
    assert!(
        e.contains("grid.xml:")
            && e.contains(r#"invalid mode "corner", must be one of: "point", "cell""#),
        "{e}"
    );
    let e = load(&scene("", "point", 1).replace(r#"value="4""#, r#"value="0""#));
    assert!(e.contains("'nx' must be a positive integer"), "{e}");
    let with_film = scene("", "point", 1).replace(
        "</sensor>",
        r#"<film type="hdrfilm"><integer name="width" value="5"/><integer name="height" value="3"/></film></sensor>"#,
    );
    let e = load(&with_film);
    assert!(e.contains("4x3") && e.contains("5x3"), "{e}");
    let e = load(
        &scene("", "point", 1).replace("</sensor>", r#"<float name="fov" value="3"/></sensor>"#),
    );
    assert!(e.contains("fov"), "unused parameter: {e}");
}
