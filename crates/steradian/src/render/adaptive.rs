//! Adaptive sampling: a camera image's samples spread over its pixels where they lower the
//! image's relative error most ([`SampleAllocation`](super::SampleAllocation); CLI
//! `--allocation`, Python `allocation=`).
//!
//! **What it minimises.** The image's mean relative variance
//!   Σ_p σ²_p / (n_p (μ²_p + f² Ȳ²))
//! over pixels p (μ_p a pixel's value per channel, σ²_p/n_p the variance of its mean over
//! n_p samples, Ȳ the image's mean), the quantity `benches/render_vs_mitsuba.py`
//! measures as relMSE, with a floor of f = [`ERROR_FLOOR`] of the image mean so that dark
//! pixels count as the eye counts them. For a fixed number of samples the minimum is at
//! n_p ∝ √v_p, v_p = σ²_p / (μ²_p + f² Ȳ²) (Lagrange: ∂/∂n_p of v_p/n_p + λ n_p = 0).
//!
//! **The pilot.** Before the render, one pixel of every [`PILOT_STRIDE`]² takes
//! [`REPLICATES`] independent scrambles of [`pilot_spp`] samples each (spp/16, 1 to 4: 6 % of
//! the samples of a 64-spp render, less of a longer one; half of that where the first half
//! finds too little to gain). The variance between the scrambles'
//! means is the error of a Sobol render itself, where the variance of one scramble's samples
//! overstates it by 1.2–5×, unevenly over the image (the reference scenes at 16 spp: on
//! cornell a density from the one-scramble variance predicted 2.9× and gave 1.02×). But four
//! scrambles rarely see a rare bright path (a caustic), and where they all miss it the
//! spread between them says nothing: a pilot pixel's estimate is the larger of that spread
//! and [`SPREAD_SHARE`] of the one its samples' own spread implies. The estimates are
//! averaged over each pilot pixel's 3 × 3 and 5 × 5 pilot neighbourhoods (the mean of the
//! two), every film pixel takes its pilot pixel's, and the densities d_p ∝ √v̄_p are
//! normalised to a mean of 1
//! within [[`MIN_DENSITY`], [`MAX_DENSITY`]]. The floor of 0.75 keeps every pixel's error
//! within 1/√0.75 = 1.15× a uniform render's, so a per-pixel test against a reference at the
//! nominal spp stays valid (at 0.5 the `gridvolume` cloud fell from 99.84 % to 99.74 % of its
//! pixels passing Mitsuba's render-test rule, below its 99.75 %). Under `Auto` the render is
//! adaptive when the densities predict a relative variance at least [`MIN_ADAPTIVE_GAIN`]
//! times lower than a uniform render's; otherwise it is uniform and the pilot's cost is lost.
//!
//! Measured (2026-12-06, Intel Xeon, 2 cores, the reference scenes at 64 spp, relMSE from two
//! seeds, `benches/results/2026-12-06-intel-xeon.md`): the prediction runs high (veach 3.45×
//! predicted, 2.13× lower relMSE obtained; materials 1.64×, 1.26×), and the samples placed cost
//! more than the mean (veach 9 % more time with its pilot). Time to relMSE 1e-3 against a
//! uniform render: veach 0.52×, materials 0.91×, cornell (predicted 1.19×: uniform) 1.03×.
//! Tried: 2 samples per scramble instead of 4 (veach relMSE 6.8e-5 against 5.7e-5); no
//! averaging over neighbours (veach 1.18e-4: no gain at all, the map is noise); a 5 × 5
//! average (veach 8.7e-5, materials 4.4e-5 against 4.7e-5); a floor of 0.2 Ȳ (within noise).
//! The samples' own spread and the two neighbourhoods (2026-12-07, AMD EPYC, 2 cores, 64 spp,
//! relMSE from pairs of seeds, `benches/results/2026-12-07-amd-epyc.md`): `glossy_spheres`
//! 1.514e-4 → 1.303e-4 (4 pairs, same time), materials 4.63e-5 → 4.33e-5 (2 pairs), veach
//! 6.32e-5 → 6.30e-5 (6 pairs); alone, the spread gave 1.473e-4, 4.33e-5 and 6.30e-5 (veach's
//! 3 × 3 average stays near its best, glossy_spheres' caustics need the wider one).
//!
//! **The render.** At nominal sample count s (the pass bounds of `schedule.rs`, unchanged),
//! pixel p holds its first ⌈d_p · s⌉ samples: passes, checkpoints, ranges and the image's
//! independence of the thread count are those of a uniform render, and `spp` is the mean per
//! pixel. Each sample's filter weights are multiplied by 1/d_p, so that a filter that splats
//! into neighbours weighs the image as a uniform render would (Σ_q n_q/d_q ∫w·L over
//! neighbours q is, up to the rounding of n_q, the uniform weighting); a pixel's value is
//! Σw·L/Σw over the samples that reached it, and its standard error follows from the same
//! weighted moments (`Film::develop_stderr`).
//!
//! **Why it is unbiased.** The pilot draws its samples from a scramble of its own (the
//! render's seed mixed with a constant): its values are independent of every sample of the
//! render, and it is not part of the image. Given the pilot, the render is a render with a
//! fixed, unequal number of samples per pixel: each pixel's samples are the first n_p of its
//! own Owen-scrambled sequence, whose mean is unbiased for any n_p, exactly as in a uniform
//! render. Had the pilot been the render's own first samples, a pixel whose first samples
//! came out low would get more samples to dilute them and one whose samples came out high
//! fewer: a bias (measured by the test beside this module, which fails for that variant).
//! Stopping at a target error (`target_error.rs`) is a rule on the whole image, as for a
//! uniform render.
//!
//! Distributed and resumed renders re-run the pilot (it is deterministic: the same densities
//! bit for bit, their digest in the sums' header) rather than ship it.

