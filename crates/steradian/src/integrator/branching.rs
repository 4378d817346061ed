//! How many paths continue from each camera ray's first hit, when the scene leaves `path`'s
//! `branches` unset: the splitting factor with the least noise per unit of work, chosen by a
//! short pilot before the render.
//!
//! **Model.** N branches cost C(N) = C₁ + N·C₂ per camera sample (C₁: camera ray, first hit and
//! film splat; C₂: one branch) and leave a variance V(N) = V_b + V_w/N (V_b: what the first hit
//! decides; V_w: one branch given the first hit); V·C is least at N* = √(C₁·V_w / (C₂·V_b))
//! (Arvo and Kirk 1990; Rath et al., "EARS", 2022).
//!
//! **Pilot.** Stratified camera samples and branches (`sampling/sampler.rs`) remove most of V_b,
//! so V and C are measured as the render makes them:
//! - up to 256 pixels at random over the film (all of a smaller film) are rendered with each of
//!   [`CANDIDATES`] in R replicates of S camera samples (the render's sampler, seeded apart,
//!   never put on the film; R = 8, more on films of fewer than 128 pixels), with the same
//!   pixels and numbers whatever the render's seed;
//! - V(N) = S × the variance between replicates, summed over pixels with weights 1/(μ² + ε),
//!   μ the pixel's mean and ε = 10⁻² × the film's mean squared, after clamping values above the
//!   99.9th percentile; C(N) = rays traced per camera sample + [`CAMERA_SAMPLE_COST`], a count,
//!   not a clock, so that the choice and the image are the same on every run;
//! - V_w is also measured on its own, as the spread of the 16-branch candidate's branches
//!   about their camera sample's mean, unclamped (weighted as above), and the larger of the
//!   two counts: the clamp that keeps fireflies from deciding the fit also hides the rare
//!   bright paths that branching averages, and 16 branches per sample see them far more often
//!   than one;
//! - the model is fitted to the five candidates ([`best_count`]); the largest count whose
//!   modelled V·C is within 30 % of the least wins (powers of two keep N·spp a power of two,
//!   where Sobol points stratify best). Leaning upwards costs little where the model is
//!   right (one step above the optimum costs at most 12.5 % by the model itself) and guards
//!   against two failures of the model that both split too little: a pilot of a few thousand
//!   samples sees too few of a heavy-tailed scene's rare bright paths and underestimates V_w,
//!   and stratified branches make V(N) fall faster than 1/N (on `glossy_spheres`, 4 → 8
//!   branches cut the render's error 2.3×), which V_b + V_w/N cannot follow. S is the
//!   largest power of two up to min(spp, 16) that keeps the pilot within 1/4 of a one-branch
//!   render's work; renders too small for S = 1 and irradiance meters get
//!   [`DEFAULT_BRANCHES`](super::DEFAULT_BRANCHES).
//!
//! Decisions (2026-12-02, AMD EPYC, 2 cores; `docs/design/2026-12-02-branching-pilot.md`):
//! - Sobol replicates, not i.i.d. samples (which overstate V_b): equal-time error at 16 spp
//!   −26 % on cornell (3 → 16 branches), within noise on materials and veach.
//! - Random pixels, not a grid, which missed the edges: the point-light scene holds 80 % of its
//!   error at 16 branches on 1 % of its pixels.
//! - V_w at least the 16 branches' own spread (2026-12-06, AMD EPYC, 2 cores, 64 spp, e × t
//!   from three pairs of seeds, `benches/results/2026-12-06-amd-epyc.md`): `glossy_spheres`
//!   chose 2 branches on 6 of 8 seeds and now 4–16, 0.42× → 0.92× Mitsuba's speed at equal
//!   error; seven reference scenes whose choice moved: e × t 0.78–0.94× of before on six,
//!   1.14× on `serialized` (geometric mean 0.89×); cornell, materials and veach keep 16.
//! - Leaning upwards by 15 % (2026-12-06, AMD EPYC, 2 cores, 64 spp): `glossy_spheres` chose
//!   16, 8, 4, 8, 4, 4, 16, 8 branches over seeds 0–7 and now 16, 16, 8, 16, 8, 8, 16, 16,
//!   0.81× → 0.92× Mitsuba's speed at equal error (`render_vs_mitsuba.py`, 4 pairs); the
//!   twelve reference scenes whose choice moved (up one step each): e × t from 4 pairs of
//!   seeds 0.98× of before in geometric mean (0.82× `projector` to 1.22× `mesh-attribute`;
//!   a repeat of four of them, 8 pairs: 1.02×, so neutral within the noise); cornell,
//!   materials and veach keep 16.
//! - Leaning upwards by 30 %, not 15 %, and one pilot whatever the render's seed (2026-12-07,
//!   AMD EPYC, 2 cores, 64 spp, e × t from 4 pairs of seeds,
//!   `benches/results/2026-12-07-amd-epyc.md`): over 16 seeds `glossy_spheres` had chosen
//!   16 branches 8 times, 8 five times and 4 three times
//!   (e × t at fixed counts 4.27e-4, 3.81e-4, 6.00e-4), and now chooses 16; e × t 0.71× of
//!   before, most of it because renders with different seeds are now replicates of one
//!   estimator (a pair of seeds with different counts has the mean of their variances and
//!   of their times; per render the expected e × t moves from 4.45e-4 to 4.27e-4); the nine
//!   reference scenes whose choice moved: 0.73× (`sunsky`) to 0.99× (`bspline-curves`),
//!   geometric mean 0.86×; cornell, materials and veach keep 16. With the same pixels and
//!   numbers for every seed, the spread between seeds is the render's error and its time is
//!   the same from seed to seed.

