//! # `hdrfilm` — high dynamic range film
//!
//! Mitsuba plugin `hdrfilm`: accumulates filtered radiance samples per pixel and develops them
//! into a linear, unclamped RGB image.
//!
//! | parameter          | type    | default      | meaning                                          |
//! |--------------------|---------|--------------|--------------------------------------------------|
//! | `width`            | integer | 768          | image width in pixels (1 ..= 32768)              |
//! | `height`           | integer | 576          | image height in pixels (1 ..= 32768)             |
//! | `pixel_format`     | string  | `"rgb"`      | only `rgb` (no alpha) is supported               |
//! | `component_format` | string  | `"float16"`  | `float16` or `float32`: precision of files the film writes itself; developed images are always f32 |
//! | `sample_border`    | boolean | false        | also sample pixels just outside the film so that edge pixels get the same filter support as interior ones |
//! | `rfilter`          | filter  | `gaussian`   | reconstruction filter (σ = 0.5 px, radius 2 px)  |
//!
//! Pixel (i, j) covers `[i, i+1) × [j, j+1)` in film coordinates (x right, y down, row 0 on
//! top); its centre is `(i + 0.5, j + 0.5)`. A sample at `p` is splatted to all pixels whose
//! centres lie within the filter radius of `p` on both axes, with weight `w(dx)·w(dy)`, and each
//! pixel develops to the weighted mean `Σw·L / Σw` (so edge pixels are normalised too; pixels
//! with no weight develop to 0). Sums are kept in f64: Mitsuba's scalar film sums in f32 and
//! drifts (≈ +0.7 % on a 4M-sample pixel); steradian does not copy that.
//!
//! Rendering threads fill [`ImageBlock`]s (from [`Film::create_block`]) and [`Film::merge`]
//! them; several films of the same size (passes, machines) combine with
//! [`Film::accumulate`].

use glam::UVec2;

use super::filter::ReconstructionFilter;
use super::image::Image;
use super::image_block::{ImageBlock, PixelAccum};

/// Largest accepted width or height, in pixels.
pub const MAX_FILM_SIZE: u32 = 1 << 15;

/// Precision of the files a film writes itself (`component_format`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ComponentFormat {
    /// IEEE half floats (Mitsuba's default).
    #[default]
    Float16,
    /// IEEE single floats.
    Float32,
}

impl ComponentFormat {
    /// Parses Mitsuba's `component_format` string.
    pub fn parse(s: &str) -> Result<ComponentFormat, String> {
        match s {
            "float16" => Ok(ComponentFormat::Float16),
            "float32" => Ok(ComponentFormat::Float32),
            other => Err(format!(
                "hdrfilm: unsupported component_format \"{other}\" (expected \"float16\" or \"float32\")"
            )),
        }
    }
}

/// The film: per-pixel f64 sums of filtered samples (see the module documentation).
#[derive(Clone, Debug)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    pub filter: ReconstructionFilter,
    /// Precision for files written by the film itself (default float16).
    pub component_format: ComponentFormat,
    /// Whether the sensor should also sample the border pixels outside the film (default false).
    pub sample_border: bool,
    data: Vec<PixelAccum>,
    dropped: u64,
}

impl Default for Film {
    /// Mitsuba's default `hdrfilm`: 768×576, gaussian filter.
    fn default() -> Self {
        Film::new(768, 576, ReconstructionFilter::default()).expect("default film size is valid")
    }
}

impl Film {
    /// Default width in pixels.
    pub const DEFAULT_WIDTH: u32 = 768;
    /// Default height in pixels.
    pub const DEFAULT_HEIGHT: u32 = 576;

    /// A cleared film. Errors on a zero size or a side larger than [`MAX_FILM_SIZE`].
    pub fn new(width: u32, height: u32, filter: ReconstructionFilter) -> Result<Film, String> {
        if width == 0 || height == 0 {
            return Err(format!(
                "hdrfilm: film size must be at least 1x1 pixels, got {width}x{height}"
            ));
        }
        if width > MAX_FILM_SIZE || height > MAX_FILM_SIZE {
            return Err(format!(
                "hdrfilm: film size {width}x{height} is too large (at most {MAX_FILM_SIZE} pixels per side)"
            ));
        }
        Ok(Film {
            width,
            height,
            filter,
            component_format: ComponentFormat::default(),
            sample_border: false,
            data: vec![PixelAccum::default(); width as usize * height as usize],
            dropped: 0,
        })
    }

