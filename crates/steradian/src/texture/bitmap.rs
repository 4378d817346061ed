//! `bitmap`: a texture read from an image file.
//!
//! | parameter     | type      | default    | meaning |
//! |---------------|-----------|------------|---------|
//! | `filename`    | string    | (required) | PNG, JPEG or OpenEXR file (relative to the scene file) |
//! | `filter_type` | string    | `bilinear` | `bilinear` interpolation of the four nearest texels, or `nearest` texel |
//! | `wrap_mode`   | string    | `repeat`   | outside [0, 1]²: `repeat` (tile), `mirror` (reflect at the edges), `clamp` (edge texels) |
//! | `raw`         | boolean   | false      | keep the stored values; otherwise 8/16-bit (PNG, JPEG) values are sRGB-decoded to linear |
//! | `to_uv`       | transform | identity   | applied to (u, v) before the lookup; of a 4×4 matrix the z row and column are ignored |
//!
//! As in Mitsuba 3, (u, v) = (0, 0) is the top-left corner of the picture: u runs along a row,
//! v down the rows (row 0 is the first row of the file; meshes flip v on load). Texel (i, j)
//! covers u ∈ [i/w, (i+1)/w); bilinear lookups interpolate between texel centres at
//! (u·w − ½, v·h − ½). Grey images give grey colours; scalar parameters (`eval_1`: alpha,
//! opacity, blend weight, bump height) read the luminance Y = 0.212671 R + 0.715160 G +
//! 0.072169 B of RGB images. The alpha channel is ignored (use a `mask` with its own opacity
//! texture). Mitsuba stores 8/16-bit textures in half precision; steradian keeps f32 (values
//! differ by < 0.05 %).

use std::fmt;
use std::sync::Arc;

use glam::{Mat2, Vec2};

use super::image_file::LoadedImage;
use crate::spectrum::{luminance, LUMINANCE_WEIGHTS};
use crate::Spectrum;

/// How texels are combined (`filter_type`; the default is Mitsuba's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FilterType {
    #[default]
    Bilinear,
    Nearest,
}

/// What lookups outside [0, 1]² see (`wrap_mode`; the default is Mitsuba's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WrapMode {
    #[default]
    Repeat,
    Mirror,
    Clamp,
}

/// An affine map of texture coordinates, uv' = m·uv + t (Mitsuba's `to_uv`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    pub m: Mat2,
    pub t: Vec2,
}

impl UvTransform {
    pub const IDENTITY: UvTransform = UvTransform { m: Mat2::IDENTITY, t: Vec2::ZERO };

    /// The 2-D part of a 4×4 transform: rows/columns x and y, translation from column w.
    pub fn from_mat4(m: &glam::Mat4) -> Self {
        UvTransform {
            m: Mat2::from_cols(
                Vec2::new(m.x_axis.x, m.x_axis.y),
                Vec2::new(m.y_axis.x, m.y_axis.y),
            ),
            t: Vec2::new(m.w_axis.x, m.w_axis.y),
        }
    }

    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.m * uv + self.t
    }
}

/// The sRGB transfer function inverted: encoded value in [0, 1] → linear.
#[inline]
pub fn srgb_to_linear(x: f32) -> f32 {
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

#[derive(Clone, PartialEq)]
pub struct Bitmap {
    /// The file name, for messages.
    pub name: String,
    width: usize,
    height: usize,
    /// 1 or 3.
    channels: usize,
    /// Linear values, row-major, row 0 at v = 0.
    data: Arc<[f32]>,
    pub filter: FilterType,
    pub wrap: WrapMode,
    pub to_uv: UvTransform,
    mean: Spectrum,
    max: f32,
}

impl fmt::Debug for Bitmap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Bitmap")
            .field("name", &self.name)
            .field("resolution", &(self.width, self.height, self.channels))
            .field("filter", &self.filter)
            .field("wrap", &self.wrap)
            .field("to_uv", &self.to_uv)
            .finish()
    }
}

impl Bitmap {
    /// Default `raw` (Mitsuba's): sRGB-encoded images are decoded to linear values.
    pub const DEFAULT_RAW: bool = false;

