//! Warps: maps from uniform samples in [0,1)² to directions and points, each with its
//! density. Solid-angle densities are in 1/sr, area densities in 1/m².

use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI};

use glam::{Vec2, Vec3};

/// (sin x, cos x) for |x| ≤ π/4 from their Taylor polynomials to degree 11 and 10 (remainder
/// below 2·10⁻¹⁰; the result is within a few ulps). libm's `sinf`/`cosf` reduce arbitrary
/// arguments and cost a call; the warps only need small ones.
#[inline]
fn sin_cos_small(x: f32) -> (f32, f32) {
    let x2 = x * x;
    let s = x
        * (1.0
            + x2 * (-1.0 / 6.0
                + x2 * (1.0 / 120.0
                    + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362_880.0 + x2 * (-1.0 / 39_916_800.0))))));
    let c = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 + x2 * (-1.0 / 3_628_800.0)))));
    (s, c)
}

/// (sin 2πt, cos 2πt) for t in [0, 1] (a sample coordinate): the nearest quarter turn is split
/// off exactly, the rest (at most an eighth of a turn) goes through [`sin_cos_small`].
#[inline]
pub(crate) fn sin_cos_turns(t: f32) -> (f32, f32) {
    let q = (4.0 * t + 0.5).floor();
    let (s, c) = sin_cos_small((4.0 * t - q) * FRAC_PI_2);
    // rotate by q quarter turns
    match (q as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// Uniform point on the unit disk (Shirley–Chiu concentric map: low distortion, so
/// stratification survives the warp).
#[inline]
pub fn square_to_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let a = 2.0 * u - Vec2::ONE;
    if a.x == 0.0 && a.y == 0.0 {
        return Vec2::ZERO;
    }
    // φ = π/4·(a.y/a.x), or π/2 − π/4·(a.x/a.y): both within π/4 of an axis
    if a.x.abs() > a.y.abs() {
        let (s, c) = sin_cos_small(FRAC_PI_4 * (a.y / a.x));
        Vec2::new(a.x * c, a.x * s)
    } else {
        let (s, c) = sin_cos_small(FRAC_PI_4 * (a.x / a.y));
        Vec2::new(a.y * s, a.y * c)
    }
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
    let (s, c) = sin_cos_turns(u.x);
    Vec3::new(r * c, r * s, z)
}

pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Uniform direction on the +z hemisphere; density 1/(2π).
#[inline]
pub fn square_to_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = u.y;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = sin_cos_turns(u.x);
    Vec3::new(r * c, r * s, z)
}

pub const UNIFORM_HEMISPHERE_PDF: f32 = 1.0 / (2.0 * PI);

/// Uniform direction in the cone of half-angle θmax around +z, given `one_minus` =
/// 1 − cos θmax; density 1 / (2π (1 − cos θmax)). The caller passes 1 − cos θmax rather than
/// cos θmax because for a tiny cone it can compute it without cancellation (a sphere seen
/// from afar: sin² θmax / (1 + cos θmax)), which `1.0 - cos_max` in single precision cannot.
#[inline]
pub fn square_to_uniform_cone(u: Vec2, one_minus: f32) -> Vec3 {
    // cos θ = 1 − u·(1 − cos θmax); sin² θ from the same product, so no cancellation either
    let cos_t = 1.0 - u.y * one_minus;
    let sin2 = (u.y * one_minus * (2.0 - u.y * one_minus)).max(0.0);
    let sin_t = sin2.sqrt();
    let (s, c) = sin_cos_turns(u.x);
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
    let (s, c) = sin_cos_turns(u.y);
    Vec2::new(r * c, r * s)
}

/// x ∈ [0, 1] with density ∝ (1 − x)·a + x·b (a, b ≥ 0, not both 0): the inverse of the CDF
/// (a·x + (b − a)·x²/2) / ((a + b)/2), in the form that stays exact as b → a.
#[inline]
pub fn unit_to_linear(u: f32, a: f32, b: f32) -> f32 {
    let root = ((1.0 - u) * a * a + u * b * b).sqrt();
    let den = a + root;
    if den <= 0.0 {
        return 0.0;
    }
    (u * (a + b) / den).min(1.0)
}

