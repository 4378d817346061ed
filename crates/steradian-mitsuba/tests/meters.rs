//! Meters read delta lights exactly (steradian samples every emitter at the measurement point,
//! unlike Mitsuba's meter, which reads 0 for them), lights add, and the error bars are honest.

mod common;

use std::path::Path;

use steradian::radiometry;
use steradian::render::{render, RenderOptions};
use steradian::testkit::{temp_dir, write_file};

/// Renders sensor `id` of an inline scene; returns (value, stderr) of the single pixel.
fn measure(xml: &str, id: &str, spp: u32, seed: u64) -> ([f64; 3], [f64; 3]) {
    let scene = steradian_mitsuba::load_string(xml, Path::new("meter.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let sensor = scene.scene.sensor_index(id).unwrap();
    let out = render(
        &scene,
        &RenderOptions {
            spp: Some(spp),
            seed: Some(seed),
            sensor: Some(sensor),
            threads: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    let (v, e) = (out.film().develop().get(0, 0), out.film().develop_stderr().get(0, 0));
    ([v.x as f64, v.y as f64, v.z as f64], [e.x as f64, e.y as f64, e.z as f64])
}

/// A tiny disk meter (radius 1e-4 m, so the irradiance is constant over it to 1e-8) at the
/// origin, tilted: its normal is (0, sin 30°, cos 30°) after `rotate x -30`.
fn tilted_meter(lights: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  {lights}
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/><rotate x="1" angle="-30"/></transform>
    <sensor type="irradiancemeter" id="meter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>
  </shape>
</scene>"#
    )
}

fn normal() -> glam::DVec3 {
    let t = (-30f64).to_radians();
    // rotating +z about +x by −30°: (0, −sin(−30°), cos(−30°)) = (0, 0.5, 0.866)
    glam::DVec3::new(0.0, -t.sin(), t.cos())
}

fn assert_rel(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * b.abs(),
        "{what}: {a} vs {b} (rel err {:.2e})",
        (a - b).abs() / b.abs()
    );
}

#[test]
fn point_light_on_a_tilted_meter_is_exact() {
    let (pos, i) = (glam::DVec3::new(0.3, 2.0, 1.5), [10.0, 20.0, 30.0]);
    let xml = tilted_meter(&format!(
        r#"<emitter type="point"><point name="position" x="{}" y="{}" z="{}"/><rgb name="intensity" value="{}, {}, {}"/></emitter>"#,
        pos.x, pos.y, pos.z, i[0], i[1], i[2]
    ));
    let (v, _) = measure(&xml, "meter", 64, 1);
    for c in 0..3 {
        let h = radiometry::point_irradiance(i[c], pos, glam::DVec3::ZERO, normal());
        assert_rel(v[c], h, 1e-4, "point");
    }
}

#[test]
fn spot_light_on_its_axis_is_exact() {
    // a spot at (0,0,3) aimed at the meter: on its axis the fall-off is 1, so H = I cos θ / r²
    // with θ = 30° between the meter's normal and the direction to the light.
    let xml = tilted_meter(
        r#"<emitter type="spot"><rgb name="intensity" value="5"/><float name="cutoff_angle" value="25"/>
             <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform></emitter>"#,
    );
    let (v, _) = measure(&xml, "meter", 64, 2);
    let h = radiometry::point_irradiance(
        5.0,
        glam::DVec3::new(0.0, 0.0, 3.0),
        glam::DVec3::ZERO,
        normal(),
    );
    assert_rel(v[0], h, 1e-4, "spot");
}

#[test]
fn directional_light_on_a_tilted_meter_is_exact() {
    // light travelling along −z: H⊥ cos θ with cos θ = n·(+z) = cos 30°
    let xml = tilted_meter(
        r#"<emitter type="directional"><vector name="direction" value="0, 0, -1"/><rgb name="irradiance" value="2, 3, 4"/></emitter>"#,
    );
    let (v, _) = measure(&xml, "meter", 64, 3);
    for (c, h) in [2.0, 3.0, 4.0].iter().enumerate() {
        assert_rel(v[c], h * 30f64.to_radians().cos(), 1e-4, "directional");
    }
}

#[test]
fn a_point_light_and_an_area_light_add() {
    // a disk emitter of radius 0.5 at height 1 facing down, centred over a meter facing up,
    // plus a point light: H = π L r²/(h² + r²) + I/d²
    let area = r#"<shape type="disk"><transform name="to_world"><scale value="0.5"/><rotate x="1" angle="180"/><translate z="1"/></transform>
                  <emitter type="area"><rgb name="radiance" value="1.5"/></emitter></shape>"#;
    // the point light sits off to the side so that the emitting disk does not shadow it
    let point = r#"<emitter type="point"><point name="position" value="1.5, 0, 2"/><rgb name="intensity" value="8"/></emitter>"#;
    let meter = |lights: &str| {
        format!(
            r#"<scene version="3.0.0"><integrator type="path"><integer name="max_depth" value="1"/></integrator>{lights}
            <shape type="disk"><transform name="to_world"><scale value="1e-4"/></transform>
              <sensor type="irradiancemeter" id="m"><film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film></sensor>
            </shape></scene>"#
        )
    };
    let (both, se) = measure(&meter(&format!("{area}{point}")), "m", 1 << 16, 4);
    let (only_area, _) = measure(&meter(area), "m", 1 << 16, 4);
    let (only_point, _) = measure(&meter(point), "m", 64, 4);
    let h_area = radiometry::disk_on_axis_irradiance(1.5, 0.5, 1.0);
    let h_point = radiometry::point_irradiance(
        8.0,
        glam::DVec3::new(1.5, 0.0, 2.0),
        glam::DVec3::ZERO,
        glam::DVec3::Z,
    );
    assert_rel(only_point[0], h_point, 1e-4, "point alone");
    // the area estimate is Monte Carlo: 5 standard errors
    assert!(
        (both[0] - (h_area + h_point)).abs() <= 5.0 * se[0],
        "sum {} vs {} ± {}",
        both[0],
        h_area + h_point,
        se[0]
    );
    assert!(
        (only_area[0] - h_area).abs() <= 5.0 * se[0] + 1e-6,
        "area alone {} vs {h_area}",
        only_area[0]
    );
}

#[test]
fn error_bars_cover_the_truth_95_percent_of_the_time() {
    // 200 independent measurements of a noisy case (a disk emitter's irradiance, 256 samples
    // each, cosine + light sampling): value ± 2·stderr must hold the closed form in 93–97 %
    // of them (a normal estimator covers 95.4 %; with 200 seeds the binomial sd is 1.5 %).
    let xml =
        std::fs::read_to_string(common::validation_scene("disk_on_axis_irradiance.xml")).unwrap();
    let expected = 0.6957160201721342;
    let scene =
        steradian_mitsuba::load_string(&xml, Path::new("disk.xml"), Path::new("."), &[]).unwrap();
    let mut inside = 0;
    for seed in 0..200u64 {
        let out = render(
            &scene,
            &RenderOptions {
                spp: Some(256),
                seed: Some(1000 + seed),
                threads: Some(1),
                ..Default::default()
            },
        )
        .unwrap();
        let (v, e) = (
            out.film().develop().get(0, 0).x as f64,
            out.film().develop_stderr().get(0, 0).x as f64,
        );
        assert!(e > 0.0);
        if (v - expected).abs() <= 2.0 * e {
            inside += 1;
        }
    }
    let coverage = inside as f64 / 200.0;
    eprintln!("coverage of ±2σ over 200 seeds: {:.1} %", 100.0 * coverage);
    assert!((0.93..=0.97).contains(&coverage), "coverage {coverage}");
}

#[test]
fn a_triangle_mesh_emitter_reads_like_the_rectangle_it_tiles() {
    // The closed-form corner case (emitter x ∈ [0, 2], y ∈ [0, 1] at z = 1 facing −z, meter at
    // the origin facing +z: E = π·L·F, F = 0.167375010) with the emitter given as two OBJ
    // triangles: solid-angle sampling of the triangles (chosen by area, density pmf/Ω) and
    // the MIS densities of cosine-sampled hits must agree with each other and the closed form.
    let dir = temp_dir("tri-emitter");
    write_file(&dir, "rect.obj", "v 0 0 1\nv 2 0 1\nv 2 1 1\nv 0 1 1\nf 1 4 3\nf 1 3 2\n");
    let xml = r#"<scene version="3.0.0"><integrator type="path"><integer name="max_depth" value="1"/></integrator>
        <shape type="obj"><string name="filename" value="rect.obj"/><emitter type="area"><rgb name="radiance" value="2, 3, 4"/></emitter></shape>
        <shape type="disk"><transform name="to_world"><scale value="1e-4"/></transform>
          <sensor type="irradiancemeter" id="m"><film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film></sensor>
        </shape></scene>"#;
    let scene = steradian_mitsuba::load_string(xml, &dir.join("tri.xml"), &dir, &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let out = render(
        &scene,
        &RenderOptions {
            spp: Some(1 << 14),
            seed: Some(5),
            threads: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    let (v, e) = (out.film().develop().get(0, 0), out.film().develop_stderr().get(0, 0));
    std::fs::remove_dir_all(&dir).ok();
    let f = 0.167375010;
    for (c, l) in [2.0, 3.0, 4.0].iter().enumerate() {
        let expect = std::f64::consts::PI * l * f;
        let (v, e) = (v[c] as f64, e[c] as f64);
        assert!(
            e > 0.0 && (v - expect).abs() <= 5.0 * e + 1e-6 * expect,
            "channel {c}: {v} ± {e} vs {expect}"
        );
    }
}
