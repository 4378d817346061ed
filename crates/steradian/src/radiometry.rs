//! Closed-form radiometry: the formulas the renderer is built on, in f64, each with its unit.
//!
//! | quantity            | symbol | unit       |
//! |---------------------|--------|------------|
//! | radiant flux        | Φ      | W          |
//! | radiant intensity   | I      | W/sr       |
//! | irradiance/exitance | H, M   | W/m²       |
//! | radiance            | L      | W/(m²·sr)  |
//! | solid angle         | ω      | sr         |
//! | BRDF                | ρ      | 1/sr       |
//!
//! These functions serve as ground truth for tests and `steradian verify`; the renderer's
//! Monte Carlo estimators must converge to them.

use std::f64::consts::PI;

use glam::DVec3;

/// Irradiance (W/m²) on a surface with unit normal `n` at `p` from an isotropic point light of
/// intensity `intensity` (W/sr) at `light`: H = I·max(0, n·d)/r², d the unit direction to the
/// light. The inverse-square cosine law.
pub fn point_irradiance(intensity: f64, light: DVec3, p: DVec3, n: DVec3) -> f64 {
    let d = light - p;
    let r2 = d.length_squared();
    intensity * n.dot(d / r2.sqrt()).max(0.0) / r2
}

/// H = I·cos θ / r² (W/m²) for intensity I (W/sr), distance r (m) and incidence angle θ (rad).
pub fn point_irradiance_at(intensity: f64, r: f64, theta: f64) -> f64 {
    intensity * theta.cos().max(0.0) / (r * r)
}

/// Flux Φ = 4π·I (W) of an isotropic point light of intensity I (W/sr).
pub fn point_light_flux(intensity: f64) -> f64 {
    4.0 * PI * intensity
}

/// Exitance M = π·L (W/m²) of a Lambertian emitter of radiance L (W/(m²·sr)).
pub fn lambertian_exitance(radiance: f64) -> f64 {
    PI * radiance
}

/// The Lambertian BRDF ρ₀ = a/π (1/sr) of albedo a; energy conservation requires a ≤ 1, i.e.
/// ρ₀ ≤ 1/π.
pub fn lambert_brdf(albedo: f64) -> f64 {
    albedo / PI
}

/// ∫ cosⁿθ dω over the hemisphere (sr) = 2π/(n+1): the integral of the classic Phong lobe.
pub fn phong_lobe_integral(n: f64) -> f64 {
    2.0 * PI / (n + 1.0)
}

/// Normalisation of the modified (energy-conserving) Phong lobe, (n+2)/(2π) (1/sr), so that
/// ∫ (n+2)/(2π) cosⁿα cos θ dω = 1 when the lobe is centred on the normal.
pub fn modified_phong_normalization(n: f64) -> f64 {
    (n + 2.0) / (2.0 * PI)
}

/// Directional albedo of ρ = k_d/π + k_s·(n+2)/(2π)·cosⁿα at normal incidence (where the
/// mirror direction is the normal): k_d + k_s. Energy is conserved iff k_d + k_s ≤ 1.
pub fn modified_phong_albedo_normal_incidence(kd: f64, ks: f64, _n: f64) -> f64 {
    kd + ks
}

/// Solid angle (sr) of a cone of half-angle θ: 2π(1 − cos θ).
pub fn cone_solid_angle(half_angle: f64) -> f64 {
    2.0 * PI * (1.0 - half_angle.cos())
}

/// Projected solid angle ∫cos θ dω (sr) of a cone of half-angle θ around the normal: π sin²θ.
/// A Lambertian disk of radiance L subtending θ gives irradiance H = L·π sin²θ on axis.
pub fn cone_projected_solid_angle(half_angle: f64) -> f64 {
    PI * half_angle.sin().powi(2)
}

/// Solid angle (sr) of the triangle (a, b, c) seen from `p` (Van Oosterom & Strackee 1983):
/// tan(Ω/2) = |a·(b×c)| / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|), with a, b, c relative
/// to p.
pub fn triangle_solid_angle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (a, b, c) = (a - p, b - p, c - p);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let num = a.dot(b.cross(c)).abs();
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    let half = num.atan2(den);
    2.0 * if half < 0.0 { half + PI } else { half }
}

/// Solid angle (sr) of the planar quadrilateral (a, b, c, d), as two triangles.
pub fn quad_solid_angle(p: DVec3, a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    triangle_solid_angle(p, a, b, c) + triangle_solid_angle(p, a, c, d)
}

/// Solid angle (sr) of a 2a × 2b rectangle seen from distance d on its axis:
/// 4·asin(ab / √((a²+d²)(b²+d²))).
pub fn rectangle_solid_angle_on_axis(a: f64, b: f64, d: f64) -> f64 {
    4.0 * (a * b / ((a * a + d * d) * (b * b + d * d)).sqrt()).asin()
}