use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::block::BlockRenderer;
use super::densities::Densities;
use super::schedule::WorkItem;
use crate::film::{BoxFilter, PixelAccum};
use crate::sampling::{mix64, Sampler};
use glam::UVec2;

/// Under `Auto`, the predicted gain in relative variance at which a render is adaptive.
pub const MIN_ADAPTIVE_GAIN: f64 = 1.4;

/// Under `Auto`, renders of fewer samples per pixel are uniform (the pilot's one sample per
/// scramble would cost too large a share, and estimate too little).
pub const MIN_SPP_FOR_AUTO: u32 = 32;

/// Lowest sample density, relative to the mean (module docs).
pub const MIN_DENSITY: f64 = 0.75;

/// Highest sample density, relative to the mean.
pub const MAX_DENSITY: f64 = 16.0;

/// The relative error's floor, as a fraction of the image's mean (see the module docs): on
/// the reference scenes 0.3–0.5 gave the largest gains, 0.1 and 1 a tenth less.
pub const ERROR_FLOOR: f64 = 0.5;

/// Radius, in pilot pixels, of the smaller of the two squares over which the pilot's
/// variances are averaged (the other's is twice as large; module docs).
const SMOOTHING_RADIUS: usize = 1;

/// The share of the samples' own spread that bounds a pilot pixel's variance from below
/// (module docs).
const SPREAD_SHARE: f64 = 0.5;

/// The pilot samples one pixel in each square of this side.
pub const PILOT_STRIDE: u32 = 2;

/// Independent scrambles of the pilot (module docs).
pub const REPLICATES: usize = 4;

/// Mixed into the render's seed for the pilot's own scramble.
const PILOT_SALT: u64 = 0xada7_7e5a_3b1e_d00d;

/// What the adaptive pilot measured and decided.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveReport {
    /// Samples per pixel of the pilot.
    pub pilot_spp: u32,
    /// Its samples, all pixels.
    pub pilot_samples: u64,
    /// Its wall time.
    pub pilot_time: Duration,
    /// The ratio of a uniform render's relative variance to the adaptive one's, predicted
    /// from the pilot.
    pub predicted_gain: f64,
    /// Whether the render is adaptive (else uniform: `Auto` found too little to gain).
    pub adaptive: bool,
}

/// Samples per replicate of the pilot of a render of `spp` samples per pixel: spp/16, 1 to 4
/// (half of them first, to decide whether the rest are worth taking).
pub fn pilot_spp(spp: u32) -> u32 {
    (spp / 16).clamp(1, 4)
}

