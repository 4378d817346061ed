//! `steradian.radiometry`: the closed-form formulas of `steradian::radiometry`, in float64.
//!
//! Points and directions are 3-sequences (tuple, list or NumPy array) in metres; angles are
//! radians. Each docstring gives the formula and the units.

use glam::DVec3;
use pyo3::prelude::*;
use steradian::radiometry as r;

fn v(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// Irradiance (W/m²) on a surface with unit normal `n` at point `p` from an isotropic point
/// light of intensity `intensity` (W/sr) at `light`: H = I·max(0, n·d)/r², d the unit
/// direction to the light (the inverse-square cosine law). Points in m.
#[pyfunction]
fn point_irradiance(intensity: f64, light: [f64; 3], p: [f64; 3], n: [f64; 3]) -> f64 {
    r::point_irradiance(intensity, v(light), v(p), v(n))
}

/// Irradiance H = I·max(0, cos θ)/r² (W/m²) for intensity I (W/sr), distance r (m) and
/// incidence angle θ (rad).
#[pyfunction]
fn point_irradiance_at(intensity: f64, r: f64, theta: f64) -> f64 {
    r::point_irradiance_at(intensity, r, theta)
}

/// Flux Φ = 4π·I (W) of an isotropic point light of intensity I (W/sr).
#[pyfunction]
fn point_light_flux(intensity: f64) -> f64 {
    r::point_light_flux(intensity)
}

/// Exitance M = π·L (W/m²) of a Lambertian emitter of radiance L (W/(m²·sr)).
#[pyfunction]
fn lambertian_exitance(radiance: f64) -> f64 {
    r::lambertian_exitance(radiance)
}

/// The Lambertian BRDF ρ = a/π (1/sr) of albedo a (dimensionless; energy conservation needs
/// a ≤ 1).
#[pyfunction]
fn lambert_brdf(albedo: f64) -> f64 {
    r::lambert_brdf(albedo)
}

/// ∫ cosⁿθ dω over the hemisphere = 2π/(n+1) (sr): the integral of the classic Phong lobe of
/// exponent n.
#[pyfunction]
fn phong_lobe_integral(n: f64) -> f64 {
    r::phong_lobe_integral(n)
}

/// Normalisation (n+2)/(2π) (1/sr) of the energy-conserving Phong lobe of exponent n, so that
/// ∫ (n+2)/(2π) cosⁿα cos θ dω = 1 for a lobe centred on the normal.
#[pyfunction]
fn modified_phong_normalization(n: f64) -> f64 {
    r::modified_phong_normalization(n)
}

/// Directional albedo (dimensionless) at normal incidence of the modified Phong BRDF
/// ρ = k_d/π + k_s·(n+2)/(2π)·cosⁿα: k_d + k_s, whatever the exponent n. Energy is conserved
/// iff k_d + k_s ≤ 1.
#[pyfunction]
fn modified_phong_albedo_normal_incidence(kd: f64, ks: f64, n: f64) -> f64 {
    r::modified_phong_albedo_normal_incidence(kd, ks, n)
}

/// Solid angle (sr) of a cone of half-angle θ (rad): 2π(1 − cos θ).
#[pyfunction]
fn cone_solid_angle(half_angle: f64) -> f64 {
    r::cone_solid_angle(half_angle)
}

/// Projected solid angle ∫ cos θ dω (sr) of a cone of half-angle θ (rad) around the normal:
/// π sin²θ. A Lambertian disk of radiance L subtending θ gives irradiance H = L·π sin²θ on
/// its axis.
#[pyfunction]
fn cone_projected_solid_angle(half_angle: f64) -> f64 {
    r::cone_projected_solid_angle(half_angle)
}

/// Solid angle (sr) of the triangle (a, b, c) seen from point p (Van Oosterom & Strackee
/// 1983). Points in m.
#[pyfunction]
fn triangle_solid_angle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    r::triangle_solid_angle(v(p), v(a), v(b), v(c))
}

/// Solid angle (sr) of the planar quadrilateral (a, b, c, d) seen from point p, as two
/// triangles. Points in m.
#[pyfunction]
fn quad_solid_angle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    r::quad_solid_angle(v(p), v(a), v(b), v(c), v(d))
}

/// Solid angle (sr) of a 2a × 2b rectangle seen from distance d on its axis (lengths in m):
/// 4·asin(ab / √((a²+d²)(b²+d²))).
#[pyfunction]
fn rectangle_solid_angle_on_axis(a: f64, b: f64, d: f64) -> f64 {
    r::rectangle_solid_angle_on_axis(a, b, d)
}

/// Solid angle (sr) of a disk of radius r seen from distance h on its axis (m):
/// 2π(1 − h/√(h²+r²)).
#[pyfunction]
fn disk_solid_angle_on_axis(radius: f64, h: f64) -> f64 {
    r::disk_solid_angle_on_axis(radius, h)
}

