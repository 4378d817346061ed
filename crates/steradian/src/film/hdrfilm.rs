//! # `hdrfilm` — high dynamic range film
//!
//! Mitsuba plugin `hdrfilm`: accumulates filtered radiance samples per pixel and develops them
//! into a linear, unclamped RGB image.
//!
//! | parameter          | type    | default      | meaning                                          |
//! |--------------------|---------|--------------|--------------------------------------------------|
//! | `width`            | integer | 768          | image width in pixels (1 ..= 32768)              |
//! | `height`           | integer | 576          | image height in pixels (1 ..= 32768)             |
//! | `pixel_format`     | string  | `"rgb"`      | `rgb`, `rgba`, `luminance`, `luminance_alpha`, `xyz`, `xyza`: the file's channels (`pixel_format.rs`) |
//! | `component_format` | string  | `"float16"`  | `float16`, `float32` or `uint32`: `steradian render` writes f32 for both float formats (half precision would only lose digits) and, for `uint32`, Mitsuba 3.9.1's integers (each value clamped to [0, 1] and scaled to 2³² − 1); developed images are always f32 |
//! | `sample_border`    | boolean | false        | also sample the pixels just outside the film (or crop window), [`SampleBorder`] |
//! | `rfilter`          | filter  | `gaussian`   | reconstruction filter (σ = 0.5 px, radius 2 px)  |
//!
//! | `crop_offset_x`, `crop_offset_y` | integer | 0 | the rendered window's top-left pixel in the full film |
//! | `crop_width`, `crop_height` | integer | `width`, `height` less the offset | the rendered window's size: the image written |
//!
//! **Crop window** (Mitsuba's): the camera frames the full `width` × `height` film (its field
//! of view and aspect ratio), and only the window is rendered and written, each pixel exactly
//! as in the full render; the film's own `width` and `height` are then the window's, and
//! [`FilmWindow`] maps its positions into the full frame.
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

use glam::{UVec2, Vec2};

use super::filter::ReconstructionFilter;
use super::image::Image;
use super::image_block::{ImageBlock, PixelAccum};
use super::pixel_format::PixelFormat;
use super::splat_block::SplatBlock;

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
    /// Unsigned 32-bit integers: Mitsuba 3.9.1's conversion, the value clamped to [0, 1] and
    /// multiplied by 2³² − 1 (in single precision, as Mitsuba computes it), so that radiance
    /// above 1 W/(m²·sr) saturates.
    UInt32,
}