/// One pilot pixel's replicate means per channel (`None`: a replicate whose samples were all
/// dropped).
type ReplicateMeans = [Option<[f64; 3]>; REPLICATES];

/// What the pilot learnt at one pilot pixel.
#[derive(Clone, Copy, Debug)]
struct PilotPixel {
    /// Each replicate's mean.
    means: ReplicateMeans,
    /// The variance of one replicate's mean that the spread of its own samples implies, per
    /// channel, averaged over the replicates (`None` with fewer than 2 samples per replicate).
    spread: Option<[f64; 3]>,
}

impl PilotPixel {
    fn of(reps: &[PixelAccum; REPLICATES]) -> PilotPixel {
        let means = reps.map(|p| (p.w > 0.0).then(|| p.mean()));
        // each replicate's variance of its mean (its samples weigh 1 each: n is their count)
        let (mut sum, mut count) = ([0.0; 3], 0usize);
        for v in reps.iter().filter_map(PixelAccum::mean_variance) {
            for c in 0..3 {
                sum[c] += v[c];
            }
            count += 1;
        }
        let spread = (count > 0).then(|| sum.map(|s| s / count as f64));
        PilotPixel { means, spread }
    }
}

/// Renders the pilot with `blocks` (the render's own renderer: its scene, integrator and
/// sensor) and decides: the densities when the render is to be adaptive (`force`: whatever
/// the predicted gain), and the report. `None` when cancelled.
///
/// The pilot takes its samples in two stages: the first half of each scramble's, then, unless
/// they already predict less than [`MIN_ADAPTIVE_GAIN`] (and `force` is off), the rest; a
/// render whose noise is even (cornell: predicted 1.2×) pays only the first.
pub(super) fn pilot(
    blocks: &BlockRenderer,
    spp: u32,
    force: bool,
    pool: &rayon::ThreadPool,
    cancelled: &(impl Fn() -> bool + Sync),
) -> Option<(Option<Densities>, AdaptiveReport)> {
    let start = Instant::now();
    let m = pilot_spp(spp);
    let (width, height) = (blocks.width, blocks.height);
    let (gw, gh) = (width.div_ceil(PILOT_STRIDE), height.div_ceil(PILOT_STRIDE));
    let replicates: [BlockRenderer; REPLICATES] = std::array::from_fn(|r| BlockRenderer {
        sampler: Sampler {
            seed: mix64(blocks.sampler.seed ^ PILOT_SALT ^ mix64(r as u64 + 1)),
            ..blocks.sampler
        },
        filter: BoxFilter::new().into(),
        densities: None,
        // adaptive renders carry no AOV layers but the alpha channel, which the pilot skips
        aov_layers: 0,
        alpha: None,
        ..*blocks
    });
    let mut sums = vec![[PixelAccum::default(); REPLICATES]; (gw * gh) as usize];
    // samples s0..s1 of every scramble of every pilot pixel, added to `sums`
    let take = |sums: &mut [[PixelAccum; REPLICATES]], s0: u32, s1: u32| -> Option<()> {
        let rows: Vec<Option<()>> = pool.install(|| {
            sums.par_chunks_mut(gw as usize)
                .enumerate()
                .map(|(j, row)| {
                    if cancelled() {
                        return None;
                    }
                    for (i, acc) in row.iter_mut().enumerate() {
                        let pixel = UVec2::new(i as u32 * PILOT_STRIDE, j as u32 * PILOT_STRIDE);
                        let item = WorkItem { offset: pixel, size: UVec2::ONE, s0, s1 };
                        for (b, a) in replicates.iter().zip(acc.iter_mut()) {
                            let block = b.render(&item, || false).expect("never cancelled").block;
                            if let Some(p) = block.pixel(pixel.x as i64, pixel.y as i64) {
                                a.add(p);
                            }
                        }
                    }
                    Some(())
                })
                .collect()
        });
        rows.into_iter().collect()
    };
    let decide = |sums: &[[PixelAccum; REPLICATES]]| {
        let grid: Vec<PilotPixel> = sums.iter().map(PilotPixel::of).collect();
        densities(&grid, (gw as usize, gh as usize, PILOT_STRIDE as usize), width, height)
    };
    let first = m.div_ceil(2);
    take(&mut sums, 0, first)?;
    let (mut density, mut predicted_gain) = decide(&sums);
    let mut taken = first;
    if (force || predicted_gain >= MIN_ADAPTIVE_GAIN) && m > first {
        take(&mut sums, first, m)?;
        (density, predicted_gain) = decide(&sums);
        taken = m;
    }
    let adaptive = force || predicted_gain >= MIN_ADAPTIVE_GAIN;
    let report = AdaptiveReport {
        pilot_spp: taken * REPLICATES as u32,
        pilot_samples: sums.len() as u64 * (taken as u64 * REPLICATES as u64),
        pilot_time: start.elapsed(),
        predicted_gain,
        adaptive,
    };
    Some((adaptive.then(|| Densities::new(density)), report))
}