/// Solid angle (sr) of a disk of radius r seen from distance h on its axis:
/// 2π(1 − h/√(h²+r²)).
pub fn disk_solid_angle_on_axis(radius: f64, h: f64) -> f64 {
    2.0 * PI * (1.0 - h / (h * h + radius * radius).sqrt())
}

/// Solid angle (sr) of a disk (centre c, unit normal n, radius r) seen from any point p, by
/// Gauss–Legendre quadrature of the flux of 1/r² through the disk in polar coordinates
/// (exact to ~1e-10 away from the rim).
pub fn disk_solid_angle(p: DVec3, c: DVec3, n: DVec3, radius: f64) -> f64 {
    let h = (p - c).dot(n);
    if h.abs() < 1e-300 {
        return 0.0;
    }
    let (u, v) = orthonormal_pair(n);
    let (nodes, weights) = gauss_legendre::<64>();
    let mut acc = 0.0;
    for (i, &xr) in nodes.iter().enumerate() {
        let r = 0.5 * radius * (xr + 1.0);
        for (j, &xp) in nodes.iter().enumerate() {
            let phi = PI * (xp + 1.0);
            let q = c + u * (r * phi.cos()) + v * (r * phi.sin());
            let d = q - p;
            let d2 = d.length_squared();
            // dω = |cos| dA / d², cos = |h| / |d|
            acc += weights[i] * weights[j] * r * h.abs() / (d2 * d2.sqrt());
        }
    }
    acc * 0.5 * radius * PI
}

/// Solid angle (sr) of a sphere of radius r whose centre is at distance d > r: 2π(1 − √(1 − r²/d²)).
/// Returns 4π from inside.
pub fn sphere_solid_angle(radius: f64, d: f64) -> f64 {
    if d <= radius {
        return 4.0 * PI;
    }
    2.0 * PI * (1.0 - (1.0 - (radius / d).powi(2)).sqrt())
}

/// Irradiance (W/m²) at a point on the axis of a Lambertian disk emitter of radiance L
/// (W/(m²·sr)) and radius r, at distance h, facing it: H = π L r²/(h² + r²) = L·π sin²θ.
pub fn disk_on_axis_irradiance(radiance: f64, radius: f64, h: f64) -> f64 {
    PI * radiance * radius * radius / (h * h + radius * radius)
}

/// Irradiance (W/m²) at a point facing a parallel Lambertian a × b rectangle of radiance L at
/// distance d, the point lying on the normal through one corner (Lambert's formula; the
/// configuration factor of a differential area to a parallel rectangle).
pub fn rect_parallel_corner_irradiance(radiance: f64, a: f64, b: f64, d: f64) -> f64 {
    let x = a / d;
    let y = b / d;
    let sx = (1.0 + x * x).sqrt();
    let sy = (1.0 + y * y).sqrt();
    let f = (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI);
    PI * radiance * f
}

/// Beer–Lambert: the fraction of light that crosses a distance `d` (m) of a medium of
/// extinction coefficient `sigma_t` (1/m), T = exp(−σ_t d).
pub fn beer_lambert(sigma_t: f64, d: f64) -> f64 {
    (-sigma_t * d).exp()
}

/// Singly scattered radiance (W/(m²·sr)) leaving a homogeneous half-space lit by a collimated
/// beam of irradiance `e` (W/m², on a plane facing the beam) at incidence cos θ₀ = `mu0`, seen
/// at exitance cos θ = `mu` (both from the surface normal), for single-scattering albedo
/// `albedo` and phase-function value `phase` (1/sr) at the scattering angle between beam and
/// view: L₁ = α p E μ₀ / (μ₀ + μ) (Chandrasekhar 1960, §1.4; depth z contributes
/// σ_s p E e^(−σ_t z/μ₀) e^(−σ_t z/μ) dz/μ, σ_t itself cancels).
pub fn single_scattering_half_space(e: f64, albedo: f64, phase: f64, mu0: f64, mu: f64) -> f64 {
    albedo * phase * e * mu0 / (mu0 + mu)
}

/// Irradiance (W/m²) from an isotropic point source of intensity I (W/sr) at distance r, at
/// incidence angle θ, through an absorbing slab of thickness `thickness` (m, parallel to the
/// receiving plane, crossed at the same angle θ) of extinction `sigma_t` (1/m) in otherwise
/// clear space: E = I cos θ / r² · exp(−σ_t thickness / cos θ).
pub fn point_irradiance_through_slab(
    intensity: f64,
    r: f64,
    theta: f64,
    sigma_t: f64,
    thickness: f64,
) -> f64 {
    point_irradiance_at(intensity, r, theta) * beer_lambert(sigma_t, thickness / theta.cos())
}

