//! Per-thread accumulation of filtered samples over a rectangle of pixels.

use glam::{UVec2, Vec2};

use super::filter::{ReconstructionFilter, MAX_FILTER_TAPS};
use crate::Spectrum;

/// Running sums of one pixel, in f64: `Σw·L`, `Σw`, `Σw·L²`, `Σw²`.
///
/// The squared sums allow a per-pixel standard error of the developed (weighted-mean) value,
/// see [`Film::develop_stderr`](super::Film::develop_stderr).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelAccum {
    /// Σ w·L per channel.
    pub wl: [f64; 3],
    /// Σ w.
    pub w: f64,
    /// Σ w·L² per channel.
    pub wl2: [f64; 3],
    /// Σ w².
    pub w2: f64,
}

impl PixelAccum {
    /// Adds one weighted sample.
    #[inline(always)]
    pub fn add_sample(&mut self, w: f64, l: [f64; 3]) {
        for c in 0..3 {
            let wl = w * l[c];
            self.wl[c] += wl;
            self.wl2[c] += wl * l[c];
        }
        self.w += w;
        self.w2 += w * w;
    }

    /// Adds another pixel's sums.
    #[inline(always)]
    pub fn add(&mut self, o: &PixelAccum) {
        for c in 0..3 {
            self.wl[c] += o.wl[c];
            self.wl2[c] += o.wl2[c];
        }
        self.w += o.w;
        self.w2 += o.w2;
    }

    /// The weighted mean `Σw·L / Σw` (0 when `Σw = 0`).
    #[inline]
    pub fn mean(&self) -> [f64; 3] {
        if self.w > 0.0 {
            self.wl.map(|s| s / self.w)
        } else {
            [0.0; 3]
        }
    }
}

/// Accumulator for the pixels `offset .. offset + size` of a film plus a border of
/// ⌈radius − 0.5⌉ pixels on every side, so that all samples taken inside the rectangle are
/// splatted completely. Sums are kept in f64 ([`PixelAccum`]).
///
/// Coordinates given to [`put`](Self::put) are **film** pixel coordinates: pixel (i, j) covers
/// `[i, i+1) × [j, j+1)` and its centre is `(i + 0.5, j + 0.5)`.
///
/// Pixels with negative film coordinates are never written. A block made by
/// [`Film::create_block`](super::Film::create_block) also skips pixels beyond the film's right
/// and bottom edges; one made by [`ImageBlock::new`] keeps them in its border and
/// [`Film::merge`](super::Film::merge) clips them.
#[derive(Clone, Debug)]
pub struct ImageBlock {
    offset: UVec2,
    size: UVec2,
    border: u32,
    filter: ReconstructionFilter,
    /// Film coordinates of storage pixel (0, 0): offset − border (may be negative).
    origin: [i64; 2],
    /// Storage size: size + 2·border.
    stride: [i64; 2],
    /// Exclusive upper bound (film coordinates) of pixels that may be written.
    clip_max: [i64; 2],
    data: Vec<PixelAccum>,
    dropped: u64,
}

impl ImageBlock {
    /// A block for the film pixels `offset .. offset + size` (plus the filter's border).
    pub fn new(offset: UVec2, size: UVec2, filter: &ReconstructionFilter) -> ImageBlock {
        Self::with_clip(offset, size, filter, [i64::MAX, i64::MAX])
    }

    pub(crate) fn with_clip(
        offset: UVec2,
        size: UVec2,
        filter: &ReconstructionFilter,
        clip_max: [i64; 2],
    ) -> ImageBlock {
        let border = filter.border_size();
        let stride = [
            size.x as i64 + 2 * border as i64,
            size.y as i64 + 2 * border as i64,
        ];
        ImageBlock {
            offset,
            size,
            border,
            filter: *filter,
            origin: [
                offset.x as i64 - border as i64,
                offset.y as i64 - border as i64,
            ],
            stride,
            clip_max,
            data: vec![PixelAccum::default(); (stride[0] * stride[1]) as usize],
            dropped: 0,
        }
    }

    /// Film coordinates of the block's first interior pixel.
    pub fn offset(&self) -> UVec2 {
        self.offset
    }

    /// Interior size in pixels (without the border).
    pub fn size(&self) -> UVec2 {
        self.size
    }

    /// Border width in pixels on every side.
    pub fn border(&self) -> u32 {
        self.border
    }

    /// The reconstruction filter used by [`put`](Self::put).
    pub fn filter(&self) -> &ReconstructionFilter {
        &self.filter
    }