use glam::UVec2;
use rayon::prelude::*;

use super::path::{Branches, Counts, RayCount};
use super::PathTracer;
use crate::sampling::{mix64, Sampler};
use crate::scene::Scene;
use crate::sensor::{film_position, Quantity, Sensor};
use crate::spectrum::luminance;
use crate::Spectrum;

/// Rays' worth of work for making a camera ray and splatting its value on the film (filter
/// weights over up to 5 × 5 pixels): on a Cornell box these take about as long as tracing and
/// shading one ray (measured 2026-12-01, AMD EPYC, 2 cores).
pub const CAMERA_SAMPLE_COST: f64 = 1.0;

/// The counts the pilot tries, in increasing order.
pub const CANDIDATES: [u32; 5] = [1, 2, 4, 8, 16];

/// The largest count the pilot chooses.
pub const MAX_AUTO_BRANCHES: u32 = CANDIDATES[CANDIDATES.len() - 1];

/// Pixels of the pilot, at most: drawn at random over the film (a regular grid would miss
/// the edges, which hold most of what the first hit decides: 80 % of the point-light
/// scene's error at 16 branches sits on 1 % of its pixels, measured 2026-12-02).
const PILOT_PIXELS: u32 = 256;

/// Replicates per pilot pixel, at least; films with fewer than [`PILOT_UNITS`] pixels (a
/// meter's one) get more, so that every pilot has about as many degrees of freedom.
const PILOT_REPLICATES: u32 = 8;
const PILOT_UNITS: u32 = 1024;

/// Camera samples per replicate, at most.
const PILOT_MAX_SPP: u32 = 16;

/// The pilot's work, at most, as a fraction of a one-branch render's (1/4).
const PILOT_BUDGET_FRACTION: u64 = 4;

/// The share of the pilot's largest values that are clamped (see [`choose`]).
const CLAMP_TAIL: f64 = 1e-3;

/// How much more modelled V·C the pilot accepts for a larger count (see [`best_count`]).
const UPWARD_TOLERANCE: f64 = 0.3;

/// Decorrelates the pilot's numbers from the render's (whatever its seed: see the module docs).
const PILOT_SALT: u64 = 0x7069_6c6f_7420_7321;

