//! `envmap`: a sky read from a latitude-longitude image, surrounding the scene at infinity.
//!
//! | parameter          | type      | default    | meaning |
//! |--------------------|-----------|------------|---------|
//! | `filename`         | string    | (required) | OpenEXR, Radiance RGBE `.hdr`, PNG or JPEG image, at least 2×3 pixels (relative to the scene file) |
//! | `scale`            | float     | 1          | factor on every pixel (≥ 0, finite) |
//! | `to_world`         | transform | identity   | emitter-to-world rotation (its translation is ignored) |
//! | `mis_compensation` | boolean   | true under `path`, else false | sample by max(Y − Ȳ, 0) instead of Y (Karlík et al. 2019), see below |
//!
//! **Units.** A pixel holds radiance in W/(m²·sr), multiplied by `scale`. EXR and RGBE values
//! are used as stored (RGBE's `EXPOSURE` header is ignored, as Mitsuba 3 does); 8- and 16-bit
//! PNG/JPEG values are sRGB-decoded to linear first, as Mitsuba does for every integer image.
//! A grey image is grey radiance. The alpha channel is dropped.
//!
//! **Orientation** (Mitsuba 3's convention, checked against Mitsuba 3.9.1's `eval`). In the
//! emitter's local frame +Y is up. The radiance arriving from direction d = (x, y, z) (pointing
//! from the scene towards the sky) is looked up at
//!   u = atan2(x, −z) / 2π (wrapped to [0, 1)),   v = arccos(y) / π,
//! where u runs along a row (left to right) and v down the rows: the top row is the zenith
//! (+Y), the bottom row the nadir, the left and right edges look towards −Z, the column at
//! u = ¼ towards +X, the middle column towards +Z and u = ¾ towards −X. World directions
//! reach the local frame through the inverse of `to_world`.
//!
//! **Lookup.** As Mitsuba's: columns are periodic (the first repeats after the last) and
//! centred at u = (i + ½)/w, rows sit at v = j/(h − 1) (row 0 exactly at the zenith, the last
//! row exactly at the nadir); the radiance is the bilinear interpolation of the four pixels
//! around (u·w − ½, v·(h − 1)).
//!
//! **Sampling.** The bilinear lookup splits the sphere into w × (h − 1) cells of the (u, v)
//! square, each between four pixels. A cell is chosen with probability proportional to the
//! mean luminance Y of its four corner pixels times its solid angle (2π/w)·(cos θ_top −
//! cos θ_bottom): the sin θ Jacobian of the lat-long map enters here. Within the cell (u, v)
//! follows the bilinear interpolation of the corners' Y (a linear density in v, then one in u:
//! `warp::square_to_bilinear`), the shape of the radiance itself, so the weight L/p of a
//! sample barely varies inside a cell. The density of the direction is exactly
//!   p(ω) = p(u, v) / (2π² sin θ)   (1/sr),
//! and `pdf_direction` returns that same value for any direction, which MIS needs.
//! `flux` (for `light_selection` by power) uses ∫ L dω over the sphere from the same cells.
//! Uniform positions inside the cells had left L/p anywhere between 0 and 4 times its mean
//! across the edge of a sun a few pixels wide: on `benches/envmap/glossy_spheres.xml` the
//! bilinear positions cut the error at equal samples by 21 % (relative MSE 1.01e-4 → 7.97e-5
//! at 256 spp, 8 branches, two seeds; 2026-12-06, Intel Xeon).
//!
//! **MIS compensation.** With `mis_compensation`, cells are chosen by max(Y − Ȳ, 0), Ȳ the
//! mean pixel luminance, so that the darker half of the sky is left to BSDF sampling (off
//! when the map is nearly uniform: Ȳ − min Y ≤ 1 % of Ȳ, as in Mitsuba). Directions in the
//! dark part then have zero light-sampling density: every estimator steradian combines with
//! an envmap (path, direct with BSDF samples, the irradiance meter) also samples directions
//! some other way, so nothing is lost; `direct` with `bsdf_samples` = 0 misses that light,
//! as Mitsuba's does. Where the scene leaves it unset, it is on under `path` (whose every
//! light sample is weighed by MIS against a BSDF sample, also at the last vertex when an
//! environment lights the scene) and off under the other integrators, as in Mitsuba (pbrt-v4
//! makes the same split). Measured on `benches/envmap/glossy_spheres.xml` (2026-12-07, AMD
//! EPYC, 2 cores, 64 spp, 4 pairs of seeds): e × t 0.87× at 16 branches, 0.94× at 8.
//!
//! **Where steradian differs from Mitsuba on purpose.**
//! - `mis_compensation` defaults to true under `path` (Mitsuba: false everywhere); it moves
//!   samples, never the image.
//! - Sampling: Mitsuba warps by a hierarchical bilinear density over the pixel grid
//!   (`Hierarchical2D`, sin θ taken per pixel); steradian chooses a cell by a tabulated CDF
//!   (with a guide table, about one step per sample) and is bilinear inside it, sin θ taken
//!   per cell. Both are exact for their own density, so only the noise differs.
//! - `to_world` must be a rotation (or a reflection): Mitsuba evaluates the transformed,
//!   un-normalised direction, which for a scale or shear is not a lat-long lookup at all and
//!   whose sampling density would need a Jacobian it does not apply; steradian refuses them.
//! - Negative or non-finite pixels are errors (Mitsuba renders them).
//! - `bitmap` and `data` (a Python `Bitmap` object, a tensor) cannot come from a scene file;
//!   Mitsuba's envmap has no `filter_type`, and neither does steradian's (always bilinear).

