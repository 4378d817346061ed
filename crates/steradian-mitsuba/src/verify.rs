//! The built-in verification suite behind `steradian verify`: closed-form radiometry cases
//! rendered through the whole pipeline (XML → scene → meter → estimate ± standard error), and
//! pure-math checks of the `radiometry` module. The cases and their scenes are embedded, so
//! an installed binary can check itself.
//!
//! Pass rule (from the suite): |measured − expected| ≤ tolerance·|expected| per channel
//! (`tolerance_abs` where the expected value is 0), at the case's own spp, with a fixed seed.

use std::path::Path;

use serde_json::Value;
use steradian::radiometry as rad;
use steradian::render::{render, RenderOptions};

/// The embedded scenes, by the file name the cases use.
const SCENES: &[(&str, &str)] = &[
    (
        "point_normal_incidence.xml",
        include_str!("../../../scenes/validation/point_normal_incidence.xml"),
    ),
    (
        "point_inverse_square.xml",
        include_str!("../../../scenes/validation/point_inverse_square.xml"),
    ),
    (
        "disk_on_axis_irradiance.xml",
        include_str!("../../../scenes/validation/disk_on_axis_irradiance.xml"),
    ),
    (
        "rect_parallel_corner_irradiance.xml",
        include_str!("../../../scenes/validation/rect_parallel_corner_irradiance.xml"),
    ),
    (
        "area_emitter_one_sided.xml",
        include_str!("../../../scenes/validation/area_emitter_one_sided.xml"),
    ),
    (
        "env_constant_irradiance.xml",
        include_str!("../../../scenes/validation/env_constant_irradiance.xml"),
    ),
    (
        "furnace_convex_sphere.xml",
        include_str!("../../../scenes/validation/furnace_convex_sphere.xml"),
    ),
    ("emissive_room.xml", include_str!("../../../scenes/validation/emissive_room.xml")),
    (
        "rect_perpendicular_corner_irradiance.xml",
        include_str!("../../../scenes/validation/rect_perpendicular_corner_irradiance.xml"),
    ),
    ("room_flux_balance.xml", include_str!("../../../scenes/validation/room_flux_balance.xml")),
    (
        "overcast_sky_horizontal_illuminance.xml",
        include_str!("../../../scenes/validation/overcast_sky_horizontal_illuminance.xml"),
    ),
    (
        "roof_opening_sky_component.xml",
        include_str!("../../../scenes/validation/roof_opening_sky_component.xml"),
    ),
    (
        "window_sky_component.xml",
        include_str!("../../../scenes/validation/window_sky_component.xml"),
    ),
    (
        "sun_and_sky_horizontal_illuminance.xml",
        include_str!("../../../scenes/validation/sun_and_sky_horizontal_illuminance.xml"),
    ),
];
const CASES: &str = include_str!("../../../scenes/validation/cases.json");
const MATH_CASES: &str = include_str!("../../../scenes/validation/math_cases.json");

/// The outcome of one rendered case.
#[derive(Clone, Debug)]
pub struct CaseResult {
    pub name: String,
    pub quantity: String,
    pub units: String,
    pub spp: u32,
    pub expected: [f64; 3],
    pub measured: [f64; 3],
    /// Standard error of the measured mean, per channel.
    pub stderr: [f64; 3],
    /// (measured − expected)/σ per channel, σ being the standard error combined with the
    /// f32 resolution of the value (1e-6 relative), so that exact (zero-variance) estimates
    /// of delta lights do not report infinite z-scores for rounding.
    pub z: [f64; 3],
    /// The case's pass bound per channel (absolute).
    pub bound: [f64; 3],
    pub pass: bool,
    pub seconds: f64,
}

/// The outcome of one math check.
#[derive(Clone, Debug)]
pub struct MathResult {
    pub name: String,
    pub quantity: String,
    pub expected: f64,
    pub measured: f64,
    pub tolerance: f64,
    pub pass: bool,
}

fn as_f64(v: &Value, what: &str) -> Result<f64, String> {
    v.as_f64().ok_or_else(|| format!("{what} is not a number"))
}

fn triple(v: &Value, what: &str) -> Result<[f64; 3], String> {
    let a = v
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| format!("{what} must hold 3 numbers"))?;
    Ok([as_f64(&a[0], what)?, as_f64(&a[1], what)?, as_f64(&a[2], what)?])
}