impl ComponentFormat {
    /// Parses Mitsuba's `component_format` string.
    pub fn parse(s: &str) -> Result<ComponentFormat, String> {
        match s {
            "float16" => Ok(ComponentFormat::Float16),
            "float32" => Ok(ComponentFormat::Float32),
            "uint32" => Ok(ComponentFormat::UInt32),
            other => Err(format!(
                "unsupported component_format \"{other}\" (expected \"float16\", \"float32\" or \
                 \"uint32\")"
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
    /// Whether camera renders also sample a margin around the film (default: no).
    pub sample_border: SampleBorder,
    /// The channels of the files the render writes (default RGB).
    pub pixel_format: PixelFormat,
    /// Where the film lies in the full frame the camera sees (a crop window), or the whole
    /// frame.
    window: FilmWindow,
    data: Vec<PixelAccum>,
    /// AOV layers: names and Σw·a per pixel (pixel-major, then layer), see
    /// [`with_aov_layers`](Film::with_aov_layers).
    aov_names: Vec<AovLayer>,
    aov: Vec<[f64; 3]>,
    dropped: u64,
}

/// An extra image of one to three channels an integrator writes beside the radiance
/// (Mitsuba's AOVs): its EXR channels are `<name>.<channel>`; the film keeps three values per
/// layer and the unnamed ones stay 0.
#[derive(Clone, Debug, PartialEq)]
pub struct AovLayer {
    pub name: String,
    pub channels: Vec<&'static str>,
}

/// Which pixels a camera render samples (`sample_border`). Mitsuba 3 samples the film's
/// pixels only by default, so that a pixel within the filter's reach of the edge gathers less
/// weight than an inner one, from one side; with `sample_border` it also samples a margin of
/// [`ReconstructionFilter::border_size`] pixels (⌈radius − ½⌉: 2 for the default gaussian, 0
/// for `box`) around the film or its crop window, whose samples reach the edge pixels only, so
/// that every pixel gathers its filter's whole support. The margin's samples are taken as a
/// pixel's and splatted like them (an adaptive render gives them the nearest film pixel's
/// count and weight), and they count in the samples reported. Meters and `ptracer` (whose
/// light paths land wherever the camera sees them) ignore it, as Mitsuba's `ptracer` does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SampleBorder {
    /// The film's pixels only (Mitsuba's default).
    #[default]
    FilmOnly,
    /// The film's pixels and a margin of the filter's border size around them.
    WithMargin,
}

/// Where a film's pixels lie in the full frame its camera sees: the whole frame, or a crop
/// window of it (`crop_offset_x/y`, `crop_width/height`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilmWindow {
    /// The window's top-left corner in the full frame, pixels.
    offset: Vec2,
    /// The full frame's width and height, pixels.
    full: Vec2,
}

impl FilmWindow {
    /// The whole frame of a `width` × `height` film.
    pub fn whole(width: u32, height: u32) -> FilmWindow {
        FilmWindow { offset: Vec2::ZERO, full: Vec2::new(width as f32, height as f32) }
    }

    /// The fraction of the full frame (what cameras take, [0, 1]² over it) at film position
    /// `pos` (pixels of the window).
    #[inline]
    pub fn frame_uv(&self, pos: Vec2) -> Vec2 {
        (self.offset + pos) / self.full
    }

    /// The film position (pixels of the window) at fraction `uv` of the full frame: the
    /// inverse of [`frame_uv`](Self::frame_uv); outside the window for points it does not
    /// hold.
    #[inline]
    pub fn position(&self, uv: Vec2) -> Vec2 {
        uv * self.full - self.offset
    }

    /// The full frame's size, pixels.
    pub fn full_size(&self) -> UVec2 {
        self.full.as_uvec2()
    }
}

impl AovLayer {
    /// Its channels' names in a file or array: `<name>.<channel>`, or `<channel>` for a
    /// layer without a name (the alpha channel's `A`).
    pub fn channel_names(&self) -> Vec<String> {
        self.channels
            .iter()
            .map(
                |c| if self.name.is_empty() { c.to_string() } else { format!("{}.{c}", self.name) },
            )
            .collect()
    }

    /// The alpha channel of an `rgba` film (`pixel_format.rs`): the file's `A`, kept as the
    /// last AOV layer.
    pub fn alpha() -> AovLayer {
        AovLayer { name: String::new(), channels: vec!["A"] }
    }
}

impl Film {
    /// Pixels sampled beyond each edge of the film by camera renders ([`SampleBorder`]).
    pub fn sample_margin(&self) -> u32 {
        match self.sample_border {
            SampleBorder::FilmOnly => 0,
            SampleBorder::WithMargin => self.filter.border_size(),
        }
    }

    /// Whether the film keeps an alpha layer (its last, [`AovLayer::alpha`]).
    pub fn has_alpha_layer(&self) -> bool {
        self.aov_names.last() == Some(&AovLayer::alpha())
    }
}

impl Default for Film {
    /// Mitsuba's default `hdrfilm`: 768×576, gaussian filter.
    fn default() -> Self {
        Film::new(Film::DEFAULT_WIDTH, Film::DEFAULT_HEIGHT, ReconstructionFilter::default())
            .expect("default film size is valid")
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
            sample_border: SampleBorder::default(),
            pixel_format: PixelFormat::default(),
            window: FilmWindow::whole(width, height),
            data: vec![PixelAccum::default(); width as usize * height as usize],
            aov_names: Vec::new(),
            aov: Vec::new(),
            dropped: 0,
        })
    }

    /// The film with AOV layers (cleared), developed like the radiance: Σw·a/Σw with the
    /// weights of the film's filter.
    pub fn with_aov_layers(mut self, layers: Vec<AovLayer>) -> Self {
        self.aov = vec![[0.0; 3]; self.data.len() * layers.len()];
        self.aov_names = layers;
        self
    }

    /// The AOV layers' names.
    pub fn aov_layers(&self) -> &[AovLayer] {
        &self.aov_names
    }

    /// AOV layer `k` developed: per pixel Σw·a/Σw (0 where Σw = 0).
    pub fn develop_aov(&self, k: usize) -> Image {
        let n = self.aov_names.len();
        let mut data = Vec::with_capacity(self.data.len() * 3);
        for (i, p) in self.data.iter().enumerate() {
            let a = self.aov[i * n + k];
            data.extend(a.map(|v| if p.w != 0.0 { (v / p.w) as f32 } else { 0.0 }));
        }
        Image { width: self.width, height: self.height, data }
    }

