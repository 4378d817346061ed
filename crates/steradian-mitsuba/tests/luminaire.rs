//! `luminaire`: a photometric file (IES or EULUMDAT) as a point source, read back in lux by an
//! irradiance meter against the inverse-square law; bad files and misuse are located errors.

use std::path::Path;

use steradian::emitter::LUMENS_PER_WATT;
use steradian::render::{render, RenderOptions};
use steradian::testkit::{temp_dir, write_file};

mod common;

const IES: &str =
    include_str!("../../steradian/src/photometry/testdata/cosine_3000lm_point_0-180.ies");
const LDT: &str =
    include_str!("../../steradian/src/photometry/testdata/cosine_3000lm_square300mm.ldt");

/// A cosine downlight (I₀ = 3000/π cd) 2.5 m above the origin, nadir turned to −y, and a tiny
/// upward-facing disk meter at (x, 0, z).
fn scene(dir: &Path, file: &str, x: f64, z: f64, extra: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  <emitter type="luminaire">
    <string name="filename" value="{}"/>
    <transform name="to_world"><rotate x="1" angle="-90"/><translate y="2.5"/></transform>
    {extra}
  </emitter>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/><rotate x="1" angle="-90"/><translate x="{x}" z="{z}"/></transform>
    <sensor type="irradiancemeter" id="meter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>
  </shape>
</scene>"#,
        dir.join(file).display()
    )
}