/// The densities (mean 1, one per pixel of the `width` × `height` film) that minimise the
/// relative variance the pilot's `grid` (`gw` × `gh` pilot pixels, one per `stride`² film
/// pixels) predicts, and the predicted gain over a uniform render. Uniform
/// densities (gain 1) where the pilot saw no light or no noise.
fn densities(
    grid: &[PilotPixel],
    (gw, gh, stride): (usize, usize, usize),
    width: u32,
    height: u32,
) -> (Vec<f64>, f64) {
    let (w, h) = (width as usize, height as usize);
    let uniform = (vec![1.0; w * h], 1.0);
    // the image's mean over pilot pixels, replicates and channels
    let (sum, count) = grid
        .iter()
        .flat_map(|p| p.means.iter())
        .flatten()
        .fold((0.0, 0usize), |(s, n), m| (s + m.iter().sum::<f64>(), n + 3));
    let floor2 = (ERROR_FLOOR * sum / count.max(1) as f64).powi(2);
    if !(floor2 > 0.0 && floor2.is_finite()) {
        return uniform;
    }
    // each pilot pixel's relative variance of a replicate's mean, averaged over its channels:
    // the larger of the spread between replicates and half the samples' own (module docs); a
    // pixel with fewer than 2 replicates takes the mean of the others
    let rel: Vec<Option<f64>> = grid
        .iter()
        .map(|pixel| {
            let reps: Vec<&[f64; 3]> = pixel.means.iter().flatten().collect();
            let n = reps.len() as f64;
            (reps.len() >= 2).then(|| {
                let mean: [f64; 3] =
                    std::array::from_fn(|c| reps.iter().map(|m| m[c]).sum::<f64>() / n);
                let relative = |c: usize, var: f64| var / (mean[c] * mean[c] + floor2);
                let between = (0..3)
                    .map(|c| {
                        let var =
                            reps.iter().map(|m| (m[c] - mean[c]).powi(2)).sum::<f64>() / (n - 1.0);
                        relative(c, var)
                    })
                    .sum::<f64>()
                    / 3.0;
                let within = pixel
                    .spread
                    .map_or(0.0, |v| (0..3).map(|c| relative(c, v[c])).sum::<f64>() / 3.0);
                between.max(SPREAD_SHARE * within)
            })
        })
        .collect();
    let known: Vec<f64> = rel.iter().flatten().copied().collect();
    let fill = known.iter().sum::<f64>() / known.len().max(1) as f64;
    let rel: Vec<f64> = rel.iter().map(|r| r.unwrap_or(fill)).collect();
    // the mean of the averages over squares of radius 1 and 2
    let (near, far) = (
        box_average(&rel, gw, gh, SMOOTHING_RADIUS),
        box_average(&rel, gw, gh, 2 * SMOOTHING_RADIUS),
    );
    let smooth: Vec<f64> = near.iter().zip(&far).map(|(a, b)| 0.5 * (a + b)).collect();
    // each film pixel takes its pilot pixel's relative variance
    let v: Vec<f64> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| smooth[(y / stride) * gw + x / stride])
        .collect();
    let mut density: Vec<f64> = v.iter().map(|v| v.sqrt()).collect();
    let total: f64 = density.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return uniform;
    }
    // the scale λ at which clamp(λ·d, MIN, MAX) has a mean of 1 (the mean grows with λ; the
    // bounds bracket it), by bisection, then the last rounding divided out
    let n = density.len() as f64;
    let mean_at =
        |l: f64| density.iter().map(|d| (l * d).clamp(MIN_DENSITY, MAX_DENSITY)).sum::<f64>() / n;
    let (mut lo, mut hi) = (0.0, MAX_DENSITY * n / total);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if mean_at(mid) < 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    density.iter_mut().for_each(|d| *d = (hi * *d).clamp(MIN_DENSITY, MAX_DENSITY));
    let mean = density.iter().sum::<f64>() / n;
    density.iter_mut().for_each(|d| *d /= mean);
    let uniform_var: f64 = v.iter().sum();
    let adaptive_var: f64 = v.iter().zip(&density).map(|(v, d)| v / d).sum();
    let gain = if adaptive_var > 0.0 { uniform_var / adaptive_var } else { 1.0 };
    (density, gain)
}

