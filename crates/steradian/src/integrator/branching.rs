//! How many paths continue from each camera ray's first hit, when the scene leaves `path`'s
//! `branches` unset: the splitting factor that gives the least noise per unit of work, chosen
//! by a short pilot before the render.
//!
//! Splitting a camera sample into N branches at its first hit costs C₁ + N·C₂ (C₁: the camera
//! ray, its intersection and the film splat; C₂: one branch) and leaves the variance
//! V_b + V_w/N (V_b: the variance of what the first hit alone decides, such as where in the
//! pixel the ray lands and what the hit emits; V_w: the variance of one branch given the first
//! hit). Their product, the inverse of the efficiency, is least at
//!
//!   N* = √(C₁·V_w / (C₂·V_b))
//!
//! (the optimal splitting factor of Arvo and Kirk, "Particle transport and image synthesis",
//! SIGGRAPH 1990; Rath et al., "EARS", SIGGRAPH 2022, learn the same factor per region).
//!
//! The pilot estimates the four numbers from samples of its own (i.i.d., seeded from the
//! render's seed, never put on the film): up to 8192 camera samples, spread over up to
//! 32 × 32 pixels evenly placed on the film (all in the one pixel of a radiance meter), each
//! split into M = 4 branches with values X₁ … X₄ after the first hit's emission P.
//! - V_w: the mean over samples of the branches' sample variance;
//! - V_b: the variance of Y = P + mean(X) over a pixel's samples, minus V_w/M (V_b is a
//!   difference, and M = 4 rather than 2 keeps the subtracted part, and its noise, small);
//! - both are summed over pixels with weights 1/(μ² + ε), μ the pixel's mean and ε = 10⁻² ×
//!   the film's mean squared: relative error, what noise looks like, without letting black
//!   pixels dominate; values above the 99.9th percentile of the pilot's values are clamped
//!   first, so that a few fireflies do not decide alone;
//! - costs are counted in rays traced (closest-hit and shadow rays alike), plus
//!   [`CAMERA_SAMPLE_COST`] rays' worth for generating a camera ray and splatting its value.
//!   A count, not a clock, so that the choice (and the image) is the same on every run.
//!
//! N* is rounded and clamped to 1..=[`MAX_AUTO_BRANCHES`]. The pilot spends at most 1/16 of
//! the render's camera samples; a render too small for that gets
//! [`DEFAULT_BRANCHES`](super::DEFAULT_BRANCHES).
//! Choices on the reference scenes (seed 0): cornell 3, materials 11, veach 7, plastics 4,
//! textures 6, pointlight 4, furnace 16 (whose first hits, a convex object under a uniform
//! sky, decide almost nothing). Over seeds: cornell 3–4, materials 7–16, veach 4–15 (the
//! estimate of V_b is noisy; the efficiency is flat near the optimum). In
//! equal-time sweeps the best fixed counts are 4 for cornell, 16 for materials (4: 2.95,
//! 8: 2.85, 16: 2.68 user-s × relMSE/10⁻³) and 4 for veach, with efficiency within about
//! 10 % from 3 to 8. A point light with `max_depth` = 2, whose light after the first hit has
//! no noise at all, gets 1, where 4 branches would take 2.2× the time for the same image.

use glam::{UVec2, Vec2};
use rayon::prelude::*;

use super::path::{Branches, RayCount};
use super::PathTracer;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::sensor::{Quantity, Sensor};
use crate::spectrum::luminance;
use crate::Spectrum;

/// Rays' worth of work for making a camera ray and splatting its value on the film (filter
/// weights over up to 5 × 5 pixels): measured on a Cornell box, where these take about as long as
/// tracing and shading one ray.
pub const CAMERA_SAMPLE_COST: f64 = 1.0;

/// The largest count the pilot chooses.
pub const MAX_AUTO_BRANCHES: u32 = 16;

/// Pixels of the pilot along each film axis (at most).
const PILOT_GRID: u32 = 32;

/// Camera samples of the pilot, at most (8 per pixel of a full grid).
const PILOT_SAMPLES: u64 = 8192;

/// The fewest camera samples per pilot pixel that still estimate a pixel's variance.
const PILOT_MIN_SAMPLES_PER_PIXEL: u64 = 2;

/// The pilot's share of the render's camera samples, at most.
const PILOT_BUDGET_FRACTION: u64 = 16;

/// Branches per pilot camera sample: V_b comes out as a difference, s²(Y) − V_w/M, which is
/// less noisy the smaller V_w/M is.
const PILOT_BRANCHES: usize = 4;

