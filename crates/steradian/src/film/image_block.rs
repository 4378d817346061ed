//! Per-thread accumulation of filtered samples over a rectangle of pixels.

use glam::{UVec2, Vec2};

use super::filter::{ReconstructionFilter, MAX_FILTER_TAPS};
use crate::Spectrum;

/// Taps per axis of the small-footprint splat path.
const SMALL_TAPS: usize = 8;

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
        for ((s1, s2), lc) in self.wl.iter_mut().zip(self.wl2.iter_mut()).zip(l) {
            let wl = w * lc;
            *s1 += wl;
            *s2 += wl * lc;
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

    /// The variance of the weighted mean per channel, s²/n: s² = n/(n − 1)·(mean of L² −
    /// mean²), the weighted sample variance over the effective sample count n = (Σw)²/Σw²;
    /// `None` without weight or with n ≤ 1 (one sample says nothing of the spread).
    #[inline]
    pub fn mean_variance(&self) -> Option<[f64; 3]> {
        if !(self.w > 0.0 && self.w2 > 0.0) {
            return None;
        }
        let n_eff = self.w * self.w / self.w2;
        if n_eff <= 1.0 + 1e-9 {
            return None;
        }
        Some(std::array::from_fn(|c| {
            let m = self.wl[c] / self.w;
            (self.wl2[c] / self.w - m * m).max(0.0) / (n_eff - 1.0)
        }))
    }

    /// The weighted mean `Σw·L / Σw` (0 when `Σw = 0`; filters with negative lobes can leave
    /// `Σw < 0` in a pixel with few samples, which is divided as Mitsuba divides it).
    #[inline]
    pub fn mean(&self) -> [f64; 3] {
        if self.w != 0.0 {
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
    /// Σw·a of each AOV layer a (three channels each), pixel-major: pixel i's layer k at
    /// `i·aov_layers + k`. Empty unless an integrator writes AOVs (`moment`).
    aov: Vec<[f64; 3]>,
    aov_layers: usize,
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
        let stride = [size.x as i64 + 2 * border as i64, size.y as i64 + 2 * border as i64];
        ImageBlock {
            offset,
            size,
            border,
            filter: *filter,
            origin: [offset.x as i64 - border as i64, offset.y as i64 - border as i64],
            stride,
            clip_max,
            data: vec![PixelAccum::default(); (stride[0] * stride[1]) as usize],
            aov: Vec::new(),
            aov_layers: 0,
            dropped: 0,
        }
    }

    /// The block with `layers` AOV layers of three channels, splatted by
    /// [`put_with_aovs`](Self::put_with_aovs) with the same weights as the radiance.
    pub fn with_aov_layers(mut self, layers: usize) -> Self {
        self.aov_layers = layers;
        self.aov = vec![[0.0; 3]; self.data.len() * layers];
        self
    }

    /// Number of AOV layers.
    pub fn aov_layers(&self) -> usize {
        self.aov_layers
    }

    /// The AOV sums Σw·a, pixel-major over [`storage_rect`](Self::storage_rect), then layer.
    pub fn aovs(&self) -> &[[f64; 3]] {
        &self.aov
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
        self.origin = [offset.x as i64 - self.border as i64, offset.y as i64 - self.border as i64];
        self.clear();
    }

    /// Counts `n` samples dropped before they reached the block (a NaN/Inf estimate).
    pub fn add_dropped(&mut self, n: u64) {
        self.dropped += n;
    }

    /// Resets all sums and the dropped count to zero.
    pub fn clear(&mut self) {
        self.data.fill(PixelAccum::default());
        self.aov.fill([0.0; 3]);
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
        self.put_with_aovs(pos, value, &[]);
    }

    /// [`put`](Self::put) that also splats one value per AOV layer (`aovs.len()` equal to
    /// [`aov_layers`](Self::aov_layers), or empty). A sample with any non-finite value is
    /// dropped whole.
    #[inline]
    pub fn put_with_aovs(&mut self, pos: Vec2, value: Spectrum, aovs: &[Spectrum]) {
        self.put_scaled(pos, value, aovs, 1.0);
    }

    /// [`put_with_aovs`](Self::put_with_aovs) with every filter weight multiplied by `scale`
    /// (> 0): an adaptive render weighs each sample by the inverse of its pixel's sample
    /// density, so that the filter's expectation is that of a uniform render.
    #[inline]
    pub fn put_scaled(&mut self, pos: Vec2, value: Spectrum, aovs: &[Spectrum], scale: f64) {
        if !(pos.is_finite() && value.is_finite() && aovs.iter().all(|a| a.is_finite())) {
            self.dropped += 1;
            return;
        }
        debug_assert!(aovs.is_empty() || aovs.len() == self.aov_layers);
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
            let i = (ly * self.stride[0] + lx) as usize;
            self.data[i].add_sample(scale, l);
            self.add_aovs(i, scale, aovs);
            return;
        }

        let Some((x0, lo_x, nx)) = self.axis_range(pos.x, 0) else {
            return;
        };
        let Some((y0, lo_y, ny)) = self.axis_range(pos.y, 1) else {
            return;
        };
        if nx <= SMALL_TAPS && ny <= SMALL_TAPS {
            // the common case (every filter up to a radius of 4 px): both axes' offsets in one
            // small array, weighed in one branch-free pass (vector code) and no large array
            // to clear
            let mut w = [0.0f32; 2 * SMALL_TAPS];
            let (wx, wy) = w.split_at_mut(SMALL_TAPS);
            tap_offsets(lo_x, pos.x, wx);
            tap_offsets(lo_y, pos.y, wy);
            self.filter.eval_in_place(&mut w);
            self.splat(x0, &w[..nx], y0, &w[SMALL_TAPS..SMALL_TAPS + ny], l, aovs, scale);
        } else {
            let mut wx = [0.0f32; MAX_FILTER_TAPS];
            let mut wy = [0.0f32; MAX_FILTER_TAPS];
            tap_offsets(lo_x, pos.x, &mut wx[..nx]);
            tap_offsets(lo_y, pos.y, &mut wy[..ny]);
            self.filter.eval_in_place(&mut wx[..nx]);
            self.filter.eval_in_place(&mut wy[..ny]);
            self.splat(x0, &wx[..nx], y0, &wy[..ny], l, aovs, scale);
        }
    }

    /// Adds `l` with weight `scale·wy[j]·wx[i]` to local pixel (x0 + i, y0 + j).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn splat(
        &mut self,
        x0: usize,
        wx: &[f32],
        y0: usize,
        wy: &[f32],
        l: [f64; 3],
        aovs: &[Spectrum],
        scale: f64,
    ) {
        let stride = self.stride[0] as usize;
        for (j, &wyj) in wy.iter().enumerate() {
            if wyj == 0.0 {
                continue;
            }
            let row = (y0 + j) * stride + x0;
            let wyj = wyj as f64 * scale;
            for (px, &wxi) in self.data[row..row + wx.len()].iter_mut().zip(wx) {
                if wxi != 0.0 {
                    px.add_sample(wyj * wxi as f64, l);
                }
            }
            if !aovs.is_empty() {
                for (i, &wxi) in wx.iter().enumerate() {
                    if wxi != 0.0 {
                        self.add_aovs(row + i, wyj * wxi as f64, aovs);
                    }
                }
            }
        }
    }

    /// Adds w·a of each AOV layer to storage pixel `i`.
    #[inline(always)]
    fn add_aovs(&mut self, i: usize, w: f64, aovs: &[Spectrum]) {
        let n = self.aov_layers;
        for (acc, a) in self.aov[i * n..i * n + aovs.len()].iter_mut().zip(aovs) {
            for c in 0..3 {
                acc[c] += w * a[c] as f64;
            }
        }
    }

    /// The stored, writable pixels along one axis whose centres lie strictly within the radius
    /// of `p`: (first local index, first film index, count), `None` when there are none.
    #[inline(always)]
    fn axis_range(&self, p: f32, axis: usize) -> Option<(usize, i64, usize)> {
        let r = self.filter.radius();
        // Pixel j qualifies when |j + 0.5 − p| < r, i.e. p − 0.5 − r < j < p − 0.5 + r.
        let lo = ((p - 0.5 - r).floor() as i64 + 1).max(0).max(self.origin[axis]);
        let hi = ((p - 0.5 + r).ceil() as i64 - 1)
            .min(self.clip_max[axis] - 1)
            .min(self.origin[axis] + self.stride[axis] - 1);
        if hi < lo {
            return None;
        }
        let n = (hi - lo + 1) as usize;
        debug_assert!(n <= MAX_FILTER_TAPS);
        Some(((lo - self.origin[axis]) as usize, lo, n.min(MAX_FILTER_TAPS)))
    }
}

