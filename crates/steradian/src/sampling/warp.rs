//! Warps: maps from uniform samples in [0,1)² to directions and points, each with its
//! density. Solid-angle densities are in 1/sr, area densities in 1/m².

use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI};

use glam::{Vec2, Vec3};

/// Uniform point on the unit disk (Shirley–Chiu concentric map: low distortion, so
/// stratification survives the warp).
#[inline]
pub fn square_to_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let a = 2.0 * u - Vec2::ONE;
    if a.x == 0.0 && a.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, phi) = if a.x.abs() > a.y.abs() { (a.x, FRAC_PI_4 * (a.y / a.x)) } else { (a.y, FRAC_PI_2 - FRAC_PI_4 * (a.x / a.y)) };
    let (s, c) = phi.sin_cos();
    Vec2::new(r * c, r * s)
}

/// Cosine-weighted direction on the +z hemisphere; density cos θ / π.
#[inline]
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = square_to_uniform_disk_concentric(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

#[inline]
pub fn square_to_cosine_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z > 0.0 {
        w.z * FRAC_1_PI
    } else {
        0.0
    }
}

/// Uniform direction on the unit sphere; density 1/(4π).
#[inline]
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.y;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.x).sin_cos();
    Vec3::new(r * c, r * s, z)
}

pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Uniform direction on the +z hemisphere; density 1/(2π).
#[inline]
pub fn square_to_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = u.y;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.x).sin_cos();
    Vec3::new(r * c, r * s, z)
}

pub const UNIFORM_HEMISPHERE_PDF: f32 = 1.0 / (2.0 * PI);

/// Uniform direction in the cone of half-angle θmax around +z (`cos_max = cos θmax`);
/// density 1 / (2π (1 − cos θmax)).
#[inline]
pub fn square_to_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    // cos θ = 1 − u·(1 − cosmax), written to keep precision for tiny cones.
    let one_minus = 1.0 - cos_max;
    let cos_t = 1.0 - u.y * one_minus;
    let sin2 = (u.y * one_minus * (2.0 - u.y * one_minus)).max(0.0);
    let sin_t = sin2.sqrt();
    let (s, c) = (2.0 * PI * u.x).sin_cos();
    Vec3::new(sin_t * c, sin_t * s, cos_t)
}

#[inline]
pub fn square_to_uniform_cone_pdf(w: Vec3, cos_max: f32) -> f32 {
    if w.z >= cos_max {
        1.0 / (2.0 * PI * (1.0 - cos_max))
    } else {
        0.0
    }
}

/// Uniform barycentrics (b1, b2) on a triangle (Heitz 2019 low-distortion map).
#[inline]
pub fn square_to_uniform_triangle(u: Vec2) -> Vec2 {
    let (mut b0, mut b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    b0 = b0.clamp(0.0, 1.0);
    b1 = b1.clamp(0.0, 1.0);
    Vec2::new(b0, b1)
}

/// Standard-normal pair from two uniforms (Box–Muller), used by the Gaussian filter tests.
#[inline]
pub fn square_to_std_normal(u: Vec2) -> Vec2 {
    let r = (-2.0 * (1.0 - u.x).ln()).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec2::new(r * c, r * s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    fn u2(r: &mut Pcg32) -> Vec2 {
        Vec2::new(r.next_f32(), r.next_f32())
    }

    /// Integrating f/pdf over samples estimates ∫f; with f = pdf the estimate is the measure of
    /// the domain. Checks that each warp's density integrates to 1 and that points land in
    /// the domain.
    #[test]
    fn warps_are_normalised() {
        let mut r = Pcg32::new(7, 3);
        let n = 200_000;
        // cosine hemisphere: E[1/pdf] = ∫ dω over hemisphere = 2π
        let mut acc = 0.0f64;
        let mut acc2 = 0.0f64;
        for _ in 0..n {
            let w = square_to_cosine_hemisphere(u2(&mut r));
            assert!((w.length() - 1.0).abs() < 1e-4 && w.z >= 0.0);
            // E[cos θ / pdf] = ∫ cos dω = π (zero variance)
            acc += (w.z / square_to_cosine_hemisphere_pdf(w)) as f64;
            // E[1] over sphere points with z > 0.5 / pdf: solid angle of the 60° cap = 2π(1-cos60°) = π
            let s = square_to_uniform_sphere(u2(&mut r));
            if s.z > 0.5 {
                acc2 += 1.0 / UNIFORM_SPHERE_PDF as f64;
            }
        }
        assert!((acc / n as f64 - std::f64::consts::PI).abs() < 1e-3);
        // Bernoulli(1/4) × 4π: σ = 4π·sqrt(p(1−p)/n)
        let sigma = 4.0 * std::f64::consts::PI * (0.25f64 * 0.75 / n as f64).sqrt();
        assert!((acc2 / n as f64 - std::f64::consts::PI).abs() < 5.0 * sigma);
    }

    #[test]
    fn cone_samples_stay_inside_and_tiny_cones_are_accurate() {
        let mut r = Pcg32::new(1, 1);
        for cos_max in [0.0f32, 0.5, 0.99, 1.0 - 1e-6] {
            for _ in 0..1000 {
                let w = square_to_uniform_cone(u2(&mut r), cos_max);
                assert!((w.length() - 1.0).abs() < 1e-4);
                assert!(w.z >= cos_max - 1e-6);
            }
        }
    }

    #[test]
    fn triangle_barycentrics_are_uniform() {
        let mut r = Pcg32::new(5, 9);
        let n = 100_000;
        let mut mean = Vec2::ZERO;
        for _ in 0..n {
            let b = square_to_uniform_triangle(u2(&mut r));
            assert!(b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 + 1e-6);
            mean += b / n as f32;
        }
        // centroid (1/3, 1/3); σ of each coordinate ≈ sqrt(1/18/n) = 7.5e-4
        assert!((mean - Vec2::splat(1.0 / 3.0)).abs().max_element() < 5.0 * 7.5e-4);
    }
}