/// Illuminance (lx) the meter reads: its green channel is white's, ×683.
fn lux(xml: &str) -> f64 {
    let job = steradian_mitsuba::load_string(xml, Path::new("luminaire.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let sensor = job.scene.sensor_index("meter").unwrap();
    let opts = RenderOptions {
        spp: Some(4),
        seed: Some(1),
        sensor: Some(sensor),
        threads: Some(1),
        ..Default::default()
    };
    let out = render(&job, &opts).unwrap();
    out.film().develop().get(0, 0).y as f64 * LUMENS_PER_WATT as f64
}

#[test]
fn illuminance_below_a_downlight_is_the_inverse_square_law() {
    let dir = temp_dir("luminaire");
    write_file(&dir, "down.ies", IES);
    write_file(&dir, "down.ldt", LDT);
    let (h, i0) = (2.5f64, 3000.0 / std::f64::consts::PI);
    // at the tabulated angles γ = 0°, 30°, 45° the table is exact: E = I₀ h² / d⁴
    for (gamma, azimuth) in [(0.0f64, 0.0f64), (30.0, 20.0), (45.0, 250.0)] {
        let r = h * gamma.to_radians().tan();
        let (x, z) = (r * azimuth.to_radians().cos(), r * azimuth.to_radians().sin());
        let d2 = h * h + r * r;
        let want = i0 * h * h / (d2 * d2);
        for file in ["down.ies", "down.ldt"] {
            let got = lux(&scene(&dir, file, x, z, ""));
            assert!((got / want - 1.0).abs() < 1e-4, "{file} at γ = {gamma}°: {got} lx vs {want}");
        }
    }
    // scale multiplies; a colour keeps the lux
    let base = lux(&scene(&dir, "down.ies", 0.5, 0.0, ""));
    let scaled = lux(&scene(&dir, "down.ies", 0.5, 0.0, r#"<float name="scale" value="2"/>"#));
    assert!((scaled / base - 2.0).abs() < 1e-5);
    let coloured =
        lux(&scene(&dir, "down.ies", 0.5, 0.0, r#"<rgb name="color" value="1, 0.5, 0.2"/>"#));
    let job = steradian_mitsuba::load_string(
        &scene(&dir, "down.ies", 0.5, 0.0, r#"<rgb name="color" value="1, 0.5, 0.2"/>"#),
        Path::new("luminaire.xml"),
        Path::new("."),
        &[],
    )
    .unwrap();
    let sensor = job.scene.sensor_index("meter").unwrap();
    let out = render(
        &job,
        &RenderOptions {
            spp: Some(4),
            sensor: Some(sensor),
            threads: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    let rgb = out.film().develop().get(0, 0);
    let y = steradian::spectrum::luminance(steradian::Spectrum::new(rgb.x, rgb.y, rgb.z)) as f64;
    assert!((y * LUMENS_PER_WATT as f64 / base - 1.0).abs() < 1e-5, "{coloured} {y}");
}

#[test]
fn bad_luminaires_are_located_errors() {
    let dir = temp_dir("luminaire-errors");
    write_file(&dir, "down.ies", IES);
    write_file(&dir, "bad.ies", IES.replace("954.929659", "x"));
    write_file(&dir, "down.txt", IES);
    let load = |xml: &str| common::load_error(xml, "luminaire.xml");
    let e = load(&scene(&dir, "missing.ies", 0.0, 0.0, ""));
    assert!(e.contains("luminaire.xml:") && e.contains("cannot read"), "{e}");
    let e = load(&scene(&dir, "bad.ies", 0.0, 0.0, ""));
    assert!(e.contains("line 13") && e.contains("'x' is not a number"), "{e}");
    let e = load(&scene(&dir, "down.txt", 0.0, 0.0, ""));
    assert!(e.contains(".ies or .ldt"), "{e}");
    let e = load(&scene(&dir, "down.ies", 0.0, 0.0, r#"<float name="scale" value="-1"/>"#));
    assert!(e.contains("scale"), "{e}");
    let e = load(&scene(&dir, "down.ies", 0.0, 0.0, r#"<float name="intensity" value="1"/>"#));
    assert!(e.contains("intensity"), "unused parameter: {e}");
    let nested = format!(
        r#"<scene version="3.0.0"><shape type="sphere"><emitter type="luminaire"><string name="filename" value="{}"/></emitter></shape></scene>"#,
        dir.join("down.ies").display()
    );
    let e = load(&nested);
    assert!(e.contains("must be flat") && e.contains("rectangle"), "{e}");
}

/// The meter's (lux, standard error) of green (white's) channel at `spp` samples.
fn lux_with_error(xml: &str, spp: u32) -> (f64, f64) {
    let job = steradian_mitsuba::load_string(xml, Path::new("luminaire.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let sensor = job.scene.sensor_index("meter").unwrap();
    let m = steradian::render::measure(
        &job,
        &RenderOptions {
            spp: Some(spp),
            seed: Some(2),
            sensor: Some(sensor),
            ..Default::default()
        },
    )
    .unwrap();
    let k = LUMENS_PER_WATT as f64;
    (m.value[1] * k, m.stderr[1] * k)
}

/// A cosine (Lambertian) downlight nested in a 0.3 × 0.3 m rectangle facing down is an area
/// source of uniform luminance I₀/A: close below it the illuminance is L π F, F the
/// configuration factor from the meter to the rectangle (Lambert's contour integral), not the
/// point law; far away it is the point law again. Within 3 standard errors and the table's
/// interpolation (cos γ tabulated every 5°, linear: 0.1 % low at most).
#[test]
fn a_luminaire_in_a_rectangle_is_an_area_source() {
    use glam::DVec3;
    let dir = temp_dir("luminous-opening");
    write_file(&dir, "down.ies", IES);
    let i0 = 3000.0 / std::f64::consts::PI;
    let half = 0.15;
    let scene = |h: f64, x: f64, z: f64| {
        format!(
            r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  <shape type="rectangle">
    <transform name="to_world"><scale value="{half}"/><rotate x="1" angle="90"/><translate y="{h}"/></transform>
    <emitter type="luminaire">
      <string name="filename" value="{}"/>
      <transform name="to_world"><rotate x="1" angle="-90"/></transform>
    </emitter>
  </shape>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/><rotate x="1" angle="-90"/><translate x="{x}" z="{z}"/></transform>
    <sensor type="irradiancemeter" id="meter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>
  </shape>
</scene>"#,
            dir.join("down.ies").display()
        )
    };
    // near field: 0.4 m below the opening, off its axis
    let (h, x, z) = (0.4, 0.2, 0.1);
    let (got, se) = lux_with_error(&scene(h, x, z), 16384);
    let p = DVec3::new(x, 0.0, z);
    let corners = [(-half, -half), (half, -half), (half, half), (-half, half)]
        .map(|(a, b)| DVec3::new(a, h, b));
    let f = steradian::radiometry::polygon_configuration_factor(p, DVec3::Y, &corners);
    let area = (2.0 * half) * (2.0 * half);
    let want = i0 / area * std::f64::consts::PI * f;
    let d2 = h * h + x * x + z * z;
    let point_law = i0 * h * h / (d2 * d2);
    eprintln!("near field: {got} ± {se} lx; area source {want}; point law {point_law}");
    assert!((got - want).abs() <= 3.0 * se + 1e-3 * want, "{got} ± {se} vs {want}");
    assert!((point_law / want - 1.0).abs() > 0.02, "the test must tell the two apart");
    // far field: the point law
    let (h, x) = (6.0, 1.0);
    let (got, se) = lux_with_error(&scene(h, x, 0.0), 4096);
    let d2 = h * h + x * x;
    let point_law = i0 * h * h / (d2 * d2);
    assert!((got - point_law).abs() <= 3.0 * se + 2e-3 * point_law, "{got} vs {point_law}");
}
