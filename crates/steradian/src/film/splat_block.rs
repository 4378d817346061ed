//! Splats of particle tracing: light paths add their contributions to any pixel of the film.
//!
//! A [`SplatBlock`] covers the whole film and holds one pass's sums Σ v per pixel (f64). A splat
//! at film position `pos` spreads its value over the pixels whose centres lie within the
//! filter's radius with the filter's weights normalised to sum 1 over the whole footprint (as
//! Mitsuba 3's particle tracer normalises them); weights of pixels outside the film are lost
//! with their share, as in Mitsuba. The box filter gives the one pixel holding `pos` the whole
//! value. Non-finite splats are dropped and counted.

use glam::Vec2;

use super::filter::{ReconstructionFilter, MAX_FILTER_TAPS};
use super::image_block::tap_offsets;
use crate::Spectrum;

/// One pass's splat sums over a whole film.
#[derive(Clone, Debug)]
pub struct SplatBlock {
    width: u32,
    height: u32,
    filter: ReconstructionFilter,
    sums: Vec<[f64; 3]>,
    dropped: u64,
}

impl SplatBlock {
    /// An empty block for a `width` × `height` film with `filter`.
    pub fn new(width: u32, height: u32, filter: ReconstructionFilter) -> SplatBlock {
        let n = width as usize * height as usize;
        SplatBlock { width, height, filter, sums: vec![[0.0; 3]; n], dropped: 0 }
    }

    /// Film width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Film height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Per-pixel sums, row-major.
    pub fn sums(&self) -> &[[f64; 3]] {
        &self.sums
    }

    /// Splats dropped for a non-finite position or value.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// Counts a path dropped before it splatted (a non-finite weight found on the way).
    pub fn count_dropped(&mut self) {
        self.dropped += 1;
    }

    /// Adds `value` at film position `pos` (pixels).
    #[inline]
    pub fn splat(&mut self, pos: Vec2, value: Spectrum) {
        if !(pos.is_finite() && value.is_finite()) {
            self.dropped += 1;
            return;
        }
        let l = [value.x as f64, value.y as f64, value.z as f64];
        if self.filter.is_box() {
            let (x, y) = (pos.x.floor() as i64, pos.y.floor() as i64);
            if x >= 0 && y >= 0 && x < self.width as i64 && y < self.height as i64 {
                let px = &mut self.sums[(y * self.width as i64 + x) as usize];
                for c in 0..3 {
                    px[c] += l[c];
                }
            }
            return;
        }
        let (mut wx, mut wy) = ([0.0f32; MAX_FILTER_TAPS], [0.0f32; MAX_FILTER_TAPS]);
        let Some((x0, nx)) = self.taps(pos.x, &mut wx) else { return };
        let Some((y0, ny)) = self.taps(pos.y, &mut wy) else { return };
        for (j, &wyj) in wy[..ny].iter().enumerate() {
            let y = y0 + j as i64;
            if wyj == 0.0 || y < 0 || y >= self.height as i64 {
                continue;
            }
            for (i, &wxi) in wx[..nx].iter().enumerate() {
                let x = x0 + i as i64;
                if wxi == 0.0 || x < 0 || x >= self.width as i64 {
                    continue;
                }
                let w = wxi as f64 * wyj as f64;
                let px = &mut self.sums[(y * self.width as i64 + x) as usize];
                for c in 0..3 {
                    px[c] += w * l[c];
                }
            }
        }
    }

    /// The normalised weights of the pixels along one axis whose centres lie within the
    /// filter's radius of `p` (the whole footprint, inside the film or not): first pixel and
    /// count; `None` when the weights sum to 0.
    fn taps(&self, p: f32, w: &mut [f32; MAX_FILTER_TAPS]) -> Option<(i64, usize)> {
        let r = self.filter.radius();
        let lo = (p - 0.5 - r).floor() as i64 + 1;
        let hi = (p - 0.5 + r).ceil() as i64 - 1;
        let n = ((hi - lo + 1).max(0) as usize).min(MAX_FILTER_TAPS);
        tap_offsets(lo, p, &mut w[..n]);
        self.filter.eval_in_place(&mut w[..n]);
        let sum: f32 = w[..n].iter().sum();
        if sum == 0.0 || !sum.is_finite() {
            return None;
        }
        w[..n].iter_mut().for_each(|x| *x /= sum);
        Some((lo, n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::{GaussianFilter, TentFilter};

    #[test]
    fn a_splat_inside_the_film_keeps_its_value() {
        for filter in [
            ReconstructionFilter::default(),
            TentFilter::new(1.0).unwrap().into(),
            GaussianFilter::new(0.5).unwrap().into(),
            crate::film::BoxFilter::new().into(),
        ] {
            let mut b = SplatBlock::new(16, 16, filter);
            b.splat(Vec2::new(7.3, 8.9), Spectrum::new(1.0, 2.0, 3.0));
            let total: [f64; 3] =
                b.sums().iter().fold([0.0; 3], |a, p| [a[0] + p[0], a[1] + p[1], a[2] + p[2]]);
            for (c, want) in [1.0, 2.0, 3.0].iter().enumerate() {
                assert!((total[c] - want).abs() < 1e-5, "{filter:?}: {total:?}");
            }
        }
        // at the border part of the footprint is lost, not folded back
        let mut b = SplatBlock::new(16, 16, TentFilter::new(1.0).unwrap().into());
        b.splat(Vec2::new(0.1, 8.5), Spectrum::splat(1.0));
        let total: f64 = b.sums().iter().map(|p| p[0]).sum();
        assert!(total < 0.9 && total > 0.3, "{total}");
        b.splat(Vec2::new(f32::NAN, 1.0), Spectrum::splat(1.0));
        assert_eq!(b.dropped(), 1);
    }
}