use std::f32::consts::PI;
use std::fmt;
use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3};

use super::{EmitterSample, Support};
use crate::geometry::{trig, Transform};
use crate::param::ParamError;
use crate::sampling::piecewise_constant::PiecewiseConstant2D;
use crate::sampling::warp::{self, sin_cos_turns};
use crate::spectrum::luminance;
use crate::texture::{srgb_to_linear, LoadedImage};
use crate::Spectrum;

/// The image, its sampling distribution and its integral, shared by clones.
#[derive(Clone, PartialEq)]
struct LatLong {
    /// The file name, for messages.
    name: String,
    /// Columns w and rows h of the image.
    width: usize,
    height: usize,
    /// (w + 1) × h radiances (W/(m²·sr), `scale` applied), row-major; the last column repeats
    /// the first so that a lookup never wraps.
    texels: Vec<Spectrum>,
    /// (w + 1) × h sampling weights of the pixels (luminance, less the mean with MIS
    /// compensation, at least 0), laid out as `texels`.
    weights: Vec<f32>,
    /// Over the (h − 1) × w cells between pixel rows and columns (row-major: a row of cells is
    /// a band of θ): chooses a band, then a cell in it.
    distribution: PiecewiseConstant2D,
    /// ∫ L dω over the sphere, W/m² per channel.
    integral: Spectrum,
}

/// An `envmap` emitter (see the module docs).
#[derive(Clone, PartialEq)]
pub struct EnvironmentMap {
    /// World to emitter frame (a rotation).
    to_local: Mat3,
    /// Emitter frame to world.
    to_world: Mat3,
    map: Arc<LatLong>,
}

impl fmt::Debug for EnvironmentMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("EnvironmentMap")
            .field("name", &self.map.name)
            .field("resolution", &(self.map.width, self.map.height))
            .field("to_world", &self.to_world)
            .field("integral", &self.map.integral)
            .finish()
    }
}

/// 1 / (2π²): the Jacobian of (u, v) ↦ direction is 2π² sin θ.
const INV_TWO_PI_SQUARED: f32 = 1.0 / (2.0 * PI * PI);

impl EnvironmentMap {
    /// Factor on the pixel values where the scene gives no `scale`.
    pub const DEFAULT_SCALE: f32 = 1.0;

    /// Whether sampling is compensated for MIS where the scene does not say: Mitsuba's
    /// default, kept for every integrator but `path` ...
    pub const DEFAULT_MIS_COMPENSATION: bool = false;