/// The share of the pilot's largest values that are clamped (see [`choose`]).
const CLAMP_TAIL: f64 = 1e-3;

/// Decorrelates the pilot's numbers from the render's.
const PILOT_SALT: u64 = 0x7069_6c6f_7420_7321;

/// What the pilot measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pilot {
    /// Camera samples taken.
    pub samples: u64,
    /// Rays' worth of work per camera sample before the split (C₁) and per branch (C₂).
    pub cost_first: f64,
    pub cost_branch: f64,
    /// Relative variances: of what the first hit decides (V_b), and of one branch (V_w).
    pub var_first: f64,
    pub var_branch: f64,
    /// The chosen count.
    pub branches: u32,
}

/// One pilot camera sample: luminance emitted at the first hit and of each branch, and the
/// rays traced before and after the split.
#[derive(Clone, Copy, Debug)]
struct PilotSample {
    first: f64,
    x: [f64; PILOT_BRANCHES],
    rays_first: u32,
    rays_branch: u32,
}

/// The branch count for `tracer` on this film: the pilot's choice, or `None` when the render
/// is too small for a pilot or the sensor is an irradiance meter (whose samples start on a
/// surface, not with a camera ray).
pub fn pilot(tracer: &PathTracer, scene: &Scene, sensor: &Sensor, width: u32, height: u32, spp: u32, seed: u64) -> Option<Pilot> {
    if sensor.quantity() == Quantity::Irradiance {
        return None;
    }
    let (gx, gy) = (width.min(PILOT_GRID), height.min(PILOT_GRID));
    let budget = width as u64 * height as u64 * spp as u64 / PILOT_BUDGET_FRACTION;
    let per_pixel = budget.min(PILOT_SAMPLES) / (gx as u64 * gy as u64);
    if per_pixel < PILOT_MIN_SAMPLES_PER_PIXEL {
        return None;
    }
    let probe = PathTracer { branches: Branches::Fixed(PILOT_BRANCHES as u32), ..tracer.clone() };
    let pixels: Vec<Vec<PilotSample>> = (0..gx * gy)
        .into_par_iter()
        .map(|i| {
            // pixel centres of an even grid over the film
            let pixel = UVec2::new(((i % gx) * 2 + 1) * width / (2 * gx), ((i / gx) * 2 + 1) * height / (2 * gy));
            let mut s = PixelSampler::independent(seed ^ PILOT_SALT, pixel.y as u64 * width as u64 + pixel.x as u64);
            let mut samples = Vec::with_capacity(per_pixel as usize);
            for _ in 0..per_pixel {
                let film_uv = (pixel.as_vec2() + s.next_2d()) / Vec2::new(width as f32, height as f32);
                let Some(ray) = sensor.start_ray(film_uv, &mut s) else { continue };
                let (mut first, mut rays) = (Spectrum::ZERO, RayCount::default());
                let hit = probe.first_hit(scene, &ray, &mut first, &mut rays);
                let mut sample = PilotSample { first: luminance(first) as f64, x: [0.0; PILOT_BRANCHES], rays_first: rays.0, rays_branch: 0 };
                if let Some((si, st)) = hit {
                    probe.for_each_branch(scene, &si, st, &mut s, PILOT_BRANCHES as u32, |b, l, rays: RayCount| {
                        sample.x[b] = luminance(l) as f64;
                        sample.rays_branch += rays.0;
                    });
                }
                if sample.first.is_finite() && sample.x.iter().all(|x| x.is_finite()) {
                    samples.push(sample);
                }
            }
            samples
        })
        .collect();
    Some(choose(&pixels))
}