/// What the pilot measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pilot {
    /// Camera samples taken (all candidates).
    pub samples: u64,
    /// Camera samples per replicate (S) and replicates per pixel (R).
    pub spp: u32,
    pub replicates: u32,
    /// Relative variance of one camera sample's value, V(N), and rays' worth of work per
    /// camera sample, C(N), for each of `CANDIDATES`.
    pub variance: [f64; CANDIDATES.len()],
    pub cost: [f64; CANDIDATES.len()],
    /// Least-squares fits C(N) = C₁ + N·C₂ ...
    pub cost_first: f64,
    pub cost_branch: f64,
    /// ... and V(N) = V_b + V_w/N: the variances of what the first hit decides (V_b) and of
    /// one branch (V_w), as the render's sampler leaves them. Where stratification makes
    /// V(N) fall faster than 1/N, V_b comes out below its true value, even negative.
    pub var_first: f64,
    pub var_branch: f64,
    /// The chosen count.
    pub branches: u32,
}

/// One pilot pixel: per candidate, the values (luminance) of its R·S camera samples, each the
/// first hit's emission followed by the N branches' values, and the rays they traced.
#[derive(Clone, Debug, Default)]
struct PilotPixel {
    values: [Vec<f64>; CANDIDATES.len()],
    rays: [u64; CANDIDATES.len()],
}

/// The branch count for `tracer` on this film: the pilot's choice, or `None` when the render
/// is too small for a pilot or the sensor is an irradiance meter (whose samples start on a
/// surface, not with a camera ray). `sampler` is the render's; the pilot takes its kind, not
/// its seed (see the module docs).
pub fn pilot(
    tracer: &PathTracer,
    scene: &Scene,
    sensor: &Sensor,
    width: u32,
    height: u32,
    spp: u32,
    sampler: &Sampler,
) -> Option<Pilot> {
    if sensor.quantity() == Quantity::Irradiance {
        return None;
    }
    let film_pixels = width as u64 * height as u64;
    let window = sensor.film.window();
    let pixels = (PILOT_PIXELS as u64).min(film_pixels) as u32;
    let replicates = PILOT_REPLICATES.max(PILOT_UNITS.div_ceil(pixels));
    // work in paths (camera samples and branches): the pilot's with S samples per replicate,
    // at most 1/PILOT_BUDGET_FRACTION of a one-branch render's
    let paths_per_sample: u64 = CANDIDATES.iter().map(|&n| 1 + n as u64).sum();
    let work = |s: u32| pixels as u64 * replicates as u64 * s as u64 * paths_per_sample;
    let budget = film_pixels * spp as u64 * 2 / PILOT_BUDGET_FRACTION;
    let mut s = 1 << spp.clamp(1, PILOT_MAX_SPP).ilog2();
    while s > 1 && work(s) > budget {
        s /= 2;
    }
    if work(s) > budget {
        return None;
    }
    let probes = CANDIDATES.map(|n| PathTracer { branches: Branches::Fixed(n), ..tracer.clone() });
    let samplers: Vec<Sampler> = (0..replicates)
        .map(|r| Sampler {
            kind: sampler.kind,
            sample_count: s,
            seed: mix64(PILOT_SALT).wrapping_add(r as u64),
        })
        .collect();
    let measured: Vec<PilotPixel> = (0..pixels)
        .into_par_iter()
        .map(|i| {
            // every pixel of a small film; otherwise pixels drawn at random over the film
            let k = if pixels as u64 == film_pixels {
                i as u64
            } else {
                mix64(PILOT_SALT ^ mix64(i as u64)) % film_pixels
            };
            let pixel = UVec2::new((k % width as u64) as u32, (k / width as u64) as u32);
            let mut out = PilotPixel::default();
            for (c, (&n, probe)) in CANDIDATES.iter().zip(&probes).enumerate() {
                let values = &mut out.values[c];
                values.reserve((replicates * s * (1 + n)) as usize);
                for sampler in &samplers {
                    for index in 0..s {
                        let mut ps = sampler.pixel_sampler(pixel, width, index);
                        let (_, film_uv) = film_position(pixel, &mut ps, &window);
                        let start = values.len();
                        values.resize(start + 1 + n as usize, 0.0);
                        let Some(ray) = sensor.start_ray(film_uv, &mut ps) else { continue };
                        let (mut first, mut rays) = (Spectrum::ZERO, RayCount::default());
                        // the chance each path counts, as `li` keeps it (`path.rs`): the first
                        // hit's emission weighs by the branches' mean chance
                        let mut counts = probe.initial_chance(scene);
                        let hit = probe.first_hit(scene, &ray, &mut first, &mut counts, &mut rays);
                        let mut counted = 0.0;
                        out.rays[c] += rays.0 as u64;
                        if let Some((si, st)) = hit {
                            probe.for_each_branch(
                                scene,
                                &si,
                                st,
                                &mut ps,
                                n,
                                counts,
                                |b, l, count, rays: RayCount| {
                                    values[start + 1 + b] = luminance(l) as f64;
                                    counted += count;
                                    out.rays[c] += rays.0 as u64;
                                },
                            );
                            counts.0 = counted / n as f32;
                        }
                        values[start] = luminance(first * counts.weight()) as f64;
                        // the render drops a sample that is not finite; here such a value counts
                        // as 0, so that it cannot poison the variances (it shapes only the choice)
                        for v in &mut values[start..] {
                            if !v.is_finite() {
                                *v = 0.0;
                            }
                        }
                    }
                }
            }
            out
        })
        .collect();
    Some(choose(&measured, replicates, s))
}