    /// ... and steradian's under `path`, which weighs every light sample against a BSDF
    /// sample (see the module docs).
    pub const DEFAULT_MIS_COMPENSATION_UNDER_PATH: bool = true;

    /// The smallest image Mitsuba accepts: 2 columns, 3 rows.
    pub const MIN_RESOLUTION: (usize, usize) = (2, 3);

    /// The emitter for decoded pixels (`name` is the file name for messages).
    pub fn new(
        name: &str,
        image: LoadedImage,
        scale: f32,
        to_world: &Transform,
        mis_compensation: bool,
    ) -> Result<EnvironmentMap, ParamError> {
        let LoadedImage { width: w, height: h, channels, data, format } = image;
        let file_err = |reason: String| ParamError::new("filename", reason);
        if w < Self::MIN_RESOLUTION.0 || h < Self::MIN_RESOLUTION.1 {
            return Err(file_err(format!(
                "\"{name}\": the environment map is {w}×{h} pixels; it must be at least {}×{}",
                Self::MIN_RESOLUTION.0,
                Self::MIN_RESOLUTION.1
            )));
        }
        if !(channels == 1 || channels == 3) || data.len() != w * h * channels {
            return Err(file_err(format!("\"{name}\": unsupported pixel layout")));
        }
        if !(scale.is_finite() && scale >= 0.0) {
            let reason = format!("scale must be finite and non-negative, got {scale}");
            return Err(ParamError::new("scale", reason));
        }
        let rotation = to_world.linear();
        let gram = rotation.transpose() * rotation;
        if !gram.abs_diff_eq(Mat3::IDENTITY, 1e-4) {
            return Err(ParamError::new(
                "to_world",
                "to_world must be a rotation: an envmap takes no scale or shear (Mitsuba would \
                 look up un-normalised directions)",
            ));
        }
        // linear radiance of every pixel, before `scale`
        let mut pixels = Vec::with_capacity(w * h);
        for (i, px) in data.chunks_exact(channels).enumerate() {
            let rgb = if channels == 1 {
                Spectrum::splat(px[0])
            } else {
                Spectrum::new(px[0], px[1], px[2])
            };
            let rgb =
                if format.is_srgb() { rgb.to_array().map(srgb_to_linear).into() } else { rgb };
            if !rgb.is_finite() || rgb.min_element() < 0.0 {
                return Err(file_err(format!(
                    "\"{name}\": pixel ({}, {}) is {rgb}; radiance must be finite and non-negative",
                    i % w,
                    i / w
                )));
            }
            pixels.push(rgb);
        }
        let stride = w + 1;
        let mut texels = Vec::with_capacity(stride * h);
        for row in pixels.chunks_exact(w) {
            texels.extend(row.iter().map(|&p| p * scale));
            texels.push(row[0] * scale);
        }

        // sampling weights per pixel: luminance, less the mean with MIS compensation
        let lum: Vec<f32> = pixels.iter().map(|&p| luminance(p)).collect();
        let mut offset = 0.0;
        if mis_compensation {
            let mean = (lum.iter().map(|&l| l as f64).sum::<f64>() / lum.len() as f64) as f32;
            let min = lum.iter().copied().fold(f32::INFINITY, f32::min);
            // a (nearly) uniform map would lose all its density: keep plain sampling there
            if mean - min > 0.01 * mean {
                offset = mean;
            }
        }
        let weight = |x: usize, y: usize| (lum[y * w + x % w] - offset).max(0.0);
        let cos_row = |y: usize| (y as f64 * std::f64::consts::PI / (h - 1) as f64).cos();
        let mut cells = Vec::with_capacity(w * (h - 1));
        let mut integral = [0f64; 3];
        let d_phi = 2.0 * std::f64::consts::PI / w as f64;
        for y in 0..h - 1 {
            let band = cos_row(y) - cos_row(y + 1);
            for x in 0..w {
                let corners =
                    weight(x, y) + weight(x + 1, y) + weight(x, y + 1) + weight(x + 1, y + 1);
                cells.push((0.25 * corners as f64 * band) as f32);
                // ∫ over the cell of the bilinear radiance ≈ mean of corners × solid angle
                let l = texels[y * stride + x]
                    + texels[y * stride + x + 1]
                    + texels[(y + 1) * stride + x]
                    + texels[(y + 1) * stride + x + 1];
                for (c, acc) in integral.iter_mut().enumerate() {
                    *acc += 0.25 * l[c] as f64 * band * d_phi;
                }
            }
        }
        let distribution = PiecewiseConstant2D::new(&cells, h - 1, w);
        let weights =
            (0..h).flat_map(|y| (0..=w).map(move |x| (x, y))).map(|(x, y)| weight(x, y)).collect();
        let integral = Spectrum::new(integral[0] as f32, integral[1] as f32, integral[2] as f32);
        Ok(EnvironmentMap {
            to_local: rotation.transpose(),
            to_world: rotation,
            map: Arc::new(LatLong {
                name: name.to_string(),
                width: w,
                height: h,
                texels,
                weights,
                distribution,
                integral,
            }),
        })
    }