    /// Film size in pixels.
    pub fn size(&self) -> UVec2 {
        UVec2::new(self.width, self.height)
    }

    /// A block for the film pixels `offset .. offset + size`, using the film's filter; it never
    /// writes pixels outside the film.
    pub fn create_block(&self, offset: UVec2, size: UVec2) -> ImageBlock {
        ImageBlock::with_clip(
            offset,
            size,
            &self.filter,
            [self.width as i64, self.height as i64],
        )
    }

    /// Number of non-finite samples dropped by the merged blocks.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// The sums of pixel (x, y). Panics outside the film.
    pub fn pixel(&self, x: u32, y: u32) -> &PixelAccum {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside film");
        &self.data[y as usize * self.width as usize + x as usize]
    }

    /// Resets all sums to zero.
    pub fn clear(&mut self) {
        self.data.fill(PixelAccum::default());
        self.dropped = 0;
    }

    /// Adds a block's sums (border included) into the film; parts outside the film are ignored.
    pub fn merge(&mut self, block: &ImageBlock) {
        let (origin, stride) = block.storage_rect();
        let x0 = origin[0].max(0);
        let x1 = (origin[0] + stride[0]).min(self.width as i64);
        let y0 = origin[1].max(0);
        let y1 = (origin[1] + stride[1]).min(self.height as i64);
        self.dropped += block.dropped();
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        let n = (x1 - x0) as usize;
        let src_all = block.pixels();
        for y in y0..y1 {
            let s = ((y - origin[1]) * stride[0] + (x0 - origin[0])) as usize;
            let d = (y as usize) * self.width as usize + x0 as usize;
            for (dst, src) in self.data[d..d + n].iter_mut().zip(&src_all[s..s + n]) {
                dst.add(src);
            }
        }
    }

    /// Adds another film's sums (e.g. another pass or machine). Errors if the sizes differ.
    pub fn accumulate(&mut self, other: &Film) -> Result<(), String> {
        if self.width != other.width || self.height != other.height {
            return Err(format!(
                "hdrfilm: cannot accumulate a {}x{} film into a {}x{} film",
                other.width, other.height, self.width, self.height
            ));
        }
        for (d, s) in self.data.iter_mut().zip(&other.data) {
            d.add(s);
        }
        self.dropped += other.dropped;
        Ok(())
    }

    /// The developed image: per pixel `Σw·L / Σw` (0 where `Σw = 0`), as f32 RGB.
    pub fn develop(&self) -> Image {
        let mut data = Vec::with_capacity(self.data.len() * 3);
        for p in &self.data {
            data.extend(p.mean().map(|v| v as f32));
        }
        Image { width: self.width, height: self.height, data }
    }

    /// A per-pixel, per-channel standard error estimate of the developed value.
    ///
    /// For a pixel with samples `Lₖ` and weights `wₖ` (W₁ = Σw, W₂ = Σw²), the developed value is
    /// the weighted mean `m = Σw·L / W₁`. Treating the weights as fixed and the `Lₖ` as i.i.d.
    /// with variance σ², `Var(m) = σ²·W₂/W₁²`. σ² is estimated by the weighted variance
    /// `v = Σw·L²/W₁ − m²` with the effective-sample-size correction `n_eff/(n_eff − 1)`,
    /// `n_eff = W₁²/W₂` (exact Bessel correction for equal weights). Hence
    ///
    /// `Var(m) ≈ (W₂/W₁²) · v · n_eff/(n_eff − 1) = v / (n_eff − 1)`,
    ///
    /// negative values (round-off) are clamped to 0 and the square root is returned. Pixels where
    /// it cannot be estimated (`Σw = 0` or `n_eff ≤ 1`, e.g. a single sample) report 0.
    pub fn develop_stderr(&self) -> Image {
        let mut data = Vec::with_capacity(self.data.len() * 3);
        for p in &self.data {
            if !(p.w > 0.0 && p.w2 > 0.0) {
                data.extend([0.0f32; 3]);
                continue;
            }
            let n_eff = p.w * p.w / p.w2;
            if n_eff <= 1.0 + 1e-9 {
                data.extend([0.0f32; 3]);
                continue;
            }
            for c in 0..3 {
                let m = p.wl[c] / p.w;
                let v = (p.wl2[c] / p.w - m * m).max(0.0);
                data.push((v / (n_eff - 1.0)).sqrt() as f32);
            }
        }
        Image { width: self.width, height: self.height, data }
    }
}