    /// The film as the crop window at `offset` of a `full`-sized frame (Mitsuba's
    /// `crop_offset_x/y` with `width`/`height` the full frame); the film's own size is the
    /// window's. An error when the window leaves the frame.
    pub fn with_crop(mut self, offset: UVec2, full: UVec2) -> Result<Film, String> {
        let end = offset + self.size();
        if end.x > full.x || end.y > full.y {
            return Err(format!(
                "hdrfilm: the crop window ({}, {}) + {}×{} leaves the {}×{} film",
                offset.x, offset.y, self.width, self.height, full.x, full.y
            ));
        }
        self.window = FilmWindow { offset: offset.as_vec2(), full: full.as_vec2() };
        Ok(self)
    }

    /// Where the film lies in its camera's full frame (see [`FilmWindow`]).
    #[inline]
    pub fn window(&self) -> FilmWindow {
        self.window
    }

    /// Film size in pixels.
    pub fn size(&self) -> UVec2 {
        UVec2::new(self.width, self.height)
    }

    /// A block for the film pixels `offset .. offset + size`, using the film's filter; it never
    /// writes pixels outside the film.
    pub fn create_block(&self, offset: UVec2, size: UVec2) -> ImageBlock {
        ImageBlock::with_clip(offset, size, &self.filter, [self.width as i64, self.height as i64])
            .with_aov_layers(self.aov_names.len())
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

    /// The raw sums: per pixel (row-major) and, pixel-major then layer, the AOV layers' Σw·a.
    pub fn sums(&self) -> (&[PixelAccum], &[[f64; 3]]) {
        (&self.data, &self.aov)
    }

    /// The raw sums, writable (a checkpoint or a range read back), and the dropped count.
    pub fn sums_mut(&mut self) -> (&mut [PixelAccum], &mut [[f64; 3]], &mut u64) {
        (&mut self.data, &mut self.aov, &mut self.dropped)
    }

    /// Resets all sums to zero.
    pub fn clear(&mut self) {
        self.data.fill(PixelAccum::default());
        self.aov.fill([0.0; 3]);
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
        let layers = self.aov_names.len();
        debug_assert_eq!(block.aov_layers(), layers, "the block's AOV layers are the film's");
        for y in y0..y1 {
            let s = ((y - origin[1]) * stride[0] + (x0 - origin[0])) as usize;
            let d = (y as usize) * self.width as usize + x0 as usize;
            for (dst, src) in self.data[d..d + n].iter_mut().zip(&src_all[s..s + n]) {
                dst.add(src);
            }
            if layers > 0 && block.aov_layers() == layers {
                let (src, dst) = (&block.aovs()[s * layers..(s + n) * layers], &mut self.aov);
                for (a, b) in dst[d * layers..(d + n) * layers].iter_mut().zip(src) {
                    for c in 0..3 {
                        a[c] += b[c];
                    }
                }
            }
        }
    }

    /// Adds one pass of particle tracing: each pixel's splat sum in `block` as one sample of
    /// weight 1, so the developed image is the mean over passes
    /// and the standard error is that of the passes, which are independent.
    pub fn add_pass(&mut self, block: &SplatBlock) {
        debug_assert_eq!(block.sums().len(), self.data.len());
        for (p, v) in self.data.iter_mut().zip(block.sums()) {
            p.add_sample(1.0, *v);
        }
        self.dropped += block.dropped();
    }

    /// Adds another film's sums (e.g. another pass or machine). Errors if the sizes differ.
    pub fn accumulate(&mut self, other: &Film) -> Result<(), String> {
        if self.width != other.width || self.height != other.height {
            return Err(format!(
                "hdrfilm: cannot accumulate a {}x{} film into a {}x{} film",
                other.width, other.height, self.width, self.height
            ));
        }
        if self.aov_names != other.aov_names {
            return Err("hdrfilm: cannot accumulate films with different AOV layers".into());
        }
        for (d, s) in self.data.iter_mut().zip(&other.data) {
            d.add(s);
        }
        for (a, b) in self.aov.iter_mut().zip(&other.aov) {
            for c in 0..3 {
                a[c] += b[c];
            }
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
            let var = p.mean_variance().unwrap_or([0.0; 3]);
            data.extend(var.map(|v| v.sqrt() as f32));
        }
        Image { width: self.width, height: self.height, data }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::filter::{BoxFilter, GaussianFilter, TentFilter};
    use crate::sampling::Pcg32;
    use crate::Spectrum;
    use glam::Vec2;

    fn filters() -> [ReconstructionFilter; 4] {
        [
            BoxFilter::new().into(),
            TentFilter::default().into(),
            TentFilter::new(1.7).unwrap().into(),
            GaussianFilter::default().into(),
        ]
    }

    fn random_samples(w: u32, h: u32, n: usize, seed: u64) -> Vec<(Vec2, Spectrum)> {
        let mut rng = Pcg32::new(seed, 3);
        (0..n)
            .map(|_| {
                let p = Vec2::new(rng.next_f32() * w as f32, rng.next_f32() * h as f32);
                let v = Spectrum::new(rng.next_f32(), rng.next_f32() * 5.0, rng.next_f32() * 0.1);
                (p, v)
            })
            .collect()
    }

    /// Renders like a tiled renderer: each sample goes to the tile whose interior holds it.
    fn render_tiled(film: &mut Film, samples: &[(Vec2, Spectrum)], tile: u32) {
        let (tw, th) = (film.width.div_ceil(tile), film.height.div_ceil(tile));
        for ty in 0..th {
            for tx in 0..tw {
                let off = UVec2::new(tx * tile, ty * tile);
                let size = UVec2::new(tile.min(film.width - off.x), tile.min(film.height - off.y));
                let mut b = film.create_block(off, size);
                for &(p, v) in samples {
                    let (ix, iy) = (p.x.floor() as u32, p.y.floor() as u32);
                    if ix / tile == tx && iy / tile == ty {
                        b.put(p, v);
                    }
                }
                film.merge(&b);
            }
        }
    }

    fn assert_films_close(a: &Film, b: &Film) {
        for y in 0..a.height {
            for x in 0..a.width {
                let (p, q) = (a.pixel(x, y), b.pixel(x, y));
                let close =
                    |u: f64, v: f64| (u - v).abs() <= 1e-12 * u.abs().max(v.abs()).max(1e-300);
                assert!(close(p.w, q.w) && close(p.w2, q.w2), "({x},{y}) {p:?} vs {q:?}");
                for c in 0..3 {
                    assert!(close(p.wl[c], q.wl[c]) && close(p.wl2[c], q.wl2[c]), "({x},{y})");
                }
            }
        }
    }

    #[test]
    fn film_size_validation() {
        let f = ReconstructionFilter::default();
        assert!(Film::new(0, 10, f).is_err());
        assert!(Film::new(10, 0, f).is_err());
        assert!(Film::new(MAX_FILM_SIZE + 1, 2, f).unwrap_err().contains("too large"));
        assert!(Film::new(1, 1, f).is_ok());
        let d = Film::default();
        assert_eq!((d.width, d.height), (768, 576));
        assert!(matches!(d.filter, ReconstructionFilter::Gaussian(g) if g.stddev() == 0.5));
        assert_eq!(d.component_format, ComponentFormat::Float16);
        assert_eq!(d.sample_border, SampleBorder::FilmOnly);
        assert_eq!(ComponentFormat::parse("float32"), Ok(ComponentFormat::Float32));
        assert!(ComponentFormat::parse("uint8").is_err());
    }

    #[test]
    fn tiled_merge_equals_single_block() {
        for f in filters() {
            let samples = random_samples(23, 17, 4000, 11);
            let mut single = Film::new(23, 17, f).unwrap();
            let mut b = single.create_block(UVec2::ZERO, single.size());
            for &(p, v) in &samples {
                b.put(p, v);
            }
            single.merge(&b);
            // Blocks made without the film's clip keep pixels beyond the edges in their
            // border; merge must clip them.
            let mut unclipped = Film::new(23, 17, f).unwrap();
            let mut b2 = ImageBlock::new(UVec2::ZERO, unclipped.size(), &f);
            for &(p, v) in &samples {
                b2.put(p, v);
            }
            unclipped.merge(&b2);
            for tile in [8, 5, 1] {
                let mut tiled = Film::new(23, 17, f).unwrap();
                render_tiled(&mut tiled, &samples, tile);
                assert_films_close(&tiled, &single);
            }
            assert_films_close(&unclipped, &single);
            // Total weight equals the sum of the in-film filter weights, computed directly.
            let r = f.radius();
            let mut expect_w = 0.0f64;
            for &(p, _) in &samples {
                for y in 0..17 {
                    for x in 0..23 {
                        let (dx, dy) = (x as f32 + 0.5 - p.x, y as f32 + 0.5 - p.y);
                        if f.is_box() {
                            if x == p.x.floor() as i32 && y == p.y.floor() as i32 {
                                expect_w += 1.0;
                            }
                        } else if dx.abs() < r && dy.abs() < r {
                            expect_w += f.eval(dy) as f64 * f.eval(dx) as f64;
                        }
                    }
                }
            }
            let total: f64 = single.data.iter().map(|p| p.w).sum();
            assert!((total - expect_w).abs() <= 1e-9 * expect_w, "{}", f.plugin_name());
        }
    }

    #[test]
    fn constant_radiance_develops_exactly() {
        let c = Spectrum::new(0.3, 1.7, 42.0);
        for f in filters() {
            let mut film = Film::new(9, 7, f).unwrap();
            let mut rng = Pcg32::new(5, 9);
            let mut b = film.create_block(UVec2::ZERO, film.size());
            for _ in 0..2000 {
                b.put(Vec2::new(rng.next_f32() * 9.0, rng.next_f32() * 7.0), c);
            }
            film.merge(&b);
            let img = film.develop();
            for y in 0..7 {
                for x in 0..9 {
                    assert!(film.pixel(x, y).w > 0.0, "pixel ({x},{y}) got no weight");
                    let v = img.get(x, y);
                    for k in 0..3 {
                        assert!(
                            (v[k] - c[k]).abs() <= 1e-6 * c[k],
                            "{} ({x},{y}) {v}",
                            f.plugin_name()
                        );
                    }
                }
            }
        }
        // Pixels without weight develop to 0.
        let film = Film::new(3, 2, ReconstructionFilter::default()).unwrap();
        assert!(film.develop().data.iter().all(|&v| v == 0.0));
    }

    #[test]
    fn f64_accumulation_has_no_drift() {
        const N: usize = 4_000_000;
        let mut film = Film::new(1, 1, BoxFilter::new().into()).unwrap();
        let mut b = film.create_block(UVec2::ZERO, UVec2::ONE);
        let mut rng = Pcg32::new(17, 1);
        // Every f32 in [0.5, 2) is an integer multiple of 2^-24, so the exact sum fits in u64.
        let mut exact: u64 = 0;
        let mut naive_f32 = 0.0f32;
        for _ in 0..N {
            let v = 1.1 + 1e-3 * (rng.next_f32() - 0.5);
            exact += (v as f64 * 16_777_216.0) as u64;
            naive_f32 += v;
            b.put(Vec2::new(0.25, 0.75), Spectrum::splat(v));
        }
        film.merge(&b);
        let exact_mean = exact as f64 / 16_777_216.0 / N as f64;
        let got = film.develop().get(0, 0);
        for k in 0..3 {
            assert!(
                (got[k] as f64 - exact_mean).abs() <= 0.6 * f32::EPSILON as f64 * exact_mean,
                "{} vs {exact_mean}",
                got[k]
            );
        }
        // The f32 running sum that this guards against is visibly wrong.
        let naive_mean = naive_f32 as f64 / N as f64;
        assert!((naive_mean - exact_mean).abs() > 1e-3 * exact_mean, "{naive_mean}");
    }

    /// Mean and standard deviation of U[0,1): 1/2 and 1/√12; its kurtosis is 9/5.
    const SIGMA_U: f64 = 0.288_675_134_594_812_9;
    const KURT_U: f64 = 1.8;

    #[test]
    fn stderr_of_box_pixels_matches_sigma_over_sqrt_n() {
        const N: usize = 10_000;
        let (w, h) = (4u32, 4u32);
        let mut film = Film::new(w, h, BoxFilter::new().into()).unwrap();
        let mut b = film.create_block(UVec2::ZERO, film.size());
        let mut rng = Pcg32::new(1234, 5);
        for y in 0..h {
            for x in 0..w {
                for _ in 0..N {
                    let p = Vec2::new(x as f32 + rng.next_f32(), y as f32 + rng.next_f32());
                    b.put(p, Spectrum::new(rng.next_f32(), rng.next_f32(), rng.next_f32()));
                }
            }
        }
        film.merge(&b);
        let se = film.develop_stderr();
        let expect = SIGMA_U / (N as f64).sqrt();
        // Relative s.d. of a sample standard deviation: ≈ ½·√((κ − 1)/n) (delta method),
        // with the f32 image rounding far below it.
        let rel_sd = 0.5 * ((KURT_U - 1.0) / N as f64).sqrt();
        let mut sum_rel = 0.0;
        for &v in &se.data {
            let rel = v as f64 / expect - 1.0;
            assert!(rel.abs() < 5.0 * rel_sd, "stderr {v} vs {expect}");
            sum_rel += rel;
        }
        let m = se.data.len() as f64;
        assert!((sum_rel / m).abs() < 5.0 * rel_sd / m.sqrt(), "mean bias {}", sum_rel / m);
    }

    #[test]
    fn stderr_of_weighted_pixels() {
        // Gaussian splatting: values i.i.d. U[0,1) independent of position; given the weights,
        // Var(weighted mean) = σ²·W₂/W₁².
        let mut film = Film::new(6, 6, GaussianFilter::default().into()).unwrap();
        let mut b = film.create_block(UVec2::ZERO, film.size());
        let mut rng = Pcg32::new(99, 2);
        for _ in 0..200_000 {
            let p = Vec2::new(rng.next_f32() * 6.0, rng.next_f32() * 6.0);
            b.put(p, Spectrum::new(rng.next_f32(), rng.next_f32(), rng.next_f32()));
        }
        film.merge(&b);
        let se = film.develop_stderr();
        for y in 0..6 {
            for x in 0..6 {
                let p = film.pixel(x, y);
                let n_eff = p.w * p.w / p.w2;
                let expect = SIGMA_U * p.w2.sqrt() / p.w;
                let rel_sd = 0.5 * ((KURT_U - 1.0) / n_eff).sqrt();
                let v = se.get(x, y);
                for k in 0..3 {
                    let rel = v[k] as f64 / expect - 1.0;
                    assert!(rel.abs() < 6.0 * rel_sd, "({x},{y}) {} vs {expect}", v[k]);
                }
            }
        }
    }

    #[test]
    fn stderr_degenerate_pixels_are_zero() {
        let mut film = Film::new(2, 1, BoxFilter::new().into()).unwrap();
        let mut b = film.create_block(UVec2::ZERO, film.size());
        b.put(Vec2::new(0.5, 0.5), Spectrum::new(3.0, 1.0, 2.0));
        film.merge(&b);
        let se = film.develop_stderr();
        assert_eq!(se.get(0, 0), Spectrum::ZERO); // one sample: unknown, reported 0
        assert_eq!(se.get(1, 0), Spectrum::ZERO); // no sample
                                                  // Identical samples: zero variance (never negative or NaN from round-off).
        let mut b = film.create_block(UVec2::ZERO, film.size());
        for _ in 0..1000 {
            b.put(Vec2::new(1.5, 0.5), Spectrum::splat(0.1));
        }
        film.merge(&b);
        let v = film.develop_stderr().get(1, 0);
        assert!(v.is_finite() && v.cmpge(Spectrum::ZERO).all() && v.max_element() < 1e-8);
    }

    #[test]
    fn accumulate_and_clear() {
        let f = ReconstructionFilter::default();
        let samples = random_samples(10, 8, 3000, 21);
        let mut all = Film::new(10, 8, f).unwrap();
        render_tiled(&mut all, &samples, 4);
        let mut a = Film::new(10, 8, f).unwrap();
        let mut b = Film::new(10, 8, f).unwrap();
        render_tiled(&mut a, &samples[..1000], 4);
        render_tiled(&mut b, &samples[1000..], 3);
        a.accumulate(&b).unwrap();
        assert_films_close(&a, &all);
        assert!(a.accumulate(&Film::new(10, 9, f).unwrap()).is_err());
        a.clear();
        assert!(a.data.iter().all(|p| *p == PixelAccum::default()));
    }

    #[test]
    fn dropped_samples_are_counted_not_merged() {
        let mut film = Film::new(4, 4, ReconstructionFilter::default()).unwrap();
        let mut b = film.create_block(UVec2::ZERO, film.size());
        b.put(Vec2::new(1.0, 1.0), Spectrum::new(f32::NAN, 0.0, 0.0));
        b.put(Vec2::new(1.0, 1.0), Spectrum::new(0.0, f32::NEG_INFINITY, 0.0));
        film.merge(&b);
        assert_eq!(film.dropped(), 2);
        assert!(film.develop().data.iter().all(|v| *v == 0.0));
    }
}