/// Offsets (pixels) from `p` to the centres of the pixels `lo`, `lo + 1`, … along one axis.
#[inline(always)]
pub(super) fn tap_offsets(lo: i64, p: f32, out: &mut [f32]) {
    for (k, d) in out.iter_mut().enumerate() {
        *d = (lo + k as i64) as f32 + 0.5 - p;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::filter::{BoxFilter, GaussianFilter, TentFilter};

    /// Checks that a block holding one sample `l` at `pos` has exactly the expected weights in
    /// every stored pixel: `w(dx)·w(dy)` where both |d| < r, untouched elsewhere.
    fn check_single_splat(filter: ReconstructionFilter, pos: Vec2, expect_touched: usize) {
        let l = Spectrum::new(1.0, 2.0, 3.0);
        let mut b = ImageBlock::new(UVec2::new(0, 0), UVec2::new(12, 10), &filter);
        b.put(pos, l);
        let (o, s) = b.storage_rect();
        let r = filter.radius();
        let mut touched = 0;
        for y in o[1]..o[1] + s[1] {
            for x in o[0]..o[0] + s[0] {
                let p = b.pixel(x, y).unwrap();
                let dx = x as f32 + 0.5 - pos.x;
                let dy = y as f32 + 0.5 - pos.y;
                let inside = if filter.is_box() {
                    x == pos.x.floor() as i64 && y == pos.y.floor() as i64
                } else {
                    dx.abs() < r && dy.abs() < r
                };
                if inside && x >= 0 && y >= 0 {
                    touched += 1;
                    let w = if filter.is_box() {
                        1.0
                    } else {
                        filter.eval(dy) as f64 * filter.eval(dx) as f64
                    };
                    assert!(w > 0.0);
                    assert!((p.w - w).abs() <= 1e-15, "({x},{y}) {} vs {w}", p.w);
                    assert!((p.w2 - w * w).abs() <= 1e-15);
                    for c in 0..3 {
                        let lc = l[c] as f64;
                        assert!((p.wl[c] - w * lc).abs() <= 1e-14);
                        assert!((p.wl2[c] - w * lc * lc).abs() <= 1e-14);
                    }
                } else {
                    assert_eq!(*p, PixelAccum::default(), "pixel ({x},{y}) was touched");
                }
            }
        }
        assert_eq!(touched, expect_touched, "{} at {pos}", filter.plugin_name());
    }

    /// AOV layers are splatted with the radiance's weights: every pixel holds w·a for each
    /// layer where it holds w·L.
    #[test]
    fn aovs_share_the_radiance_weights() {
        let g = ReconstructionFilter::from(GaussianFilter::default());
        let mut b = ImageBlock::new(UVec2::new(0, 0), UVec2::new(8, 8), &g).with_aov_layers(2);
        let (l, a) = (Spectrum::splat(1.0), [Spectrum::new(2.0, 3.0, 4.0), Spectrum::splat(-1.0)]);
        b.put_with_aovs(Vec2::new(3.3, 4.6), l, &a);
        let mut touched = 0;
        for (i, p) in b.pixels().iter().enumerate() {
            for (k, ak) in a.iter().enumerate() {
                for c in 0..3 {
                    assert_eq!(b.aovs()[2 * i + k][c], p.w * ak[c] as f64);
                }
            }
            touched += (p.w > 0.0) as usize;
        }
        assert_eq!(touched, 16);
        b.put_with_aovs(Vec2::new(3.3, 4.6), l, &[Spectrum::splat(f32::NAN), Spectrum::ONE]);
        assert_eq!(b.dropped(), 1);
    }

    #[test]
    fn gaussian_splat_footprint() {
        let g = ReconstructionFilter::from(GaussianFilter::default());
        // x centres within 2 of 5.3: 3.5 .. 6.5 (4 pixels); y within 2 of 4.8: 2.5 .. 6.5 (4).
        check_single_splat(g, Vec2::new(5.3, 4.8), 16);
        // A sample on a pixel centre: 3 pixels each way (the ones at distance 2 have w = 0 and
        // are excluded by the strict test).
        check_single_splat(g, Vec2::new(5.5, 4.5), 9);
        // Near the top-left corner: negative pixels are never written.
        check_single_splat(g, Vec2::new(0.2, 0.7), 2 * 3);
    }

    #[test]
    fn tent_and_box_splat_footprint() {
        check_single_splat(TentFilter::default().into(), Vec2::new(5.3, 4.8), 4);
        check_single_splat(TentFilter::new(1.6).unwrap().into(), Vec2::new(5.3, 4.8), 9);
        check_single_splat(BoxFilter::new().into(), Vec2::new(5.3, 4.8), 1);
        check_single_splat(BoxFilter::new().into(), Vec2::new(0.0, 9.999), 1);
    }

    #[test]
    fn out_of_bounds_samples_are_safe() {
        for f in [
            ReconstructionFilter::from(BoxFilter::new()),
            TentFilter::new(2.5).unwrap().into(),
            GaussianFilter::default().into(),
        ] {
            let mut b = ImageBlock::new(UVec2::new(4, 4), UVec2::new(3, 2), &f);
            for p in [
                Vec2::new(-100.0, -100.0),
                Vec2::new(-0.5, 5.0),
                Vec2::new(1e9, 5.0),
                Vec2::new(5.0, -1e9),
                Vec2::new(0.0, 0.0),
                Vec2::new(30.0, 30.0),
            ] {
                b.put(p, Spectrum::ONE);
            }
            assert!(b.pixels().iter().all(|p| p.w == 0.0), "{}", f.plugin_name());
            b.put(Vec2::new(f32::NAN, 5.0), Spectrum::ONE);
            b.put(Vec2::new(5.0, 5.0), Spectrum::new(f32::INFINITY, 0.0, 0.0));
            b.put(Vec2::new(5.0, 5.0), Spectrum::new(0.0, f32::NAN, 0.0));
            assert_eq!(b.dropped(), 3);
            assert!(b.pixels().iter().all(|p| p.w == 0.0));
            b.put(Vec2::new(5.2, 5.7), Spectrum::ONE);
            assert!(b.pixels().iter().any(|p| p.w > 0.0));
            b.clear();
            assert!(b.pixels().iter().all(|p| *p == PixelAccum::default()));
            assert_eq!(b.dropped(), 0);
        }
    }
}