/// The count with the least V(N)·C(N), from the pilot's pixels (see the module docs).
fn choose(pixels: &[PilotPixel], replicates: u32, spp: u32) -> Pilot {
    let (r, s) = (replicates as usize, spp as usize);
    let samples_per_candidate = (pixels.len() * r * s) as f64;
    // Fireflies (rare, bright paths) would decide the estimates alone: values are clamped at
    // the (1 − CLAMP_TAIL) quantile of all values. This only shapes the choice of N, never
    // the image; the same clamp applies to every candidate.
    let mut all: Vec<f64> =
        pixels.iter().flat_map(|p| p.values.iter().flatten().copied()).collect();
    let clamp = if all.is_empty() {
        f64::INFINITY
    } else {
        let k = ((all.len() as f64 * (1.0 - CLAMP_TAIL)) as usize).min(all.len() - 1);
        *all.select_nth_unstable_by(k, f64::total_cmp).1
    };
    // per pixel: the replicates' means for each candidate
    let means: Vec<[Vec<f64>; CANDIDATES.len()]> = pixels
        .iter()
        .map(|p| {
            std::array::from_fn(|c| {
                let per_sample = 1 + CANDIDATES[c] as usize;
                let y = |v: &[f64]| {
                    v[0].min(clamp)
                        + v[1..].iter().map(|x| x.min(clamp)).sum::<f64>() / CANDIDATES[c] as f64
                };
                p.values[c]
                    .chunks_exact(per_sample * s)
                    .map(|rep| rep.chunks_exact(per_sample).map(y).sum::<f64>() / s as f64)
                    .collect()
            })
        })
        .collect();
    // each pixel's mean over all its replicates of all candidates
    let mus: Vec<f64> = means
        .iter()
        .map(|m| m.iter().flatten().sum::<f64>() / (CANDIDATES.len() * r) as f64)
        .collect();
    let mean_of_means = mus.iter().sum::<f64>() / mus.len().max(1) as f64;
    let eps = 1e-2 * mean_of_means * mean_of_means + f64::MIN_POSITIVE;
    let mut variance = [0.0; CANDIDATES.len()];
    for (m, &mu) in means.iter().zip(&mus) {
        let w = 1.0 / (mu * mu + eps);
        for (c, reps) in m.iter().enumerate() {
            let rm = reps.iter().sum::<f64>() / r as f64;
            let s2 = reps.iter().map(|x| (x - rm) * (x - rm)).sum::<f64>() / (r as f64 - 1.0);
            // a replicate averages S samples: S·s² is one sample's worth
            variance[c] += w * s2 * s as f64;
        }
    }
    let cost: [f64; CANDIDATES.len()] = std::array::from_fn(|c| {
        CAMERA_SAMPLE_COST
            + pixels.iter().map(|p| p.rays[c]).sum::<u64>() as f64 / samples_per_candidate
    });
    // V_w also from the spread of the largest candidate's branches about their own camera
    // sample's mean, unclamped: its many branches see the rare bright paths that the clamp
    // removes often enough to count them (as if the branches were independent: where they are
    // stratified this overstates V_w, and the count errs upwards)
    let last = CANDIDATES.len() - 1;
    let n_last = CANDIDATES[last] as f64;
    let mut var_branch_within = 0.0;
    for (p, &mu) in pixels.iter().zip(&mus) {
        let w = 1.0 / (mu * mu + eps);
        for v in p.values[last].chunks_exact(1 + CANDIDATES[last] as usize) {
            let m = v[1..].iter().sum::<f64>() / n_last;
            let s2 = v[1..].iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n_last - 1.0);
            var_branch_within += w * s2 / (r * s) as f64;
        }
    }
    let Fit { cost_first, cost_branch, var_first, var_branch, branches } =
        best_count(variance, cost, var_branch_within);
    let samples = samples_per_candidate as u64 * CANDIDATES.len() as u64;
    Pilot {
        samples,
        spp,
        replicates,
        variance,
        cost,
        cost_first,
        cost_branch,
        var_first,
        var_branch,
        branches,
    }
}