/// Configuration factor from a differential area at `p` with unit normal `n` to a planar
/// polygon (`vertices` in order, all on the side `n` points to): Lambert's contour integral
/// F = (1/2π) Σ γ_i n·u_i over the edges, γ_i the angle the edge subtends at `p` and u_i the
/// unit normal of the plane through `p` and the edge. A Lambertian polygon of radiance L gives
/// the element an irradiance E = π L F (W/m²): parallel, perpendicular or tilted rectangles
/// alike (the cases of CIE 171:2006).
pub fn polygon_configuration_factor(p: DVec3, n: DVec3, vertices: &[DVec3]) -> f64 {
    let k = vertices.len();
    let sum: f64 = (0..k)
        .map(|i| {
            let (a, b) = (vertices[i] - p, vertices[(i + 1) % k] - p);
            let c = a.cross(b);
            let gamma = c.length().atan2(a.dot(b));
            gamma * n.dot(c.normalize_or_zero())
        })
        .sum();
    (sum / (2.0 * PI)).abs()
}

fn orthonormal_pair(n: DVec3) -> (DVec3, DVec3) {
    let n = n.normalize();
    let a = if n.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
    let u = n.cross(a).normalize();
    (u, n.cross(u))
}

/// N-point Gauss–Legendre nodes and weights on [−1, 1] (Newton iteration on P_N); exact for
/// polynomials of degree 2N − 1.
pub fn gauss_legendre<const N: usize>() -> ([f64; N], [f64; N]) {
    let mut x = [0.0; N];
    let mut w = [0.0; N];
    for i in 0..N / 2 {
        let mut z = (PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (mut p1, mut p2) = (1.0, 0.0);
            for j in 0..N {
                let p3 = p2;
                p2 = p1;
                p1 = ((2 * j + 1) as f64 * z * p2 - j as f64 * p3) / (j + 1) as f64;
            }
            let pp = N as f64 * (z * p1 - p2) / (z * z - 1.0);
            let dz = p1 / pp;
            z -= dz;
            if dz.abs() < 1e-15 {
                let wi = 2.0 / ((1.0 - z * z) * pp * pp);
                x[i] = -z;
                x[N - 1 - i] = z;
                w[i] = wi;
                w[N - 1 - i] = wi;
                break;
            }
        }
    }
    (x, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    #[test]
    fn solid_angles_agree_across_formulas() {
        // a rectangle on axis, by the closed form and as two triangles
        let (a, b, d) = (0.5, 1.0, 2.0);
        let p = DVec3::new(0.0, 0.0, d);
        let q = quad_solid_angle(
            p,
            DVec3::new(-a, -b, 0.0),
            DVec3::new(a, -b, 0.0),
            DVec3::new(a, b, 0.0),
            DVec3::new(-a, b, 0.0),
        );
        assert!(close(q, rectangle_solid_angle_on_axis(a, b, d), 1e-12));
        // a disk on axis: quadrature vs closed form
        let s = disk_solid_angle(DVec3::new(0.0, 0.0, 1.5), DVec3::ZERO, DVec3::Z, 0.8);
        assert!(close(s, disk_solid_angle_on_axis(0.8, 1.5), 1e-10), "{s}");
        // a cone subtending a sphere
        let (r, dist) = (1.0, 3.0);
        assert!(close(sphere_solid_angle(r, dist), cone_solid_angle((r / dist).asin()), 1e-12));
        // the whole hemisphere seen by a triangle fan around a point just above a huge plane
        let big = 1e7;
        let h = triangle_solid_angle(
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(-big, -big, 0.0),
            DVec3::new(big, -big, 0.0),
            DVec3::new(0.0, big, 0.0),
        );
        assert!(close(h, 2.0 * PI, 1e-5), "{h}");
    }

    #[test]
    fn irradiance_formulas() {
        // a disk subtending half-angle θ gives L·π·sin²θ on axis
        let (l, r, h) = (2.0f64, 0.5f64, 1.2f64);
        let theta = (r / h).atan();
        assert!(close(
            disk_on_axis_irradiance(l, r, h),
            l * cone_projected_solid_angle(theta),
            1e-12
        ));
        // inverse square and cosine
        let e = point_irradiance(
            100.0,
            DVec3::new(0.0, 0.0, 2.0),
            DVec3::ZERO,
            DVec3::new(0.0, 60f64.to_radians().sin(), 60f64.to_radians().cos()),
        );
        assert!(close(e, 12.5, 1e-12));
        // a point behind the surface receives nothing
        assert_eq!(point_irradiance(1.0, DVec3::new(0.0, 0.0, -1.0), DVec3::ZERO, DVec3::Z), 0.0);
        // the corner formula: four corner rectangles tile a centred one
        let (a, b, d) = (0.7, 0.4, 1.1);
        let four = 4.0 * rect_parallel_corner_irradiance(1.0, a, b, d);
        // centred 2a×2b rectangle on axis, by quadrature of cos²/d² over its area
        let n = 400;
        let mut acc = 0.0;
        for i in 0..n {
            for j in 0..n {
                let x = -a + 2.0 * a * (i as f64 + 0.5) / n as f64;
                let y = -b + 2.0 * b * (j as f64 + 0.5) / n as f64;
                let r2 = x * x + y * y + d * d;
                acc += d * d / (r2 * r2) * (4.0 * a * b) / (n * n) as f64;
            }
        }
        assert!(close(four, acc, 1e-4), "{four} vs {acc}");
    }

    /// Lambert's contour integral agrees with the closed form for a parallel rectangle and
    /// with a 64 × 64 Gauss–Legendre quadrature of cos θ cos θ' / (π r²) for a perpendicular
    /// and a tilted one.
    #[test]
    fn polygon_configuration_factors() {
        let (a, b, d) = (2.0, 1.5, 1.2);
        let rect = [
            DVec3::new(0.0, 0.0, d),
            DVec3::new(a, 0.0, d),
            DVec3::new(a, b, d),
            DVec3::new(0.0, b, d),
        ];
        let f = polygon_configuration_factor(DVec3::ZERO, DVec3::Z, &rect);
        let want = rect_parallel_corner_irradiance(1.0, a, b, d) / PI;
        assert!((f / want - 1.0).abs() < 1e-12, "{f} vs {want}");
        // quadrature over a rectangle corner + s·u + t·v (s, t in [0, 1]) with normal m
        let (x, w) = gauss_legendre::<64>();
        let quad = |p: DVec3, n: DVec3, corner: DVec3, u: DVec3, v: DVec3| {
            let m = u.cross(v).normalize();
            let mut sum = 0.0;
            for i in 0..64 {
                for j in 0..64 {
                    let q = corner + u * (0.5 + 0.5 * x[i]) + v * (0.5 + 0.5 * x[j]);
                    let r = q - p;
                    let r2 = r.length_squared();
                    let cos = n.dot(r) / r2.sqrt();
                    let cos_q = m.dot(r).abs() / r2.sqrt();
                    sum += w[i] * w[j] * 0.25 * cos * cos_q / (PI * r2);
                }
            }
            sum * u.cross(v).length()
        };
        // a wall x in [0, 2], z in [0, 1.5] at y = 0, seen from the floor point (0, 1, 0)
        let (p, n) = (DVec3::new(0.0, 1.0, 0.0), DVec3::Z);
        let wall = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 1.5),
            DVec3::new(0.0, 0.0, 1.5),
        ];
        let f = polygon_configuration_factor(p, n, &wall);
        let q = quad(p, n, wall[0], wall[1] - wall[0], wall[3] - wall[0]);
        assert!((f / q - 1.0).abs() < 1e-6, "perpendicular: {f} vs {q}");
        // a tilted one, wholly above the element's plane
        let tilted = [
            DVec3::new(-1.0, 0.5, 1.0),
            DVec3::new(1.0, 0.5, 1.0),
            DVec3::new(1.0, 1.5, 2.0),
            DVec3::new(-1.0, 1.5, 2.0),
        ];
        let f = polygon_configuration_factor(DVec3::ZERO, DVec3::Z, &tilted);
        let q =
            quad(DVec3::ZERO, DVec3::Z, tilted[0], tilted[1] - tilted[0], tilted[3] - tilted[0]);
        assert!((f / q - 1.0).abs() < 1e-6, "tilted: {f} vs {q}");
    }

    /// Beer–Lambert composes over consecutive distances, and the slab's path length grows as
    /// 1/cos θ.
    #[test]
    fn transmittance_through_media() {
        let (s, a, b) = (0.7, 0.4, 1.3);
        assert!((beer_lambert(s, a) * beer_lambert(s, b) - beer_lambert(s, a + b)).abs() < 1e-15);
        assert_eq!(beer_lambert(s, 0.0), 1.0);
        let (i, r, t) = (10.0, 2.0, 0.5);
        let normal = point_irradiance_through_slab(i, r, 0.0, s, t);
        assert!((normal - i / (r * r) * (-s * t).exp()).abs() < 1e-12);
        let theta = 60f64.to_radians();
        let oblique = point_irradiance_through_slab(i, r, theta, s, t);
        assert!((oblique - i * 0.5 / (r * r) * (-s * t * 2.0).exp()).abs() < 1e-12);
    }
}