    /// Number of samples refused because their position or value was NaN or infinite.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// Moves the block to another rectangle of the same size and clears it (reuses storage).
    pub fn set_offset(&mut self, offset: UVec2) {
        self.offset = offset;
        self.origin = [
            offset.x as i64 - self.border as i64,
            offset.y as i64 - self.border as i64,
        ];
        self.clear();
    }

    /// Resets all sums and the dropped count to zero.
    pub fn clear(&mut self) {
        self.data.fill(PixelAccum::default());
        self.dropped = 0;
    }

    /// Film coordinates of the stored rectangle (border included): (min, size), min may be
    /// negative.
    pub fn storage_rect(&self) -> ([i64; 2], [i64; 2]) {
        (self.origin, self.stride)
    }

    /// The sums of the film pixel (x, y), or `None` if the block does not store that pixel.
    pub fn pixel(&self, x: i64, y: i64) -> Option<&PixelAccum> {
        let lx = x - self.origin[0];
        let ly = y - self.origin[1];
        if lx < 0 || ly < 0 || lx >= self.stride[0] || ly >= self.stride[1] {
            return None;
        }
        Some(&self.data[(ly * self.stride[0] + lx) as usize])
    }

    /// All stored pixels, row-major over [`storage_rect`](Self::storage_rect).
    pub fn pixels(&self) -> &[PixelAccum] {
        &self.data
    }

    /// Splats a radiance sample taken at film position `pos` (pixels) into every stored pixel
    /// whose centre `c` satisfies `|c − pos| < radius` on both axes, with weight
    /// `w(c.x − pos.x)·w(c.y − pos.y)`. The box filter adds the sample, with weight 1, to the
    /// one pixel containing `pos`. Non-finite positions or values are dropped and counted.
    #[inline]
    pub fn put(&mut self, pos: Vec2, value: Spectrum) {
        if !(pos.is_finite() && value.is_finite()) {
            self.dropped += 1;
            return;
        }
        let l = [value.x as f64, value.y as f64, value.z as f64];

        if self.filter.is_box() {
            let x = pos.x.floor() as i64;
            let y = pos.y.floor() as i64;
            if x < 0 || y < 0 || x >= self.clip_max[0] || y >= self.clip_max[1] {
                return;
            }
            let lx = x - self.origin[0];
            let ly = y - self.origin[1];
            if lx < 0 || ly < 0 || lx >= self.stride[0] || ly >= self.stride[1] {
                return;
            }
            self.data[(ly * self.stride[0] + lx) as usize].add_sample(1.0, l);
            return;
        }

        let mut wx = [0.0f32; MAX_FILTER_TAPS];
        let mut wy = [0.0f32; MAX_FILTER_TAPS];
        let Some((x0, nx)) = self.axis_weights(pos.x, 0, &mut wx) else { return };
        let Some((y0, ny)) = self.axis_weights(pos.y, 1, &mut wy) else { return };
        let stride = self.stride[0] as usize;
        for (j, &wyj) in wy[..ny].iter().enumerate() {
            if wyj == 0.0 {
                continue;
            }
            let row = (y0 + j) * stride + x0;
            let wyj = wyj as f64;
            for (px, &wxi) in self.data[row..row + nx].iter_mut().zip(&wx[..nx]) {
                if wxi != 0.0 {
                    px.add_sample(wyj * wxi as f64, l);
                }
            }
        }
    }

    /// Weights along one axis for the stored, writable pixels whose centres lie strictly within
    /// the radius of `p`. Returns (first local index, count), `None` when empty.
    #[inline(always)]
    fn axis_weights(&self, p: f32, axis: usize, w: &mut [f32; MAX_FILTER_TAPS]) -> Option<(usize, usize)> {
        let r = self.filter.radius();
        // Pixel j qualifies when |j + 0.5 − p| < r, i.e. p − 0.5 − r < j < p − 0.5 + r.
        let lo = ((p - 0.5 - r).floor() as i64 + 1)
            .max(0)
            .max(self.origin[axis]);
        let hi = ((p - 0.5 + r).ceil() as i64 - 1)
            .min(self.clip_max[axis] - 1)
            .min(self.origin[axis] + self.stride[axis] - 1);
        if hi < lo {
            return None;
        }
        let n = (hi - lo + 1) as usize;
        debug_assert!(n <= MAX_FILTER_TAPS);
        let n = n.min(MAX_FILTER_TAPS);
        for (k, wk) in w[..n].iter_mut().enumerate() {
            let d = (lo + k as i64) as f32 + 0.5 - p;
            *wk = if d.abs() < r { self.filter.eval(d) } else { 0.0 };
        }
        Some(((lo - self.origin[axis]) as usize, n))
    }
}