    /// A texture from decoded pixels; `raw` keeps sRGB-encoded values as they are.
    pub fn new(
        name: &str,
        image: LoadedImage,
        raw: bool,
        filter: FilterType,
        wrap: WrapMode,
        to_uv: UvTransform,
    ) -> Result<Bitmap, String> {
        let LoadedImage { width, height, channels, mut data, format } = image;
        if width == 0
            || height == 0
            || !(channels == 1 || channels == 3)
            || data.len() != width * height * channels
        {
            return Err(format!("image \"{name}\" has no pixels or an unsupported layout"));
        }
        if format.is_srgb() && !raw {
            for v in data.iter_mut() {
                *v = srgb_to_linear(*v);
            }
        }
        if let Some(bad) = data.iter().find(|v| !v.is_finite()) {
            return Err(format!("image \"{name}\" holds a non-finite value ({bad})"));
        }
        let n = (width * height) as f64;
        let mut sum = [0f64; 3];
        for px in data.chunks_exact(channels) {
            for c in 0..3 {
                sum[c] += px[c.min(channels - 1)] as f64;
            }
        }
        let mean = Spectrum::new((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32);
        let max = data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        Ok(Bitmap {
            name: name.to_string(),
            width,
            height,
            channels,
            data: data.into(),
            filter,
            wrap,
            to_uv,
            mean,
            max,
        })
    }

    /// (width, height) in texels.
    pub fn resolution(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Maps a texel index to [0, n) by the wrap mode.
    #[inline]
    fn wrap_index(&self, i: i64, n: usize) -> usize {
        let n = n as i64;
        (match self.wrap {
            WrapMode::Repeat => i.rem_euclid(n),
            WrapMode::Clamp => i.clamp(0, n - 1),
            WrapMode::Mirror => {
                let k = i.rem_euclid(2 * n);
                if k >= n {
                    2 * n - 1 - k
                } else {
                    k
                }
            }
        }) as usize
    }

    /// Texel (x, y) after wrapping, as a colour.
    #[inline]
    fn texel(&self, x: i64, y: i64) -> Spectrum {
        let (x, y) = (self.wrap_index(x, self.width), self.wrap_index(y, self.height));
        let i = (y * self.width + x) * self.channels;
        if self.channels == 1 {
            Spectrum::splat(self.data[i])
        } else {
            Spectrum::new(self.data[i], self.data[i + 1], self.data[i + 2])
        }
    }

    /// The four texels around a bilinear lookup at `uv'` and the weights (fx, fy) of the
    /// second column and row.
    #[inline]
    fn bilinear_texels(&self, uv: Vec2) -> ([Spectrum; 4], Vec2) {
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (xi, yi) = (x0 as i64, y0 as i64);
        let t = [
            self.texel(xi, yi),
            self.texel(xi + 1, yi),
            self.texel(xi, yi + 1),
            self.texel(xi + 1, yi + 1),
        ];
        (t, Vec2::new(x - x0, y - y0))
    }

    /// The colour at surface coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Spectrum {
        let uv = self.to_uv.apply(uv);
        match self.filter {
            FilterType::Nearest => self.texel(
                (uv.x * self.width as f32).floor() as i64,
                (uv.y * self.height as f32).floor() as i64,
            ),
            FilterType::Bilinear => {
                let ([f00, f10, f01, f11], w) = self.bilinear_texels(uv);
                let a = f00 * (1.0 - w.x) + f10 * w.x;
                let b = f01 * (1.0 - w.x) + f11 * w.x;
                a * (1.0 - w.y) + b * w.y
            }
        }
    }

    /// The scalar value: the grey level, or the luminance of a colour.
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        let v = self.eval(uv);
        if self.channels == 1 {
            v.x
        } else {
            luminance(v)
        }
    }

    /// ∇(u, v) of [`Bitmap::eval_1`]: the derivative of the bilinear interpolant (per unit of
    /// u, v, through `to_uv` by the chain rule); 0 for nearest lookups, which are piecewise
    /// constant.
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        if self.filter == FilterType::Nearest {
            return Vec2::ZERO;
        }
        let uvt = self.to_uv.apply(uv);
        let (t, w) = self.bilinear_texels(uvt);
        let weights = if self.channels == 1 { Spectrum::X } else { LUMINANCE_WEIGHTS };
        let [f00, f10, f01, f11] = t.map(|c| c.dot(weights));
        // ∂f/∂x, ∂f/∂y in texels, then per unit of the transformed coordinates
        let dfdx = (1.0 - w.y) * (f10 - f00) + w.y * (f11 - f01);
        let dfdy = (1.0 - w.x) * (f01 - f00) + w.x * (f11 - f10);
        let d = Vec2::new(dfdx * self.width as f32, dfdy * self.height as f32);
        self.to_uv.m.transpose() * d
    }

    pub fn max_value(&self) -> f32 {
        self.max
    }

    pub fn mean(&self) -> Spectrum {
        self.mean
    }
}

#[cfg(test)]
mod tests {
    use super::super::ImageFormat;
    use super::*;

    /// A w×h single-row-pattern image from values (grey).
    fn grey(w: usize, h: usize, data: Vec<f32>, filter: FilterType, wrap: WrapMode) -> Bitmap {
        let img = LoadedImage { width: w, height: h, channels: 1, data, format: ImageFormat::Exr };
        Bitmap::new("t", img, false, filter, wrap, UvTransform::IDENTITY).unwrap()
    }