    /// ∫ L dω over the sphere, W/m² per channel (`Emitter::flux` is π r² times it, as for
    /// `constant`, whose integral is 4π L).
    pub fn integral(&self) -> Spectrum {
        self.map.integral
    }

    /// The half-texel shift from u to the cell coordinate u′ = u − ½/w.
    #[inline]
    fn half_texel(&self) -> f32 {
        0.5 / self.map.width as f32
    }

    /// The cell of cell coordinates (u′, v) ∈ [0, 1]² and where in it they lie.
    #[inline]
    fn locate(&self, u: f32, v: f32) -> CellPoint {
        let m = &*self.map;
        let x = u * m.width as f32;
        let y = v * (m.height - 1) as f32;
        // the upper clamps keep u′ = 1 and v = 1 inside the last cell
        let column = (x as usize).min(m.width - 1);
        let row = (y as usize).min(m.height - 2);
        CellPoint { row, column, at: Vec2::new(x - column as f32, y - row as f32) }
    }

    /// Bilinear radiance at a point of a cell.
    #[inline]
    fn eval_at(&self, c: &CellPoint) -> Spectrum {
        let m = &*self.map;
        let stride = m.width + 1;
        let i = c.row * stride + c.column;
        let t = &m.texels;
        let top = t[i] + (t[i + 1] - t[i]) * c.at.x;
        let bottom = t[i + stride] + (t[i + stride + 1] - t[i + stride]) * c.at.x;
        top + (bottom - top) * c.at.y
    }

    /// The sampling weights at the corners of a cell, in [`warp::square_to_bilinear`]'s order.
    #[inline]
    fn corner_weights(&self, row: usize, column: usize) -> [f32; 4] {
        let m = &*self.map;
        let stride = m.width + 1;
        let i = row * stride + column;
        let w = &m.weights;
        [w[i], w[i + 1], w[i + stride], w[i + stride + 1]]
    }

    /// Density of the cell coordinates of a point of a cell on [0, 1]².
    #[inline]
    fn pdf_at(&self, c: &CellPoint) -> f32 {
        self.map.distribution.cell_density(c.row, c.column)
            * warp::square_to_bilinear_pdf(c.at, self.corner_weights(c.row, c.column))
    }

    /// Cell coordinates (u′, v) and sin θ of the local unit direction `d`.
    #[inline]
    fn cell_uv(&self, d: Vec3) -> (f32, f32, f32) {
        let u = trig::atan2(d.x, -d.z) * (0.5 / PI) - self.half_texel();
        let u = u - u.floor();
        let v = trig::acos(d.y) * (1.0 / PI);
        let sin_theta = (d.x * d.x + d.z * d.z).sqrt();
        (u.min(1.0), v, sin_theta)
    }