/// Solid angle (sr) of a disk (centre c, unit normal n, radius in m) seen from any point p,
/// by Gauss–Legendre quadrature (exact to ~1e-10 away from the rim).
#[pyfunction]
fn disk_solid_angle(p: [f64; 3], c: [f64; 3], n: [f64; 3], radius: f64) -> f64 {
    r::disk_solid_angle(v(p), v(c), v(n), radius)
}

/// Solid angle (sr) of a sphere of radius r whose centre is at distance d > r (m):
/// 2π(1 − √(1 − r²/d²)); 4π from inside.
#[pyfunction]
fn sphere_solid_angle(radius: f64, d: f64) -> f64 {
    r::sphere_solid_angle(radius, d)
}

/// Irradiance (W/m²) on the axis of a Lambertian disk emitter of radiance L (W/(m²·sr)) and
/// radius r, at distance h (m), facing it: H = π L r²/(h² + r²) = L·π sin²θ.
#[pyfunction]
fn disk_on_axis_irradiance(radiance: f64, radius: f64, h: f64) -> f64 {
    r::disk_on_axis_irradiance(radiance, radius, h)
}

/// Irradiance (W/m²) at a point facing a parallel Lambertian a × b rectangle (m) of radiance
/// L (W/(m²·sr)) at distance d (m), the point on the normal through one corner (Lambert's
/// formula: the configuration factor of a differential area to a parallel rectangle, × πL).
#[pyfunction]
fn rect_parallel_corner_irradiance(radiance: f64, a: f64, b: f64, d: f64) -> f64 {
    r::rect_parallel_corner_irradiance(radiance, a, b, d)
}

/// Beer–Lambert: the fraction (dimensionless) of light crossing distance d (m) of extinction
/// σ_t (1/m), T = exp(−σ_t d).
#[pyfunction]
fn beer_lambert(sigma_t: f64, d: f64) -> f64 {
    r::beer_lambert(sigma_t, d)
}

/// Irradiance (W/m²) from a point source of intensity I (W/sr) at distance r (m) and incidence
/// θ (rad), through an absorbing slab of thickness t (m) and extinction σ_t (1/m) parallel to
/// the receiver: E = I cos θ / r² · exp(−σ_t t / cos θ).
#[pyfunction]
fn point_irradiance_through_slab(
    intensity: f64,
    r: f64,
    theta: f64,
    sigma_t: f64,
    thickness: f64,
) -> f64 {
    r::point_irradiance_through_slab(intensity, r, theta, sigma_t, thickness)
}

/// Singly scattered radiance (W/(m²·sr)) leaving a homogeneous half-space under a collimated
/// beam of normal irradiance E (W/m²) at incidence cos θ₀ = mu0, seen at cos θ = mu, albedo α,
/// phase value p (1/sr): L₁ = α p E μ₀/(μ₀ + μ).
#[pyfunction]
fn single_scattering_half_space(e: f64, albedo: f64, phase: f64, mu0: f64, mu: f64) -> f64 {
    r::single_scattering_half_space(e, albedo, phase, mu0, mu)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.setattr(
        "__doc__",
        "Closed-form radiometry (float64): solid angles (sr), irradiance (W/m²), \
        exitance, BRDF normalisations, transmittance and single scattering in media. Points \
        are 3-sequences in metres, angles radians.",
    )?;
    m.add_function(wrap_pyfunction!(point_irradiance, m)?)?;
    m.add_function(wrap_pyfunction!(point_irradiance_at, m)?)?;
    m.add_function(wrap_pyfunction!(point_light_flux, m)?)?;
    m.add_function(wrap_pyfunction!(lambertian_exitance, m)?)?;
    m.add_function(wrap_pyfunction!(lambert_brdf, m)?)?;
    m.add_function(wrap_pyfunction!(phong_lobe_integral, m)?)?;
    m.add_function(wrap_pyfunction!(modified_phong_normalization, m)?)?;
    m.add_function(wrap_pyfunction!(modified_phong_albedo_normal_incidence, m)?)?;
    m.add_function(wrap_pyfunction!(cone_solid_angle, m)?)?;
    m.add_function(wrap_pyfunction!(cone_projected_solid_angle, m)?)?;
    m.add_function(wrap_pyfunction!(triangle_solid_angle, m)?)?;
    m.add_function(wrap_pyfunction!(quad_solid_angle, m)?)?;
    m.add_function(wrap_pyfunction!(rectangle_solid_angle_on_axis, m)?)?;
    m.add_function(wrap_pyfunction!(disk_solid_angle_on_axis, m)?)?;
    m.add_function(wrap_pyfunction!(disk_solid_angle, m)?)?;
    m.add_function(wrap_pyfunction!(sphere_solid_angle, m)?)?;
    m.add_function(wrap_pyfunction!(disk_on_axis_irradiance, m)?)?;
    m.add_function(wrap_pyfunction!(rect_parallel_corner_irradiance, m)?)?;
    m.add_function(wrap_pyfunction!(beer_lambert, m)?)?;
    m.add_function(wrap_pyfunction!(point_irradiance_through_slab, m)?)?;
    m.add_function(wrap_pyfunction!(single_scattering_half_space, m)?)?;
    Ok(())
}