/// Names of the rendered cases.
pub fn case_names() -> Vec<String> {
    let doc: Value = serde_json::from_str(CASES).expect("embedded cases.json is valid JSON");
    doc["cases"]
        .as_array()
        .map(|a| a.iter().filter_map(|c| c["name"].as_str().map(String::from)).collect())
        .unwrap_or_default()
}

/// Runs the rendered case `name` (at its own spp, or `spp_override`) with `seed`.
pub fn run_case(
    name: &str,
    seed: u64,
    spp_override: Option<u32>,
    threads: Option<usize>,
) -> Result<CaseResult, String> {
    let doc: Value = serde_json::from_str(CASES).map_err(|e| e.to_string())?;
    let case = doc["cases"]
        .as_array()
        .and_then(|a| a.iter().find(|c| c["name"] == name))
        .ok_or_else(|| format!("no case named '{name}'"))?;
    let file = case["file"].as_str().ok_or("case without file")?;
    let file_name = Path::new(file).file_name().and_then(|f| f.to_str()).ok_or("bad file")?;
    let xml = SCENES
        .iter()
        .find(|(n, _)| *n == file_name)
        .map(|(_, x)| *x)
        .ok_or_else(|| format!("scene {file} is not embedded"))?;
    let scene =
        crate::load_string(xml, Path::new(file), Path::new("."), &[]).map_err(|e| e.to_string())?;
    let sensor_id = case["sensor_id"].as_str().ok_or("case without sensor_id")?;
    let sensor = scene
        .scene
        .sensor_index(sensor_id)
        .ok_or_else(|| format!("{file} has no sensor '{sensor_id}'"))?;
    let spp = spp_override.unwrap_or(as_f64(&case["spp"], "spp")? as u32);
    let out = render(
        &scene,
        &RenderOptions {
            spp: Some(spp),
            seed: Some(seed),
            sensor: Some(sensor),
            threads,
            ..Default::default()
        },
    )
    .map_err(|e| e.to_string())?;
    let image = out.film().develop();
    let err = out.film().develop_stderr();
    let (measured, stderr) = match case["reduce"].as_str() {
        Some("pixel") => {
            let (m, s) = (image.get(0, 0), err.get(0, 0));
            ([m.x as f64, m.y as f64, m.z as f64], [s.x as f64, s.y as f64, s.z as f64])
        }
        Some("mean") => {
            let m = image.channel_means();
            // pixels are independent: the error of the mean is √(Σσ²)/N
            let n = (err.width * err.height) as f64;
            let mut s = [0.0; 3];
            for y in 0..err.height {
                for x in 0..err.width {
                    let e = err.get(x, y);
                    for (c, sc) in s.iter_mut().enumerate() {
                        *sc += (e[c] as f64).powi(2);
                    }
                }
            }
            (m, s.map(|v| v.sqrt() / n))
        }
        other => return Err(format!("unknown reduce {other:?}")),
    };
    let expected = triple(&case["expected"], "expected")?;
    let bound = match (case["tolerance"].as_f64(), case["tolerance_abs"].as_f64()) {
        (Some(t), _) => expected.map(|e| t * e.abs()),
        (None, Some(a)) => [a; 3],
        _ => return Err("case without tolerance".into()),
    };
    let z = [0, 1, 2].map(|c| {
        let d = measured[c] - expected[c];
        let sigma = stderr[c].hypot(1e-6 * measured[c].abs());
        if sigma > 0.0 {
            d / sigma
        } else if d == 0.0 {
            0.0
        } else {
            f64::INFINITY.copysign(d)
        }
    });
    let pass = (0..3).all(|c| (measured[c] - expected[c]).abs() <= bound[c]);
    Ok(CaseResult {
        name: name.to_string(),
        quantity: case["quantity"].as_str().unwrap_or("").to_string(),
        units: case["units"].as_str().unwrap_or("").to_string(),
        spp,
        expected,
        measured,
        stderr,
        z,
        bound,
        pass,
        seconds: out.elapsed.as_secs_f64(),
    })
}