/// N* from the pilot's samples (see the module docs), summed in pixel order.
fn choose(pixels: &[Vec<PilotSample>]) -> Pilot {
    let all = || pixels.iter().flatten();
    let samples = all().count() as u64;
    let per_sample = |rays: u64| rays as f64 / samples.max(1) as f64;
    let cost_first = CAMERA_SAMPLE_COST + per_sample(all().map(|p| p.rays_first as u64).sum());
    let cost_branch = per_sample(all().map(|p| p.rays_branch as u64).sum()) / PILOT_BRANCHES as f64;
    // Fireflies (rare, bright paths) would decide the estimates alone: values are clamped at
    // the (1 − CLAMP_TAIL) quantile of all values. This only shapes the choice of N, never
    // the image; it lowers V_w more than V_b, so it errs towards fewer branches.
    let mut values: Vec<f64> = all().flat_map(|p| std::iter::once(p.first).chain(p.x)).collect();
    let clamp = if values.is_empty() {
        f64::INFINITY
    } else {
        let k = ((values.len() as f64 * (1.0 - CLAMP_TAIL)) as usize).min(values.len() - 1);
        *values.select_nth_unstable_by(k, f64::total_cmp).1
    };
    let m = PILOT_BRANCHES as f64;
    let mut stats = Vec::with_capacity(pixels.len());
    for p in pixels.iter().filter(|p| p.len() >= 2) {
        let n = p.len() as f64;
        let (mut y, mut y2, mut d) = (0.0, 0.0, 0.0);
        for q in p {
            let x = q.x.map(|x| x.min(clamp));
            let xm = x.iter().sum::<f64>() / m;
            let yq = q.first.min(clamp) + xm;
            y += yq;
            y2 += yq * yq;
            // the branches' sample variance: an unbiased estimate of V_w at this sample
            d += x.iter().map(|x| (x - xm) * (x - xm)).sum::<f64>() / (m - 1.0);
        }
        let mu = y / n;
        // (pixel mean, sample variance of Y, mean of the branches' variance)
        stats.push((mu, ((y2 - n * mu * mu) / (n - 1.0)).max(0.0), d / n));
    }
    let mean_of_means = stats.iter().map(|s| s.0).sum::<f64>() / stats.len().max(1) as f64;
    let eps = 1e-2 * mean_of_means * mean_of_means + f64::MIN_POSITIVE;
    let (mut var_first, mut var_branch) = (0.0, 0.0);
    for &(mu, s2, vw) in &stats {
        let w = 1.0 / (mu * mu + eps);
        var_branch += w * vw;
        var_first += w * (s2 - vw / m);
    }
    let branches = if var_branch <= 0.0 || cost_branch <= 0.0 {
        1
    } else if var_first <= 0.0 {
        MAX_AUTO_BRANCHES
    } else {
        let n = (cost_first * var_branch / (cost_branch * var_first)).sqrt();
        (n.round() as u32).clamp(1, MAX_AUTO_BRANCHES)
    };
    Pilot { samples, cost_first, cost_branch, var_first, var_branch, branches }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pixel's samples; the rays are spread evenly over them.
    fn pixel(samples: &[(f64, [f64; PILOT_BRANCHES])], rays_first: u32, rays_branch: u32) -> Vec<PilotSample> {
        let n = samples.len() as u32;
        samples.iter().map(|&(first, x)| PilotSample { first, x, rays_first: rays_first / n, rays_branch: rays_branch / n }).collect()
    }

    /// Branches that always agree (no noise after the first hit): one branch.
    #[test]
    fn noiseless_branches_are_not_split() {
        let p = pixel(&[(0.0, [1.0; 4]), (0.5, [2.0; 4]), (0.0, [1.5; 4])], 3, 12);
        assert_eq!(choose(&[p.clone(), p]).branches, 1);
    }

    /// The formula, on samples built so that every estimate is known exactly: two samples per
    /// pixel, first-hit values 0 and 2a, branches (b, −b, b, −b). Then Y ∈ {0, 2a}, so
    /// s²(Y) = 2a²; each sample's branch variance is V_w = 4b²/3; V_b = 2a² − V_w/4.
    #[test]
    fn optimal_factor_from_the_samples() {
        let case = |a: f64, b: f64| pixel(&[(0.0, [b, -b, b, -b]), (2.0 * a, [b, -b, b, -b])], 4, 16);
        // rays: 2 per sample before the split (+1 for the camera sample) and 16/2/4 = 2 per
        // branch: C₁ = 3, C₂ = 2
        let c = choose(&[case(3.0, 2.0)]);
        assert!((c.cost_first - 3.0).abs() < 1e-12 && (c.cost_branch - 2.0).abs() < 1e-12, "{c:?}");
        let (vw, vb) = (16.0 / 3.0, 18.0 - 4.0 / 3.0);
        assert!((c.var_branch / c.var_first - vw / vb).abs() < 1e-12, "{c:?}");
        // N* = √(3·5.33/(2·16.7)) = 0.69
        assert_eq!(c.branches, 1);
        // a = 1, b = 2.09: V_w = 5.824, V_b = 0.544, N* = √(3·5.824/(2·0.544)) = 4.01
        assert_eq!(choose(&[case(1.0, 2.09)]).branches, 4);
        // b large enough that V_b < 0: the estimate says the first hit decides nothing
        assert_eq!(choose(&[case(1.0, 3.0)]).branches, MAX_AUTO_BRANCHES);
    }
}
