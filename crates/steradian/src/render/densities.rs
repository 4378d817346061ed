//! An adaptive render's per-pixel sample densities (`adaptive.rs` decides them): how many
//! samples each pixel holds at a nominal sample count, and the weight of each.

use crate::sampling::mix64;

/// Per-pixel sample densities (mean 1) of an adaptive render.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Densities {
    density: Vec<f64>,
    /// 1/density: each sample's filter weight factor.
    weight: Vec<f64>,
    /// Nonzero digest of the densities' bits (the sums' header records it).
    pub digest: u64,
}

impl Densities {
    /// From densities of mean 1.
    pub fn new(density: Vec<f64>) -> Densities {
        let digest = density.iter().fold(0x5eed_u64, |h, d| mix64(h ^ d.to_bits())) | 1;
        let weight = density.iter().map(|d| 1.0 / d).collect();
        Densities { density, weight, digest }
    }

    /// Samples of pixel `pixel` (row-major index) at nominal sample count `s`: ⌈d · s⌉, at
    /// least 1 once s ≥ 1, never fewer at a larger s.
    #[inline]
    pub fn count(&self, pixel: usize, s: u32) -> u32 {
        (self.density[pixel] * s as f64).ceil() as u32
    }

    /// The filter weight factor of pixel `pixel`'s samples.
    #[inline]
    pub fn weight(&self, pixel: usize) -> f64 {
        self.weight[pixel]
    }

    /// Samples of all pixels at nominal sample count `s`.
    pub fn samples_at(&self, s: u32) -> u64 {
        (0..self.density.len()).map(|p| self.count(p, s) as u64).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_follow_the_densities_and_never_shrink() {
        let d = Densities::new(vec![0.5, 1.0, 1.5, 1.0]);
        for s in 0..200 {
            for p in 0..4 {
                assert!(d.count(p, s + 1) >= d.count(p, s));
                assert!(s == 0 || d.count(p, s) >= 1);
                assert!(d.count(p, s) as f64 >= d.density[p] * s as f64);
                assert!((d.count(p, s) as f64) < d.density[p] * s as f64 + 1.0);
            }
        }
        assert_eq!(d.samples_at(64), 32 + 64 + 96 + 64);
        assert_eq!(d.weight(0), 2.0);
        assert_ne!(d.digest, Densities::new(vec![1.0; 4]).digest);
    }
}