/// Evaluates one math case with the `radiometry` module.
fn eval_math(name: &str, inputs: &Value) -> Result<f64, String> {
    let get = |k: &str| {
        inputs[k].as_f64().ok_or_else(|| format!("math case {name}: missing input '{k}'"))
    };
    // Hemispherical integrals are computed by quadrature of the radiometry functions, so the
    // check exercises the normalisations rather than restating them.
    Ok(match name {
        "lambert_cosine_integral" => hemisphere_integral(|ct| ct),
        "lambert_brdf_normalization" | "lambert_albedo_0p7" => {
            let a = get("albedo")?;
            hemisphere_integral(|ct| rad::lambert_brdf(a) * ct)
        }
        n if n.starts_with("phong_lobe_integral") => {
            let e = get("n")?;
            let q = hemisphere_integral(|ct| ct.powf(e));
            check_close(q, rad::phong_lobe_integral(e), name)?
        }
        n if n.starts_with("modified_phong_normalization") => {
            let e = get("n")?;
            hemisphere_integral(|ct| rad::modified_phong_normalization(e) * ct.powf(e) * ct)
        }
        "modified_phong_albedo_normal_incidence" => {
            let (kd, ks, e) = (get("kd")?, get("ks")?, get("n")?);
            let q = hemisphere_integral(|ct| {
                (rad::lambert_brdf(kd) + ks * rad::modified_phong_normalization(e) * ct.powf(e))
                    * ct
            });
            check_close(q, rad::modified_phong_albedo_normal_incidence(kd, ks, e), name)?
        }
        n if n.starts_with("blinn_phong_ndf_normalization") => {
            let e = get("n")?;
            hemisphere_integral(|ct| rad::modified_phong_normalization(e) * ct.powf(e) * ct)
        }
        "cone_solid_angle_30deg" => rad::cone_solid_angle(get("half_angle_deg")?.to_radians()),
        "disk_projected_solid_angle_30deg" => {
            rad::cone_projected_solid_angle(get("half_angle_deg")?.to_radians())
        }
        "rectangle_solid_angle_on_axis" => {
            let (a, b, d) = (get("a")?, get("b")?, get("d")?);
            use glam::DVec3;
            let p = DVec3::new(0.0, 0.0, d);
            let q = rad::quad_solid_angle(
                p,
                DVec3::new(-a, -b, 0.0),
                DVec3::new(a, -b, 0.0),
                DVec3::new(a, b, 0.0),
                DVec3::new(-a, b, 0.0),
            );
            check_close(q, rad::rectangle_solid_angle_on_axis(a, b, d), name)?
        }
        "point_light_flux" => rad::point_light_flux(get("I")?),
        "point_light_irradiance_example" => {
            rad::point_irradiance_at(get("I")?, get("r")?, get("theta_deg")?.to_radians())
        }
        "lambertian_exitance" => rad::lambertian_exitance(get("L")?),
        other => return Err(format!("unknown math case '{other}'")),
    })
}

/// Two independent ways to the same number must agree to 1e-10 before either is reported.
fn check_close(a: f64, b: f64, name: &str) -> Result<f64, String> {
    if (a - b).abs() <= 1e-10 * b.abs().max(1e-300) {
        Ok(b)
    } else {
        Err(format!("math case {name}: quadrature {a} and closed form {b} disagree"))
    }
}

/// ∫ f(cos θ) dω over the upper hemisphere for an azimuth-independent integrand, by
/// 64-point Gauss–Legendre on [0, 1] in cos θ split into 64 panels (dω = 2π d(cos θ)).
fn hemisphere_integral(f: impl Fn(f64) -> f64) -> f64 {
    let (x, w) = rad::gauss_legendre::<16>();
    let panels = 64;
    let mut acc = 0.0;
    for k in 0..panels {
        let (a, b) = (k as f64 / panels as f64, (k + 1) as f64 / panels as f64);
        for i in 0..x.len() {
            let ct = 0.5 * (b - a) * x[i] + 0.5 * (a + b);
            acc += w[i] * 0.5 * (b - a) * f(ct);
        }
    }
    2.0 * std::f64::consts::PI * acc
}

/// Runs every math case.
pub fn run_math_cases() -> Result<Vec<MathResult>, String> {
    let doc: Value = serde_json::from_str(MATH_CASES).map_err(|e| e.to_string())?;
    let cases = doc["cases"].as_array().ok_or("math_cases.json has no cases")?;
    cases
        .iter()
        .map(|c| {
            let name = c["name"].as_str().ok_or("math case without name")?;
            let expected = as_f64(&c["expected"], "expected")?;
            let tolerance = as_f64(&c["tolerance"], "tolerance")?;
            let measured = eval_math(name, &c["inputs"])?;
            Ok(MathResult {
                name: name.to_string(),
                quantity: c["quantity"].as_str().unwrap_or("").to_string(),
                expected,
                measured,
                tolerance,
                pass: (measured - expected).abs() <= tolerance * expected.abs().max(1e-300),
            })
        })
        .collect()
}
