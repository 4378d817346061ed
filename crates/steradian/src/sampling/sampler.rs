//! Samplers: where the uniform numbers for one pixel sample come from.
//!
//! Every sample is addressed by (pixel, sample index, seed), so an image does not depend on
//! how the work is split over threads or passes: the same seed always gives the same image.

use glam::{UVec2, Vec2};

use super::pcg32::{mix64, Pcg32};

/// The sampler families steradian accepts (Mitsuba's sampler plugins).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    /// `independent`: i.i.d. uniform numbers (PCG32).
    Independent,
    /// `stratified`, `multijitter`, `orthogonal`, `ldsampler`: stratified sample sets. All map
    /// to the same per-pixel stratification of the first (film) dimensions and i.i.d. numbers
    /// for the rest: unbiased, with less noise at the pixel level.
    Stratified,
}

/// A sampler description: how many samples per pixel and with which seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampler {
    pub kind: SamplerKind,
    /// Samples per pixel.
    pub sample_count: u32,
    /// Seed; different seeds give independent images.
    pub seed: u64,
}

impl Default for Sampler {
    /// Mitsuba's default: `independent`, 4 samples per pixel, seed 0.
    fn default() -> Self {
        Sampler { kind: SamplerKind::Independent, sample_count: 4, seed: 0 }
    }
}

impl Sampler {
    /// The stream of numbers for sample `index` of `pixel` (an image of `width` pixels per row).
    #[inline]
    pub fn pixel_sampler(&self, pixel: UVec2, width: u32, index: u32) -> PixelSampler {
        let pixel_id = pixel.y as u64 * width as u64 + pixel.x as u64;
        let stream = mix64(pixel_id ^ mix64(self.seed.wrapping_add(0x9e37_79b9_7f4a_7c15)));
        let rng = Pcg32::new(mix64((index as u64) ^ (stream << 1)), stream);
        PixelSampler { rng, kind: self.kind, index, count: self.sample_count.max(1), dim: 0 }
    }
}

/// The numbers for one pixel sample.
#[derive(Clone, Debug)]
pub struct PixelSampler {
    rng: Pcg32,
    kind: SamplerKind,
    index: u32,
    count: u32,
    dim: u32,
}

impl PixelSampler {
    /// A stand-alone stream (tests, meters): i.i.d. numbers from `seed` and `stream`.
    pub fn independent(seed: u64, stream: u64) -> Self {
        PixelSampler { rng: Pcg32::new(mix64(seed), stream), kind: SamplerKind::Independent, index: 0, count: 1, dim: 0 }
    }

    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        self.dim += 1;
        self.rng.next_f32()
    }

    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        let dim = self.dim;
        self.dim += 2;
        let u = Vec2::new(self.rng.next_f32(), self.rng.next_f32());
        match self.kind {
            SamplerKind::Stratified if dim == 0 => stratify(u, self.index, self.count),
            _ => u,
        }
    }
}

/// Places `u` in stratum `index` of a ⌈√count⌉ × ⌈√count⌉ grid (strata beyond `count` are never
/// used when `count` is not a square; each used stratum is still sampled uniformly, so the
/// estimator stays unbiased only when `count` is a perfect square — otherwise the strata are
/// permuted per `index` so that every stratum is equally likely).
fn stratify(u: Vec2, index: u32, count: u32) -> Vec2 {
    let n = (count as f32).sqrt() as u32;
    if n * n != count || n <= 1 {
        return u;
    }
    let sx = index % n;
    let sy = index / n;
    Vec2::new((sx as f32 + u.x) / n as f32, (sy as f32 + u.y) / n as f32).min(Vec2::splat(1.0 - f32::EPSILON / 2.0))
}