/// The model fitted to the candidates' measurements (see [`Pilot`] for the fields), and the
/// count it chooses.
#[derive(Clone, Copy, Debug)]
struct Fit {
    cost_first: f64,
    cost_branch: f64,
    var_first: f64,
    var_branch: f64,
    branches: u32,
}

/// The model behind the choice, fitted to the candidates' measured V(N) and C(N):
/// V(N) = V_b + V_w/N by least squares in relative terms (each V(N) is as uncertain, in
/// proportion, as the others) and C(N) = C₁ + N·C₂; then the largest candidate whose modelled
/// V(N)·C(N) is within [`UPWARD_TOLERANCE`] of the least, with V_b and V_w taken as at least
/// 0 (see the module docs). The fit pools
/// the five measurements, so that one candidate's noise does not decide alone.
fn best_count(
    variance: [f64; CANDIDATES.len()],
    cost: [f64; CANDIDATES.len()],
    var_branch_within: f64,
) -> Fit {
    let n: [f64; CANDIDATES.len()] = CANDIDATES.map(|n| n as f64);
    let (cost_first, cost_branch) = fit_line(&n, &cost, &[1.0; CANDIDATES.len()]);
    let vmax = variance.iter().fold(0.0f64, |m, &v| m.max(v));
    let tiny = (1e-12 * vmax) * (1e-12 * vmax) + f64::MIN_POSITIVE;
    let (var_first, var_branch) =
        fit_line(&n.map(|n| 1.0 / n), &variance, &variance.map(|v| 1.0 / (v * v + tiny)));
    let (vb, vw) = (var_first.max(0.0), var_branch.max(var_branch_within).max(0.0));
    let model = |n: f64| (vb + vw / n) * (cost_first + n * cost_branch);
    let mut best = 0;
    for c in 1..CANDIDATES.len() {
        if model(n[c]) < model(n[best]) {
            best = c;
        }
    }
    // lean upwards: the largest count modelled within UPWARD_TOLERANCE of the least
    let least = model(n[best]);
    while best + 1 < CANDIDATES.len() && model(n[best + 1]) <= (1.0 + UPWARD_TOLERANCE) * least {
        best += 1;
    }
    let branches = if vw > 0.0 { CANDIDATES[best] } else { 1 };
    Fit { cost_first, cost_branch, var_first, var_branch, branches }
}