    #[test]
    fn orientation_top_left_is_uv_origin() {
        // rows: red green / blue white (row 0 at the top): Mitsuba gives red at (0.1, 0.1),
        // green at (0.9, 0.1), blue at (0.1, 0.9)
        let data = vec![1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.];
        let img = LoadedImage { width: 2, height: 2, channels: 3, data, format: ImageFormat::Exr };
        let b = Bitmap::new(
            "t",
            img,
            false,
            FilterType::Nearest,
            WrapMode::Repeat,
            UvTransform::IDENTITY,
        )
        .unwrap();
        assert_eq!(b.eval(Vec2::new(0.1, 0.1)), Spectrum::X);
        assert_eq!(b.eval(Vec2::new(0.9, 0.1)), Spectrum::Y);
        assert_eq!(b.eval(Vec2::new(0.1, 0.9)), Spectrum::Z);
        let bl = Bitmap { filter: FilterType::Bilinear, ..b.clone() };
        assert!((bl.eval(Vec2::splat(0.5)) - Spectrum::splat(0.5)).abs().max_element() < 1e-6);
        // Mitsuba 3.9.1: eval_1 = 0.5 and eval_1_grad = (1.43032, 0.144338) at the centre
        assert!((bl.eval_1(Vec2::splat(0.5)) - 0.5).abs() < 1e-6);
        let g = bl.eval_1_grad(Vec2::splat(0.5));
        assert!((g - Vec2::new(1.43032, 0.144338)).abs().max_element() < 1e-4, "{g}");
        // to_uv: a translation by 0.5 in u moves green to (0.1, 0.1)
        let t = Bitmap { to_uv: UvTransform { m: Mat2::IDENTITY, t: Vec2::new(0.5, 0.0) }, ..b };
        assert_eq!(t.eval(Vec2::new(0.1, 0.1)), Spectrum::Y);
    }

    #[test]
    fn wrap_modes_match_mitsuba() {
        // a 4-texel ramp 0, 1, 2, 3; expected values printed by Mitsuba 3.9.1 (scalar_rgb)
        let us = [-0.3, 0.05, 0.95, 1.1, 1.3, 2.6];
        let cases = [
            (WrapMode::Repeat, FilterType::Nearest, [2.0, 0.0, 3.0, 0.0, 1.0, 2.0]),
            (WrapMode::Repeat, FilterType::Bilinear, [2.3, 0.9, 2.1, 0.3, 0.7, 1.9]),
            (WrapMode::Mirror, FilterType::Nearest, [1.0, 0.0, 3.0, 3.0, 2.0, 2.0]),
            (WrapMode::Mirror, FilterType::Bilinear, [0.7, 0.0, 3.0, 3.0, 2.3, 1.9]),
            (WrapMode::Clamp, FilterType::Nearest, [0.0, 0.0, 3.0, 3.0, 3.0, 3.0]),
            (WrapMode::Clamp, FilterType::Bilinear, [0.0, 0.0, 3.0, 3.0, 3.0, 3.0]),
        ];
        for (wrap, filter, expect) in cases {
            let b = grey(4, 2, vec![0., 1., 2., 3., 0., 1., 2., 3.], filter, wrap);
            for (u, e) in us.iter().zip(expect) {
                let v = b.eval_1(Vec2::new(*u, 0.5));
                assert!((v - e).abs() < 1e-4, "{wrap:?} {filter:?} u={u}: {v} vs {e}");
            }
        }
    }

    #[test]
    fn gradient_matches_finite_differences() {
        let data: Vec<f32> = (0..35).map(|i| ((i * 7919) % 13) as f32 / 13.0).collect();
        let mut b = grey(7, 5, data, FilterType::Bilinear, WrapMode::Repeat);
        b.to_uv = UvTransform {
            m: Mat2::from_cols(Vec2::new(1.5, 0.3), Vec2::new(-0.4, 2.0)),
            t: Vec2::new(0.2, -0.1),
        };
        let h = 1e-3;
        for uv in [Vec2::new(0.31, 0.47), Vec2::new(0.77, 0.12), Vec2::new(-1.3, 2.2)] {
            let g = b.eval_1_grad(uv);
            let fd = Vec2::new(
                (b.eval_1(uv + Vec2::new(h, 0.0)) - b.eval_1(uv - Vec2::new(h, 0.0))) / (2.0 * h),
                (b.eval_1(uv + Vec2::new(0.0, h)) - b.eval_1(uv - Vec2::new(0.0, h))) / (2.0 * h),
            );
            assert!(
                (g - fd).abs().max_element() < 2e-2 * (1.0 + fd.abs().max_element()),
                "{uv}: {g} vs {fd}"
            );
        }
    }

    #[test]
    fn srgb_decoding_unless_raw() {
        let img = LoadedImage {
            width: 1,
            height: 1,
            channels: 1,
            data: vec![200.0 / 255.0],
            format: ImageFormat::Png,
        };
        let b = Bitmap::new(
            "t",
            img.clone(),
            false,
            FilterType::Nearest,
            WrapMode::Repeat,
            UvTransform::IDENTITY,
        )
        .unwrap();
        // Mitsuba 3.9.1 gives 0.577581 for an sRGB 200/255
        assert!((b.eval_1(Vec2::ZERO) - 0.577581).abs() < 1e-5);
        let raw = Bitmap::new(
            "t",
            img,
            true,
            FilterType::Nearest,
            WrapMode::Repeat,
            UvTransform::IDENTITY,
        )
        .unwrap();
        assert!((raw.eval_1(Vec2::ZERO) - 200.0 / 255.0).abs() < 1e-7);
    }
}