/// The mean of `v` (a `w` × `h` image, row-major) over each pixel's square of radius `r`,
/// clipped at the edges.
fn box_average(v: &[f64], w: usize, h: usize, r: usize) -> Vec<f64> {
    let mut out = vec![0.0; v.len()];
    for y in 0..h {
        let (y0, y1) = (y.saturating_sub(r), (y + r + 1).min(h));
        for x in 0..w {
            let (x0, x1) = (x.saturating_sub(r), (x + r + 1).min(w));
            let sum: f64 = (y0..y1).flat_map(|j| &v[j * w + x0..j * w + x1]).sum();
            out[y * w + x] = sum / ((y1 - y0) * (x1 - x0)) as f64;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pilot whose replicates agree everywhere but whose samples spread on the left half (a
    /// rare bright path seen as often in every scramble): the spread alone sends the samples
    /// there.
    #[test]
    fn the_samples_own_spread_counts() {
        let (gw, gh) = (8usize, 4usize);
        let (w, h) = (gw as u32, gh as u32);
        let grid: Vec<PilotPixel> = (0..gw * gh)
            .map(|i| PilotPixel {
                means: [Some([1.0; 3]); REPLICATES],
                spread: Some([if i % gw < gw / 2 { 0.5 } else { 0.0 }; 3]),
            })
            .collect();
        let (d, gain) = densities(&grid, (gw, gh, 1), w, h);
        assert!(d[0] > 1.0 && d[w as usize - 1] < 1.0 && gain > 1.1, "{} {} {gain}", d[0], d[7]);
        let quiet: Vec<PilotPixel> =
            grid.iter().map(|p| PilotPixel { spread: None, ..*p }).collect();
        assert_eq!(densities(&quiet, (gw, gh, 1), w, h).1, 1.0);
    }

    /// A pilot whose left half varies between replicates and whose right half does not: the
    /// noisy half gets the samples, the quiet half the floor, the mean stays 1 and the gain
    /// is predicted; a pilot without noise or without light gives a uniform render.
    #[test]
    fn noisy_pixels_get_more_samples() {
        let (gw, gh) = (8usize, 4usize);
        let (w, h) = (2 * gw as u32 - 1, 2 * gh as u32);
        let grid: Vec<PilotPixel> = (0..gw * gh)
            .map(|i| {
                let noisy = i % gw < gw / 2;
                let means = std::array::from_fn(|r| {
                    Some([if noisy { (r % 2) as f64 * 2.0 } else { 1.0 }; 3])
                });
                PilotPixel { means, spread: None }
            })
            .collect();
        let (d, gain) = densities(&grid, (gw, gh, 2), w, h);
        assert_eq!(d.len(), (w * h) as usize);
        let mean = d.iter().sum::<f64>() / d.len() as f64;
        assert!((mean - 1.0).abs() < 1e-12, "{mean}");
        let (left, right) = (d[0], d[w as usize - 1]);
        assert!(left > 1.0 && right <= MIN_DENSITY + 1e-9, "{left} {right}");
        assert!(d.iter().all(|&x| (MIN_DENSITY - 1e-9..=MAX_DENSITY).contains(&x)));
        assert!(gain > 1.1, "{gain}");
        // every film pixel takes its pilot pixel's density: pixels (0, 0) and (1, 1) share one
        assert_eq!(d[0], d[w as usize + 1]);
        let pixel = |m: f64| PilotPixel { means: [Some([m; 3]); REPLICATES], spread: None };
        let flat = vec![pixel(1.0); gw * gh];
        assert_eq!(densities(&flat, (gw, gh, 2), w, h), (vec![1.0; (w * h) as usize], 1.0));
        let dark = vec![pixel(0.0); gw * gh];
        assert_eq!(densities(&dark, (gw, gh, 2), w, h), (vec![1.0; (w * h) as usize], 1.0));
    }

    /// Why the pilot has a scramble of its own, on a model of the render: pixels whose samples
    /// are 10 with probability 0.1 and 0 otherwise (mean 1, skewed as a path tracer's are),
    /// densities from [`densities`], each pixel's estimate the mean of its first
    /// ⌈d · 64⌉ samples. With the pilot's replicates drawn apart from the render's samples the
    /// mean over pixels and trials is 1 within its standard error; with the pilot's replicates
    /// taken from the pixel's own first samples (a pixel whose first samples were high gets
    /// fewer samples to dilute them, and the other way round) it is not.
    #[test]
    fn the_pilot_must_be_independent_of_the_render() {
        use crate::sampling::Pcg32;
        let (gw, gh) = (16usize, 16usize);
        let (w, h) = (gw as u32, gh as u32);
        let draw = |rng: &mut Pcg32| if rng.next_f64() < 0.1 { 10.0 } else { 0.0 };
        // (mean, standard error) of the pixel estimates over `trials` images
        let run = |own: bool| {
            let (mut sum, mut sum2, mut n) = (0.0, 0.0, 0.0);
            for trial in 0..3000u64 {
                // each pixel's own stream of samples, and a pilot stream apart from it
                let mut render: Vec<Pcg32> =
                    (0..gw * gh).map(|p| Pcg32::new(trial, 2 * p as u64)).collect();
                let mut apart: Vec<Pcg32> =
                    (0..gw * gh).map(|p| Pcg32::new(trial, 2 * p as u64 + 1)).collect();
                let mut taken: Vec<Vec<f64>> = vec![Vec::new(); gw * gh];
                let grid: Vec<PilotPixel> = (0..gw * gh)
                    .map(|p| PilotPixel {
                        spread: None,
                        means: std::array::from_fn(|_| {
                            let mean = (0..2)
                                .map(|_| {
                                    if own {
                                        let v = draw(&mut render[p]);
                                        taken[p].push(v);
                                        v
                                    } else {
                                        draw(&mut apart[p])
                                    }
                                })
                                .sum::<f64>()
                                / 2.0;
                            Some([mean; 3])
                        }),
                    })
                    .collect();
                // one pilot pixel per film pixel
                let (d, _) = densities(&grid, (gw, gh, 1), w, h);
                let d = Densities::new(d);
                for (p, taken) in taken.iter_mut().enumerate() {
                    let count = d.count(p, 64) as usize;
                    while taken.len() < count {
                        taken.push(draw(&mut render[p]));
                    }
                    let m = taken[..count].iter().sum::<f64>() / count as f64;
                    (sum, sum2, n) = (sum + m, sum2 + m * m, n + 1.0);
                }
            }
            let mean = sum / n;
            (mean, ((sum2 / n - mean * mean) / (n - 1.0)).sqrt())
        };
        let (m, se) = run(false);
        eprintln!("independent pilot: {m} ± {se}");
        assert!(((m - 1.0) / se).abs() < 4.0, "independent pilot: {m} ± {se}");
        let (m, se) = run(true);
        eprintln!("own samples as the pilot: {m} ± {se}");
        assert!(((m - 1.0) / se).abs() > 4.0, "own samples as the pilot: {m} ± {se}");
    }

    #[test]
    fn box_average_is_the_clipped_mean() {
        let v: Vec<f64> = (0..12).map(|i| i as f64).collect();
        let a = box_average(&v, 4, 3, 1);
        assert_eq!(a[0], (0.0 + 1.0 + 4.0 + 5.0) / 4.0);
        assert_eq!(
            a[5],
            (0..3).flat_map(|j| (0..3).map(move |i| (j * 4 + i) as f64)).sum::<f64>() / 9.0
        );
    }
}