/// Least-squares (a, b) of y = a + b·x with weights w.
fn fit_line(x: &[f64], y: &[f64], w: &[f64]) -> (f64, f64) {
    let sw: f64 = w.iter().sum();
    let mx = x.iter().zip(w).map(|(x, w)| w * x).sum::<f64>() / sw;
    let my = y.iter().zip(w).map(|(y, w)| w * y).sum::<f64>() / sw;
    let sxy: f64 = x.iter().zip(y).zip(w).map(|((x, y), w)| w * (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().zip(w).map(|(x, w)| w * (x - mx) * (x - mx)).sum();
    let b = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - b * mx, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pixel whose camera sample `i` of replicate `rep` (of S) has the first-hit value
    /// `first(rep, i)` and branch values `branch(n, rep, i, b)`; every sample traces 1 ray
    /// before the split and 2 per branch.
    fn pixel(
        r: u32,
        s: u32,
        first: impl Fn(u32, u32) -> f64,
        branch: impl Fn(u32, u32, u32, u32) -> f64,
    ) -> PilotPixel {
        let mut p = PilotPixel::default();
        for (c, &n) in CANDIDATES.iter().enumerate() {
            for rep in 0..r {
                for i in 0..s {
                    p.values[c].push(first(rep, i));
                    p.values[c].extend((0..n).map(|b| branch(n, rep, i, b)));
                    p.rays[c] += 1 + 2 * n as u64;
                }
            }
        }
        p
    }

    /// Branches that always agree (no noise after the first hit): one branch, and V_w = 0.
    #[test]
    fn noiseless_branches_are_not_split() {
        let p = pixel(4, 2, |rep, i| (rep * 2 + i) as f64 * 0.25, |_, rep, _, _| 1.0 + rep as f64);
        let c = choose(&[p.clone(), p], 4, 2);
        assert_eq!(c.branches, 1, "{c:?}");
        assert!(
            c.variance.iter().all(|&v| v == c.variance[0])
                && c.var_branch.abs() <= 1e-12 * c.var_first,
            "{c:?}"
        );
        // C(N) = 1 + 1 + 2N: the camera sample's cost, the first ray, two rays per branch
        assert!((c.cost_first - 2.0).abs() < 1e-12 && (c.cost_branch - 2.0).abs() < 1e-12, "{c:?}");
    }

    /// Replicate values built so that V(N) is known exactly (S = 1, R = 4): the first hit is
    /// 0 or 2a, and branch 0 of N is 1 ± b, the others 1, so a sample's value is
    /// first + 1 ± b/N. Over the replicates the deviations are ±a ± b/N in all four
    /// combinations, so V(N) ∝ a² + b²/N², and C(N) = 2 + 2N.
    #[test]
    fn replicate_variances_and_costs() {
        let (a, b) = (1.0, 8.0);
        let p = pixel(
            4,
            1,
            |rep, _| if rep % 2 == 0 { 0.0 } else { 2.0 * a },
            |_, rep, _, k| {
                1.0 + if k == 0 {
                    if rep < 2 {
                        b
                    } else {
                        -b
                    }
                } else {
                    0.0
                }
            },
        );
        let c = choose(&[p], 4, 1);
        for ((v, n), cost) in c.variance.iter().zip(CANDIDATES).zip(c.cost) {
            let expected = c.variance[0] * (a * a + b * b / (n * n) as f64) / (a * a + b * b);
            assert!((v / expected - 1.0).abs() < 1e-12 && cost == 2.0 + 2.0 * n as f64, "{c:?}");
        }
        assert_eq!((c.samples, c.spp, c.replicates), (4 * CANDIDATES.len() as u64, 1, 4));
    }

    /// Rare bright branches (3 of the 16-branch candidate's 2,048 branch values, above the
    /// clamp that keeps them out of the fit) still count, through the spread of the 16
    /// branches of their own camera sample: one branch without them, many with them.
    #[test]
    fn rare_bright_branches_are_counted() {
        let first = |rep: u32, i: u32| ((rep * 4 + i) % 5) as f64;
        let calm = pixel(8, 4, first, |_, _, _, _| 1.0);
        let c = choose(&[calm.clone(), calm.clone(), calm.clone(), calm.clone()], 8, 4);
        assert_eq!((c.branches, c.var_branch), (1, 0.0), "{c:?}");
        let bright =
            pixel(
                8,
                4,
                first,
                |n, rep, i, b| {
                    if n == 16 && rep < 3 && i == 0 && b == 0 {
                        1000.0
                    } else {
                        1.0
                    }
                },
            );
        let c = choose(&[bright, calm.clone(), calm.clone(), calm], 8, 4);
        assert!(c.branches >= 8, "{c:?}");
    }

    /// The model's optimum N* = √(C₁·V_w/(C₂·V_b)) among the candidates, or a larger one
    /// modelled within 30 % of it.
    #[test]
    fn the_count_follows_the_model() {
        let pick = |vb: f64, vw: f64, c1: f64, c2: f64| {
            let p = best_count(
                CANDIDATES.map(|n| vb + vw / n as f64),
                CANDIDATES.map(|n| c1 + c2 * n as f64),
                0.0,
            );
            assert!(
                (p.var_first - vb).abs() <= 1e-9 * (vb + vw)
                    && (p.var_branch - vw).abs() <= 1e-9 * (vb + vw),
                "{p:?}"
            );
            p.branches
        };
        // N* = √(2·16/(2·1)) = 4, modelled 5·10 = 50; 8 models 3·18 = 54, within 30 %;
        // 16 models 2·34 = 68, 36 % more
        assert_eq!(pick(1.0, 16.0, 2.0, 2.0), 8);
        // N* = √(8·100/(1·1)) = 28: the largest candidate
        assert_eq!(pick(1.0, 100.0, 8.0, 1.0), 16);
        // N* = 0.5, modelled 2·5 = 10; 2 models 1.5·9 = 13.5, 35 % more
        assert_eq!(pick(1.0, 1.0, 1.0, 4.0), 1);
        // nothing decided at the first hit: as many as allowed; nothing after it: one
        assert_eq!(pick(0.0, 5.0, 2.0, 2.0), 16);
        assert_eq!(pick(5.0, 0.0, 2.0, 2.0), 1);
        // N* = √(2·18/(2·2)) = 3: 2 and 4 model 11·6 = 66 and 6.5·10 = 65; 8 models
        // 4.25·18 = 76.5, within 1.3 × 65 = 84.5; 16 models 3.125·34 = 106.25
        assert_eq!(pick(2.0, 18.0, 2.0, 2.0), 8);
        // N* = √(2·8/(2·2)) = 2: 2 models 6·6 = 36; 4 models 4·10 = 40, within 30 %; 8 models
        // 3·18 = 54, 50 % more than 36
        assert_eq!(pick(2.0, 8.0, 2.0, 2.0), 4);
        // one candidate's noise does not decide: V(4) measured 30 % low (alone it would model
        // 0.875·10 = 8.75 against 2's 1.5·6 = 9) leaves the noiseless choice, 2 (N* = 1,
        // modelled 8; 2 within 30 %)
        let mut v = CANDIDATES.map(|n| 1.0 + 1.0 / n as f64);
        let cost = CANDIDATES.map(|n| 2.0 + 2.0 * n as f64);
        assert_eq!(best_count(v, cost, 0.0).branches, 2);
        v[2] *= 0.7;
        assert_eq!(best_count(v, cost, 0.0).branches, 2);
    }
}