/// Density on [0, 1]² of [`square_to_bilinear`] with corner weights `w` = [w(0, 0), w(1, 0),
/// w(0, 1), w(1, 1)]: the bilinear interpolation of `w` over its mean.
#[inline]
pub fn square_to_bilinear_pdf(p: Vec2, w: [f32; 4]) -> f32 {
    let sum = w[0] + w[1] + w[2] + w[3];
    if sum <= 0.0 {
        return 1.0;
    }
    let bottom = w[0] + (w[1] - w[0]) * p.x;
    let top = w[2] + (w[3] - w[2]) * p.x;
    4.0 * (bottom + (top - bottom) * p.y) / sum
}

/// A point of [0, 1]² with density ∝ the bilinear interpolation of the corner weights `w`
/// (≥ 0; order as in [`square_to_bilinear_pdf`]; all 0: uniform): y from its marginal, a
/// linear density, then x from the linear density of the row at y.
#[inline]
pub fn square_to_bilinear(u: Vec2, w: [f32; 4]) -> Vec2 {
    if w[0] + w[1] + w[2] + w[3] <= 0.0 {
        return u;
    }
    let y = unit_to_linear(u.y, w[0] + w[1], w[2] + w[3]);
    let x = unit_to_linear(u.x, w[0] + (w[2] - w[0]) * y, w[1] + (w[3] - w[1]) * y);
    Vec2::new(x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bilinear warp's samples fall in a 16×16 grid as its density integrates there
    /// (χ² test, 10⁵ samples per set of weights, 1 % level over 225 degrees of freedom).
    #[test]
    fn bilinear_warp_matches_its_density() {
        use crate::sampling::Pcg32;
        let mut rng = Pcg32::new(11, 3);
        for w in [[1.0, 2.0, 3.0, 4.0], [0.0, 0.0, 0.0, 5.0], [1e4, 1.0, 0.0, 2.0], [1.0; 4]] {
            const G: usize = 16;
            let n = 100_000;
            let mut counts = [0f64; G * G];
            for _ in 0..n {
                let p = square_to_bilinear(Vec2::new(rng.next_f32(), rng.next_f32()), w);
                assert!((0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y), "{p}");
                let (i, j) = (
                    ((p.x * G as f32) as usize).min(G - 1),
                    ((p.y * G as f32) as usize).min(G - 1),
                );
                counts[j * G + i] += 1.0;
            }
            let mut chi2 = 0.0;
            let mut dof = 0;
            for j in 0..G {
                for i in 0..G {
                    // the cell's probability by the midpoint rule, exact for a bilinear density
                    let c = Vec2::new((i as f32 + 0.5) / G as f32, (j as f32 + 0.5) / G as f32);
                    let expected = square_to_bilinear_pdf(c, w) as f64 / (G * G) as f64 * n as f64;
                    if expected > 5.0 {
                        chi2 += (counts[j * G + i] - expected).powi(2) / expected;
                        dof += 1;
                    } else {
                        assert!(counts[j * G + i] <= 20.0, "{w:?}: {counts:?}");
                    }
                }
            }
            // the 1 % quantile of χ² with k degrees of freedom, Wilson–Hilferty
            let k = (dof - 1) as f64;
            let z = 2.326;
            let limit = k * (1.0 - 2.0 / (9.0 * k) + z * (2.0 / (9.0 * k)).sqrt()).powi(3);
            assert!(chi2 < limit, "{w:?}: χ² = {chi2} over {k} dof (limit {limit})");
        }
        // the density integrates to 1 and the warp inverts the linear CDF at its ends
        assert_eq!(unit_to_linear(0.0, 1.0, 3.0), 0.0);
        assert!((unit_to_linear(1.0, 1.0, 3.0) - 1.0).abs() < 1e-6);
        assert!((unit_to_linear(0.5, 2.0, 2.0) - 0.5).abs() < 1e-6);
    }

    /// The polynomial sine and cosine agree with f64's to 2·10⁻⁷ over a fine grid of turns,
    /// including both ends and the quarter-turn boundaries, and stay on the unit circle.
    #[test]
    fn sin_cos_turns_matches_f64() {
        let mut worst = 0.0f64;
        for i in 0..=400_000u32 {
            let t = i as f32 / 400_000.0;
            let (s, c) = sin_cos_turns(t);
            let a = std::f64::consts::TAU * t as f64;
            worst = worst.max((s as f64 - a.sin()).abs()).max((c as f64 - a.cos()).abs());
            assert!(((s * s + c * c) - 1.0).abs() < 1e-6, "t {t}");
        }
        assert!(worst < 2e-7, "worst error {worst}");
        for t in [0.0f32, 0.125, 0.25, 0.375, 0.5, 0.75, 1.0] {
            let (s, c) = sin_cos_turns(t);
            let a = std::f64::consts::TAU * t as f64;
            assert!(
                (s as f64 - a.sin()).abs() < 2e-7 && (c as f64 - a.cos()).abs() < 2e-7,
                "t {t}"
            );
        }
    }
    use crate::sampling::Pcg32;
    use crate::testkit::u2;

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
                let w = square_to_uniform_cone(u2(&mut r), 1.0 - cos_max);
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

    // ---- densities: every warp's density is 1/|Jacobian| and integrates to 1 ----
    // No warp here has an inverse; a map whose density matches its Jacobian everywhere and
    // integrates to 1 covers its domain once (a fold would double the measure somewhere).

    use crate::testkit::chi2::{directions_pvalue, CapGrid};

    /// The area of the image of a small square around `u` per unit area: |∂w/∂u × ∂w/∂v| for
    /// maps to the unit sphere (the solid-angle Jacobian), |det| for maps to the plane
    /// (z = 0). Central differences with steps 2h and h, Richardson-extrapolated (error
    /// O(h⁴): near the cosine warp's rim, where dz/dr = −r/z, a plain difference errs by 1 %).
    fn jacobian(map: impl Fn(Vec2) -> Vec3, u: Vec2, h: f32) -> f64 {
        let partials = |h: f32| {
            let d = |a: Vec2, b: Vec2| (map(b) - map(a)).as_dvec3() / (2.0 * h as f64);
            let du = d(u - Vec2::new(h, 0.0), u + Vec2::new(h, 0.0));
            let dv = d(u - Vec2::new(0.0, h), u + Vec2::new(0.0, h));
            (du, dv)
        };
        let ((du1, dv1), (du2, dv2)) = (partials(2.0 * h), partials(h));
        let (du, dv) = ((4.0 * du2 - du1) / 3.0, (4.0 * dv2 - dv1) / 3.0);
        du.cross(dv).length()
    }

    /// pdf(map(u))·|J(u)| = 1 on a 20 × 20 grid of the open square, to 5·10⁻⁴ (differences of
    /// single-precision values over steps of 10⁻³ and 2·10⁻³ reach 8·10⁻⁵). The grid keeps 1.25·10⁻²
    /// from the diagonals u = v and u + v = 1, where the pieces of the concentric and
    /// triangle maps meet (a difference across them would mix two pieces' derivatives).
    #[track_caller]
    fn assert_density_is_inverse_jacobian(
        name: &str,
        map: impl Fn(Vec2) -> Vec3,
        pdf: impl Fn(Vec3) -> f64,
    ) {
        let n = 20;
        let mut worst = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.25) / n as f32, (j as f32 + 0.5) / n as f32);
                let prod = pdf(map(u)) * jacobian(&map, u, 1e-3);
                worst = worst.max((prod - 1.0).abs());
            }
        }
        assert!(worst < 5e-4, "{name}: pdf·|J| is off 1 by up to {worst}");
    }

    fn plane(p: Vec2) -> Vec3 {
        p.extend(0.0)
    }

    #[test]
    fn densities_are_inverse_jacobians() {
        use std::f64::consts::PI;
        let cone_cos_max = 0.3f32;
        assert_density_is_inverse_jacobian(
            "concentric disk",
            |u| plane(square_to_uniform_disk_concentric(u)),
            |p| if p.truncate().length() <= 1.0 { 1.0 / PI } else { 0.0 },
        );
        assert_density_is_inverse_jacobian("cosine hemisphere", square_to_cosine_hemisphere, |w| {
            square_to_cosine_hemisphere_pdf(w) as f64
        });
        assert_density_is_inverse_jacobian("uniform sphere", square_to_uniform_sphere, |_| {
            UNIFORM_SPHERE_PDF as f64
        });
        assert_density_is_inverse_jacobian(
            "uniform hemisphere",
            square_to_uniform_hemisphere,
            |w| if w.z >= 0.0 { UNIFORM_HEMISPHERE_PDF as f64 } else { 0.0 },
        );
        assert_density_is_inverse_jacobian(
            "uniform cone",
            |u| square_to_uniform_cone(u, 1.0 - cone_cos_max),
            |w| square_to_uniform_cone_pdf(w, cone_cos_max) as f64,
        );
        // barycentrics (b1, b2) are uniform on the triangle b1, b2 ≥ 0, b1 + b2 ≤ 1 (area 1/2)
        assert_density_is_inverse_jacobian(
            "uniform triangle",
            |u| plane(square_to_uniform_triangle(u)),
            |b| if b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 { 2.0 } else { 0.0 },
        );
        assert_density_is_inverse_jacobian(
            "standard normal",
            |u| plane(square_to_std_normal(u)),
            |x| (-0.5 * x.length_squared() as f64).exp() / (2.0 * PI),
        );
    }

    /// The solid-angle densities integrate to 1 over the sphere (midpoint rule on the χ²
    /// harness's grid, 20 × 40 cells of 32² points), and vanish outside their domains.
    #[test]
    fn solid_angle_densities_integrate_to_one() {
        let grid = CapGrid::SPHERE.with_sub(32);
        let integral = |pdf: &dyn Fn(Vec3) -> f64| grid.expected(1, pdf).iter().sum::<f64>();
        let cases: [(&str, &dyn Fn(Vec3) -> f64); 3] = [
            ("cosine hemisphere", &|w| square_to_cosine_hemisphere_pdf(w) as f64),
            ("cone cos θmax = 0.3", &|w| square_to_uniform_cone_pdf(w, 0.3) as f64),
            ("cone cos θmax = -0.5", &|w| square_to_uniform_cone_pdf(w, -0.5) as f64),
        ];
        for (name, pdf) in cases {
            let i = integral(pdf);
            // the cone's edge cuts through cells: the midpoint rule errs by O(1/32) of a row
            assert!((i - 1.0).abs() < 2e-3, "{name}: ∫pdf dω = {i}");
        }
        assert_eq!(square_to_cosine_hemisphere_pdf(Vec3::new(0.0, 0.6, -0.8)), 0.0);
        assert_eq!(square_to_uniform_cone_pdf(Vec3::new(0.0, 0.96, 0.28), 0.3), 0.0);
    }

    /// The sphere warps' samples follow their densities (χ² test, 10⁵ samples each).
    #[test]
    fn sphere_warps_match_their_densities_chi2() {
        type Warp<'a> = &'a dyn Fn(Vec2) -> Vec3;
        type Pdf<'a> = &'a dyn Fn(Vec3) -> f64;
        // (name, warp, density, cos θmax of a cone)
        let cases: [(&str, Warp, Pdf, Option<f32>); 5] = [
            (
                "cosine hemisphere",
                &square_to_cosine_hemisphere,
                &|w| square_to_cosine_hemisphere_pdf(w) as f64,
                None,
            ),
            ("uniform sphere", &square_to_uniform_sphere, &|_| UNIFORM_SPHERE_PDF as f64, None),
            (
                "uniform hemisphere",
                &square_to_uniform_hemisphere,
                &|w| if w.z >= 0.0 { UNIFORM_HEMISPHERE_PDF as f64 } else { 0.0 },
                None,
            ),
            (
                "cone cos θmax = 0.3",
                &|u| square_to_uniform_cone(u, 0.7),
                &|w| square_to_uniform_cone_pdf(w, 0.3) as f64,
                Some(0.3),
            ),
            (
                "cone cos θmax = 0.99",
                &|u| square_to_uniform_cone(u, 0.01),
                &|w| square_to_uniform_cone_pdf(w, 0.99) as f64,
                Some(0.99),
            ),
        ];
        let tests = cases.len();
        for (k, (name, warp, pdf, cos_max)) in cases.into_iter().enumerate() {
            // a cone gets a grid over its own cap: no cell straddles its edge, and a small
            // cone's samples spread over many cells
            let grid = match cos_max {
                Some(c) => CapGrid { theta_max: (c as f64).acos(), ..CapGrid::SPHERE },
                None => CapGrid::SPHERE,
            };
            let mut r = Pcg32::new(k as u64, 21);
            let p = directions_pvalue(&grid, 100_000, || Some(warp(u2(&mut r))), pdf);
            assert!(p > 0.01 / tests as f64, "{name}: p-value {p}");
        }
    }
}