    /// Radiance arriving from world direction `d` (towards the sky), W/(m²·sr).
    #[inline]
    pub fn radiance(&self, d: Vec3) -> Spectrum {
        let local = (self.to_local * d).normalize_or_zero();
        let (u, v, _) = self.cell_uv(local);
        self.eval_at(&self.locate(u, v))
    }

    /// Radiance arriving from world direction `d` and the density with which
    /// [`sample_direction`](Self::sample_direction) proposes `d` (1/sr): one lookup for a ray
    /// that escapes the scene after a BSDF sample.
    #[inline]
    pub fn radiance_and_pdf(&self, d: Vec3) -> (Spectrum, f32) {
        let local = (self.to_local * d).normalize_or_zero();
        let (u, v, sin_theta) = self.cell_uv(local);
        let c = self.locate(u, v);
        (self.eval_at(&c), self.pdf_at(&c) * INV_TWO_PI_SQUARED / sin_theta.max(f32::EPSILON))
    }

    #[inline]
    pub fn sample_direction(&self, u: glam::Vec2) -> Option<EmitterSample> {
        let m = &*self.map;
        let cs = m.distribution.sample_cell([u.y, u.x]);
        if cs.density <= 0.0 {
            return None;
        }
        let [row, column] = cs.cell;
        let w = self.corner_weights(row, column);
        let at = warp::square_to_bilinear(Vec2::new(cs.offset[1], cs.offset[0]), w);
        let c = CellPoint { row, column, at };
        let pdf_uv = cs.density * warp::square_to_bilinear_pdf(at, w);
        let v = (row as f32 + at.y) / (m.height - 1) as f32;
        let cu = (column as f32 + at.x) / m.width as f32;
        let (sin_theta, cos_theta) = sin_cos_turns(0.5 * v);
        let turns = cu + self.half_texel();
        let (sin_phi, cos_phi) = sin_cos_turns(if turns >= 1.0 { turns - 1.0 } else { turns });
        let sin_theta = sin_theta.max(0.0);
        let local = Vec3::new(sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta);
        let pdf = pdf_uv * INV_TWO_PI_SQUARED / sin_theta.max(f32::EPSILON);
        if pdf <= 0.0 {
            return None;
        }
        let radiance = self.eval_at(&c);
        Some(EmitterSample {
            wi: self.to_world * local,
            dist: f32::INFINITY,
            pdf,
            weight: radiance / pdf,
            support: Support::Extended,
        })
    }

    /// Solid-angle density of `sample_direction` proposing world direction `wi`, 1/sr.
    #[inline]
    pub fn pdf_direction(&self, wi: Vec3) -> f32 {
        let local = (self.to_local * wi).normalize_or_zero();
        let (u, v, sin_theta) = self.cell_uv(local);
        self.pdf_at(&self.locate(u, v)) * INV_TWO_PI_SQUARED / sin_theta.max(f32::EPSILON)
    }
}

/// A point of a cell of the lookup grid: the cell (between pixel rows `row`, `row` + 1 and
/// columns `column`, `column` + 1) and where in it, ∈ [0, 1]².
struct CellPoint {
    row: usize,
    column: usize,
    at: Vec2,
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::chi2::{directions_pvalue, CapGrid};
    use crate::texture::ImageFormat;

