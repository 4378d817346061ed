//! Purpose: the `distant` sensor measures what Mitsuba 3.9.1's does (its Z-test rule on the
//! one pixel, against 1M-spp `llvm_ad_rgb` references) for each way of aiming: over the
//! scene's bounding sphere, at a point, over a target shape; a moved aim fails; a diffuse
//! ground under a uniform sky reads its mean albedo times the sky's radiance (closed form);
//! Mitsuba's refusals (a film that is not 1x1, both `to_world` and `direction`, a target that is
//! neither point nor shape) are located errors.

mod common;

use std::path::Path;

use common::{check_error, reference_scene as data, z_test_against};
use steradian::render::{render, RenderOptions};

const SPP: u32 = 16384;

fn load(name: &str) -> steradian::render::Job {
    steradian_mitsuba::load_file(&data(name), &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// `xml` loaded as if it were `tests/reference/{name}` (so that its include resolves).
fn load_as(xml: &str, name: &str) -> steradian::render::Job {
    steradian_mitsuba::load_string(xml, Path::new(name), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn each_aim_matches_mitsuba() {
    for aim in ["none", "point", "shape"] {
        let name = format!("distant-{aim}");
        let job = load(&format!("{name}.xml"));
        assert!(z_test_against(&job, SPP, &name, &name).passes(), "{name}");
    }
}

/// A changed aim changes the reading beyond the rule's tolerance: the point moved down the
/// sphere by 0.2 m, the target rectangle moved off the sphere, the rays of the untargeted
/// sensor tilted the other way.
#[test]
fn a_moved_aim_fails() {
    let cases = [
        ("point", r#"value="0.3, -0.2, 1.0""#, r#"value="0.3, -0.2, 0.8""#),
        ("shape", r#"<translate x="0.2""#, r#"<translate x="-1.0""#),
        ("none", r#"value="0.3, -0.2, -1""#, r#"value="-0.3, 0.5, -1""#),
    ];
    for (aim, from, to) in cases {
        let name = format!("distant-{aim}");
        let xml = std::fs::read_to_string(data(&format!("{name}.xml"))).unwrap();
        assert!(xml.contains(from), "{name}");
        let job = load_as(&xml.replace(from, to), &format!("{name}.xml"));
        assert!(!z_test_against(&job, SPP, &name, &format!("{name} (moved)")).passes(), "{name}");
    }
}

/// A diffuse checkerboard (equal areas of two albedos) under a uniform sky of radiance L, lit
/// only by it and seen by one bounce: every point leaves ρ·L, so the sensor aimed over the
/// whole board reads (ρ₀ + ρ₁)/2 · L, whatever its direction.
#[test]
fn a_lambertian_board_under_a_uniform_sky_reads_its_mean_albedo() {
    let xml = r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="2"/></integrator>
  <emitter type="constant"><rgb name="radiance" value="2, 1, 0.5"/></emitter>
  <shape type="rectangle">
    <transform name="to_world"><scale value="2"/></transform>
    <bsdf type="diffuse">
      <texture type="checkerboard" name="reflectance">
        <rgb name="color0" value="0.1, 0.2, 0.7"/>
        <rgb name="color1" value="0.8, 0.6, 0.2"/>
        <transform name="to_uv"><scale value="4"/></transform>
      </texture>
    </bsdf>
  </shape>
  <sensor type="distant">
    <vector name="direction" value="0.3, -0.2, -1"/>
    <shape type="rectangle" name="target"><transform name="to_world"><scale value="2"/></transform></shape>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film>
  </sensor>
</scene>"#;
    let job = load_as(xml, "board.xml");
    let out = render(
        &job,
        &RenderOptions { spp: Some(SPP), seed: Some(3), threads: Some(1), ..Default::default() },
    )
    .unwrap();
    let (v, se) = (out.film().develop().get(0, 0), out.film().develop_stderr().get(0, 0));
    let expected = [(0.1 + 0.8) / 2.0 * 2.0, (0.2 + 0.6) / 2.0, (0.7 + 0.2) / 2.0 * 0.5];
    for (c, e) in expected.into_iter().enumerate() {
        let z = (v[c] as f64 - e).abs() / se[c] as f64;
        eprintln!("channel {c}: {} ± {} vs {e} (z = {z:.2})", v[c], se[c]);
        assert!(se[c] > 0.0 && z < 4.0, "channel {c}: {} ± {} vs {e}", v[c], se[c]);
    }
}

fn load_err(sensor: &str) -> steradian_mitsuba::LoadError {
    let xml = format!(
        "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n{sensor}\n<shape type=\"sphere\"/>\n</scene>"
    );
    steradian_mitsuba::load_string(&xml, Path::new("d.xml"), Path::new("."), &[]).unwrap_err()
}

const ONE_PIXEL: &str = r#"<film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film>"#;

#[test]
fn mitsubas_refusals_are_located_errors() {
    // the default film is 768 x 576
    let e = load_err(r#"<sensor type="distant"/>"#);
    check_error(&e, Path::new("d.xml"), 3, 1, &["distant", "1x1 film", "768x576"]);
    let e = load_err(&format!(
        r#"<sensor type="distant"><vector name="direction" value="0, 0, -1"/><transform name="to_world"><translate x="1"/></transform>{ONE_PIXEL}</sensor>"#
    ));
    check_error(&e, Path::new("d.xml"), 3, 1, &["'to_world' or 'direction', not both"]);
    let e = load_err(&format!(
        r#"<sensor type="distant"><vector name="direction" value="0, 0, 0"/>{ONE_PIXEL}</sensor>"#
    ));
    check_error(&e, Path::new("d.xml"), 3, 1, &["direction", "non-zero"]);
    let e = load_err(&format!(
        r#"<sensor type="distant"><bsdf type="diffuse" name="target"/>{ONE_PIXEL}</sensor>"#
    ));
    check_error(&e, Path::new("d.xml"), 3, 24, &["'target' must be a point or a shape"]);
    let e = load_err(&format!(
        r#"<sensor type="distant"><float name="target" value="1"/>{ONE_PIXEL}</sensor>"#
    ));
    check_error(&e, Path::new("d.xml"), 3, 24, &["target"]);
    // a target shape only places the aim: a BSDF in it is not used
    let e = load_err(&format!(
        r#"<sensor type="distant"><shape type="sphere" name="target"><bsdf type="diffuse"/></shape>{ONE_PIXEL}</sensor>"#
    ));
    check_error(&e, Path::new("d.xml"), 3, 59, &["unreferenced object", "bsdf"]);
}