    /// A w×h RGB image from a function of the pixel.
    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> [f32; 3]) -> LoadedImage {
        let mut data = Vec::new();
        for y in 0..h {
            for x in 0..w {
                data.extend(f(x, y));
            }
        }
        LoadedImage { width: w, height: h, channels: 3, data, format: ImageFormat::Exr }
    }

    /// A sky with a smooth gradient and a hot spot 1000× brighter.
    fn sky(w: usize, h: usize) -> LoadedImage {
        image(w, h, |x, y| {
            let hot = if (x, y) == (w / 3, h / 3) { 1000.0 } else { 0.0 };
            [1.0 + x as f32 + hot, 0.5 + y as f32, 0.2 + hot]
        })
    }

    fn rotated() -> Transform {
        Transform::rotate(Vec3::new(1.0, 2.0, 0.5).normalize(), 37.0).unwrap()
    }

    /// The lookups Mitsuba 3.9.1 returns for a 4×3 map with pixel (x, y) =
    /// (x + 1, 10(y + 1), 100(x + 1)(y + 1)) (printed by its `eval`).
    #[test]
    fn orientation_and_bilinear_lookup_match_mitsuba() {
        let img = image(4, 3, |x, y| {
            let (x, y) = (x as f32 + 1.0, y as f32 + 1.0);
            [x, 10.0 * y, 100.0 * x * y]
        });
        let env = EnvironmentMap::new("t", img, 1.0, &Transform::IDENTITY, false).unwrap();
        let cases = [
            ([0.0, 1.0, 0.0], [2.5, 10.0, 250.0]),
            ([0.0, -1.0, 0.0], [2.5, 30.0, 750.0]),
            ([0.0, 0.0, -1.0], [2.5, 20.0, 500.0]),
            ([1.0, 0.0, 0.0], [1.5, 20.0, 300.0]),
            ([0.0, 0.0, 1.0], [2.5, 20.0, 500.0]),
            ([-1.0, 0.0, 0.0], [3.5, 20.0, 700.0]),
            ([0.3, 0.2, -0.9], [1.8855, 18.6773, 352.16]),
        ];
        for (d, want) in cases {
            let got = env.radiance(Vec3::from(d).normalize());
            let want = Spectrum::from(want);
            assert!(
                ((got - want).abs() / want).max_element() < 1e-4,
                "direction {d:?}: {got} vs Mitsuba's {want}"
            );
        }
        // scale multiplies, to_world rotates: a quarter turn about +Y takes the local +X
        // direction (u = ¼, between pixels 1 and 2 of the row) to world −Z
        let img = image(4, 3, |x, _| [x as f32 + 1.0; 3]);
        let turn = Transform::rotate(Vec3::Y, 90.0).unwrap();
        let env = EnvironmentMap::new("t", img, 2.0, &turn, false).unwrap();
        let local = Vec3::X;
        let world = turn.vector(local);
        assert!((env.radiance(world) - Spectrum::splat(3.0)).abs().max_element() < 1e-4);
    }

    #[test]
    fn sample_weight_and_pdf_agree_with_lookups() {
        let env = EnvironmentMap::new("t", sky(16, 9), 1.5, &rotated(), false).unwrap();
        let mut rng = Pcg32::new(5, 6);
        let mut worst = 0f32;
        for _ in 0..20_000 {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let Some(s) = env.sample_direction(u) else { continue };
            assert!((s.wi.length() - 1.0).abs() < 1e-5);
            let pdf = env.pdf_direction(s.wi);
            let l = env.radiance(s.wi);
            worst = worst.max((pdf - s.pdf).abs() / s.pdf);
            let w = l / s.pdf;
            assert!(
                ((w - s.weight).abs() / w.max_element()).max_element() < 2e-3,
                "{w} {}",
                s.weight
            );
        }
        // the round trip (u, v) → direction → (u, v) keeps the cell: the density agrees to
        // rounding (a direction rounding into a neighbouring cell would be off by the ratio of
        // two cells' densities, far more than this)
        assert!(worst < 1e-3, "pdf mismatch {worst}");
    }

    /// χ² test of sampled directions against `pdf_direction` with the shared harness, on a
    /// (θ, φ) grid of the emitter's frame (θ from +y, φ = atan2(x, −z), the map's own axes)
    /// whose cell edges fall between quadrature points of the map's cells.
    fn chi2(env: &EnvironmentMap, to_world: &Transform, n: usize, seed: u64) -> f64 {
        // grid (x, y, z) = map (−z, x, y): the harness's +z pole is the map's +y
        let to_grid = |d: Vec3| Vec3::new(-d.z, d.x, d.y);
        let from_grid = |g: Vec3| Vec3::new(g.y, g.z, -g.x);
        let grid = CapGrid::SPHERE.with_sub(16);
        let total: f64 = grid
            .expected(1, |g| env.pdf_direction(to_world.vector(from_grid(g))) as f64)
            .iter()
            .sum();
        assert!((total - 1.0).abs() < 2e-3, "pdf integrates to {total}");
        let mut rng = Pcg32::new(seed, 3);
        directions_pvalue(
            &grid,
            n,
            || {
                let s = env.sample_direction(Vec2::new(rng.next_f32(), rng.next_f32()))?;
                Some(to_grid(to_world.inverse().vector(s.wi)))
            },
            |g| env.pdf_direction(to_world.vector(from_grid(g))) as f64,
        )
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        // 8×5: cell edges at φ = (i + ½)/8 turns and θ = jπ/4 fall on grid lines or midway
        // between quadrature points of the 40 × 20 histogram
        let t = rotated();
        let env = EnvironmentMap::new("t", sky(8, 5), 1.0, &t, false).unwrap();
        let p = chi2(&env, &t, 200_000, 1);
        eprintln!("envmap χ² p-value {p}");
        assert!(p > 0.01, "chi2 p-value {p}");
        let env = EnvironmentMap::new("t", sky(8, 5), 1.0, &t, true).unwrap();
        let p = chi2(&env, &t, 200_000, 2);
        eprintln!("envmap χ² p-value with MIS compensation {p}");
        assert!(p > 0.01, "chi2 p-value with MIS compensation {p}");
    }

    #[test]
    fn uniform_map_integrates_to_four_pi_l() {
        let env =
            EnvironmentMap::new("t", image(6, 4, |_, _| [2.0; 3]), 1.0, &rotated(), false).unwrap();
        let want = Spectrum::splat(2.0 * 4.0 * PI);
        assert!((env.integral() - want).abs().max_element() < 1e-4 * want.x);
        let mut rng = Pcg32::new(1, 1);
        for _ in 0..1000 {
            let s = env.sample_direction(Vec2::new(rng.next_f32(), rng.next_f32())).unwrap();
            assert!((env.radiance(s.wi) - Spectrum::splat(2.0)).abs().max_element() < 1e-5);
        }
        // MIS compensation stays off for a uniform map (it would leave no density)
        let env =
            EnvironmentMap::new("t", image(6, 4, |_, _| [2.0; 3]), 1.0, &rotated(), true).unwrap();
        assert!(env.pdf_direction(Vec3::Y.normalize()) > 0.0);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let t = Transform::IDENTITY;
        let small = EnvironmentMap::new("t", sky(2, 2), 1.0, &t, false).unwrap_err();
        assert!(small.to_string().contains("at least 2×3") && small.param == "filename", "{small}");
        let neg = image(4, 3, |x, _| [if x == 2 { -1.0 } else { 1.0 }, 0.0, 0.0]);
        let e = EnvironmentMap::new("t", neg, 1.0, &t, false).unwrap_err();
        assert!(e.to_string().contains("pixel (2, 0)"), "{e}");
        let nan = image(4, 3, |_, y| [if y == 1 { f32::NAN } else { 1.0 }; 3]);
        assert!(EnvironmentMap::new("t", nan, 1.0, &t, false).is_err());
        assert!(EnvironmentMap::new("t", sky(4, 3), -1.0, &t, false).is_err());
        let scaled = Transform::scale(Vec3::splat(2.0)).unwrap();
        let e = EnvironmentMap::new("t", sky(4, 3), 1.0, &scaled, false).unwrap_err();
        assert!(e.to_string().contains("rotation") && e.param == "to_world", "{e}");
    }

    #[test]
    fn srgb_images_are_decoded() {
        let mut img = image(2, 3, |_, _| [0.5; 3]);
        img.format = ImageFormat::Png;
        let env = EnvironmentMap::new("t", img, 1.0, &Transform::IDENTITY, false).unwrap();
        let l = env.radiance(Vec3::Z);
        assert!((l.x - srgb_to_linear(0.5)).abs() < 1e-6, "{l}");
    }
}
