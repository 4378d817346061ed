//! A density on [0, 1]² that interpolates a grid of values bilinearly, optionally
//! conditioned on up to three parameters, sampled by inverting its continuous marginal CDF
//! over y and then its conditional CDF over x (Mitsuba 3's `Marginal2D` with
//! `Continuous = true`, the warp of its `measured` BSDF).
//!
//! **Grid.** nx × ny values (x contiguous), ≥ 2 per axis; value (i, j) sits at
//! (i/(nx − 1), j/(ny − 1)). Between them the function is the bilinear interpolant over
//! (nx − 1) × (ny − 1) patches. With parameters, the array holds one grid (a *slice*) per
//! combination of the parameters' tabulated values (the last parameter varying fastest), and
//! a lookup interpolates linearly between the two tabulated values around each parameter
//! (clamped at the ends); a parameter tabulated once is ignored.
//!
//! **Two uses.** [`Marginal2D::density`] normalises each slice to integrate to 1 over
//! [0, 1]² and builds the CDFs: `sample` maps uniforms to points with that density and
//! `invert` maps points back to uniforms (its exact inverse), both returning the density.
//! [`Marginal2D::interpolant`] keeps the values as given and only interpolates (`eval`).
//!
//! **Why Mitsuba's construction, step for step.** The CDFs are the exact integrals of the
//! bilinear interpolant (trapezoids along x, then along y, summed in f64); a sample solves the
//! quadratic of the linear density inside its patch. The `measured` model stores its colours
//! over the *inverse* of its VNDF warp, so a different warp, even an exact one, would look the
//! colours up at other places: the mapping itself is part of the material's definition.

/// The most parameters a distribution may depend on.
pub const MAX_PARAMS: usize = 3;

/// Mitsuba's clamp of uniforms away from 0 and 1 before sampling.
const EPSILON: f32 = 5.960_464_5e-8; // 2⁻²⁴
const ONE_MINUS_EPSILON: f32 = 1.0 - EPSILON;

/// How the values are kept (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Normalised to a density per slice, with CDFs for sampling.
    Density,
    /// As given; interpolation only.
    Interpolant,
}

/// Weights and slice of one set of parameter values.
struct ParamLookup {
    /// Index of the lower slice.
    slice: usize,
    /// (lower, upper) weight per parameter.
    weights: [[f32; 2]; MAX_PARAMS],
}

/// A bilinearly interpolated density or function on [0, 1]² (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Marginal2D {
    kind: Kind,
    nx: usize,
    ny: usize,
    /// Tabulated values of each parameter, ascending.
    params: Vec<Vec<f32>>,
    /// Slice stride of each parameter (0 for a parameter tabulated once).
    strides: Vec<usize>,
    /// One nx·ny grid per slice (normalised for a density).
    data: Vec<f32>,
    /// Per slice, the CDF over rows at the ny row positions (0 … 1); empty for an interpolant.
    marginal_cdf: Vec<f32>,
    /// Per slice and row, the running integral along x at the nx columns, in the units of
    /// `marginal_cdf`; empty for an interpolant.
    conditional_cdf: Vec<f32>,
}

/// The last index i ∈ [0, size − 2] with `pred(i)` (0 when none): the interval a monotone
/// predicate changes in, by bisection (Mitsuba's `math::find_interval`).
#[inline]
fn find_interval(size: usize, pred: impl Fn(usize) -> bool) -> usize {
    let (mut first, mut len) = (1usize, size.saturating_sub(2));
    while len > 0 {
        let half = len / 2;
        let middle = first + half;
        if pred(middle) {
            first = middle + 1;
            len -= half + 1;
        } else {
            len = half;
        }
    }
    (first - 1).min(size.saturating_sub(2))
}

impl Marginal2D {
    /// A density from `data` (`nx`·`ny` values per slice; slices ordered as `params`, the last
    /// varying fastest), each slice normalised to integrate to 1.
    pub fn density(
        data: &[f32],
        nx: usize,
        ny: usize,
        params: Vec<Vec<f32>>,
    ) -> Result<Marginal2D, String> {
        Self::new(Kind::Density, data, nx, ny, params)
    }

    /// An interpolant of `data` as given (layout as for [`Marginal2D::density`]).
    pub fn interpolant(
        data: &[f32],
        nx: usize,
        ny: usize,
        params: Vec<Vec<f32>>,
    ) -> Result<Marginal2D, String> {
        Self::new(Kind::Interpolant, data, nx, ny, params)
    }

    fn new(
        kind: Kind,
        data: &[f32],
        nx: usize,
        ny: usize,
        params: Vec<Vec<f32>>,
    ) -> Result<Marginal2D, String> {
        if nx < 2 || ny < 2 {
            return Err(format!("a {nx}×{ny} grid: each side needs at least 2 values"));
        }
        if params.len() > MAX_PARAMS {
            return Err(format!("{} parameters, at most {MAX_PARAMS}", params.len()));
        }
        let mut strides = vec![0; params.len()];
        let mut slices = 1;
        for (i, values) in params.iter().enumerate().rev() {
            if values.is_empty() {
                return Err("a parameter without tabulated values".into());
            }
            if values.iter().any(|v| !v.is_finite()) || values.windows(2).any(|w| w[0] >= w[1]) {
                return Err(format!("parameter values {values:?} are not finite and increasing"));
            }
            strides[i] = if values.len() > 1 { slices } else { 0 };
            slices *= values.len();
        }
        let n = nx * ny;
        if data.len() != slices * n {
            return Err(format!(
                "{} values for {slices} slices of {nx}×{ny} (expected {})",
                data.len(),
                slices * n
            ));
        }
        if let Some(v) = data.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
            return Err(format!("a value is {v}; values must be finite and non-negative"));
        }
        let mut m = Marginal2D {
            kind,
            nx,
            ny,
            params,
            strides,
            data: data.to_vec(),
            marginal_cdf: Vec::new(),
            conditional_cdf: Vec::new(),
        };
        if kind == Kind::Density {
            m.marginal_cdf = vec![0.0; slices * ny];
            m.conditional_cdf = vec![0.0; slices * n];
            for s in 0..slices {
                let d = &mut m.data[s * n..(s + 1) * n];
                let cond = &mut m.conditional_cdf[s * n..(s + 1) * n];
                let marg = &mut m.marginal_cdf[s * ny..(s + 1) * ny];
                // trapezoids along each row, then along y over the rows' totals
                for y in 0..ny {
                    let mut sum = 0f64;
                    for x in 0..nx - 1 {
                        let i = y * nx + x;
                        sum += 0.5 * (d[i] as f64 + d[i + 1] as f64);
                        cond[i + 1] = sum as f32;
                    }
                }
                let mut sum = 0f64;
                for y in 0..ny - 1 {
                    sum += 0.5 * (cond[(y + 1) * nx - 1] as f64 + cond[(y + 2) * nx - 1] as f64);
                    marg[y + 1] = sum as f32;
                }
                let total = marg[ny - 1];
                if total.is_nan() || total <= 0.0 {
                    return Err(format!("slice {s} is zero everywhere: it cannot be sampled"));
                }
                let normalization = 1.0 / total;
                cond.iter_mut().for_each(|c| *c *= normalization);
                marg.iter_mut().for_each(|c| *c *= normalization);
                d.iter_mut().for_each(|c| *c *= normalization);
            }
        }
        Ok(m)
    }

    /// Patches per axis, as f32: the factor from a patch's unit square to [0, 1]².
    #[inline]
    fn patches(&self) -> [f32; 2] {
        [(self.nx - 1) as f32, (self.ny - 1) as f32]
    }

    /// The density factor of [0, 1]² (patches' count) for a density, 1 for an interpolant.
    #[inline]
    fn scale(&self) -> f32 {
        match self.kind {
            Kind::Density => ((self.nx - 1) * (self.ny - 1)) as f32,
            Kind::Interpolant => 1.0,
        }
    }

    /// The lower slice and the weights of the parameter values `param` (one per parameter).
    #[inline]
    fn weights(&self, param: &[f32]) -> ParamLookup {
        debug_assert_eq!(param.len(), self.params.len());
        let mut lookup = ParamLookup { slice: 0, weights: [[1.0, 0.0]; MAX_PARAMS] };
        for (dim, values) in self.params.iter().enumerate() {
            if values.len() == 1 {
                continue;
            }
            let p = param[dim];
            let i = find_interval(values.len(), |k| values[k] < p);
            let (p0, p1) = (values[i], values[i + 1]);
            let w1 = ((p - p0) / (p1 - p0)).clamp(0.0, 1.0);
            lookup.weights[dim] = [1.0 - w1, w1];
            lookup.slice += self.strides[dim] * i;
        }
        lookup
    }

    /// The value at `i0` of `array` (one entry per slice of `size`), interpolated across the
    /// parameters from the lower slice `i0` lies in.
    #[inline]
    fn lookup(&self, array: &[f32], i0: usize, size: usize, w: &ParamLookup) -> f32 {
        self.lookup_dim(array, i0, size, w, self.params.len())
    }

    fn lookup_dim(
        &self,
        array: &[f32],
        i0: usize,
        size: usize,
        w: &ParamLookup,
        dim: usize,
    ) -> f32 {
        if dim == 0 {
            return array[i0];
        }
        let [w0, w1] = w.weights[dim - 1];
        let v0 = self.lookup_dim(array, i0, size, w, dim - 1);
        if w1 == 0.0 {
            return v0;
        }
        let v1 = self.lookup_dim(array, i0 + self.strides[dim - 1] * size, size, w, dim - 1);
        v0 * w0 + v1 * w1
    }

    /// The four grid values around patch index `i` (the patch's lower corner).
    #[inline]
    fn corners(&self, i: usize, w: &ParamLookup) -> [f32; 4] {
        let n = self.nx * self.ny;
        let d = &self.data;
        [
            self.lookup(d, i, n, w),
            self.lookup(d, i + 1, n, w),
            self.lookup(d, i + self.nx, n, w),
            self.lookup(d, i + self.nx + 1, n, w),
        ]
    }

    /// The value (the density on [0, 1]² for a density) at `pos` ∈ [0, 1]², for parameter
    /// values `param`.
    pub fn eval(&self, pos: [f32; 2], param: &[f32]) -> f32 {
        let w = self.weights(param);
        let [px, py] = self.patches();
        let x = pos[0].clamp(0.0, 1.0) * px;
        let y = pos[1].clamp(0.0, 1.0) * py;
        let (ix, iy) = ((x as usize).min(self.nx - 2), (y as usize).min(self.ny - 2));
        let (w1x, w1y) = (x - ix as f32, y - iy as f32);
        let (w0x, w0y) = (1.0 - w1x, 1.0 - w1y);
        let i = ix + iy * self.nx + w.slice * self.nx * self.ny;
        let [v00, v10, v01, v11] = self.corners(i, &w);
        (w0y * (w0x * v00 + w1x * v10) + w1y * (w0x * v01 + w1x * v11)) * self.scale()
    }

    /// Draws a point from uniforms `u` ∈ [0, 1)²; returns it and its density. A density only.
    pub fn sample(&self, u: [f32; 2], param: &[f32]) -> ([f32; 2], f32) {
        debug_assert_eq!(self.kind, Kind::Density);
        let w = self.weights(param);
        let (nx, ny) = (self.nx, self.ny);
        let n = nx * ny;
        let mut sx = u[0].clamp(EPSILON, ONE_MINUS_EPSILON);
        let mut sy = u[1].clamp(EPSILON, ONE_MINUS_EPSILON);

        // the row: invert the marginal CDF, then the linear density between its two rows
        let row_offset = w.slice * ny;
        let marginal = |k: usize| self.lookup(&self.marginal_cdf, row_offset + k, ny, &w);
        let row = find_interval(ny, |k| marginal(k) < sy);
        sy -= marginal(row);
        let mut col_offset = row * nx + w.slice * n;
        let cdf = &self.conditional_cdf;
        let r0 = self.lookup(cdf, col_offset + nx - 1, n, &w);
        let r1 = self.lookup(cdf, col_offset + 2 * nx - 1, n, &w);
        sy = solve_linear_density(r0, r1, sy);

        // the column, along the row interpolated at that height
        sx *= (1.0 - sy) * r0 + sy * r1;
        let conditional = |k: usize| {
            let v0 = self.lookup(cdf, col_offset + k, n, &w);
            let v1 = self.lookup(cdf, col_offset + nx + k, n, &w);
            (1.0 - sy) * v0 + sy * v1
        };
        let col = find_interval(nx, |k| conditional(k) < sx);
        sx -= conditional(col);
        col_offset += col;
        let [v00, v10, v01, v11] = self.corners(col_offset, &w);
        let c0 = (1.0 - sy) * v00 + sy * v01;
        let c1 = (1.0 - sy) * v10 + sy * v11;
        sx = solve_linear_density(c0, c1, sx);
        let [px, py] = self.patches();
        let p = [(col as f32 + sx) / px, (row as f32 + sy) / py];
        (p, ((1.0 - sx) * c0 + sx * c1) * self.scale())
    }

    /// The uniforms [`Marginal2D::sample`] maps to `pos`, and the density there. A density
    /// only.
    pub fn invert(&self, pos: [f32; 2], param: &[f32]) -> ([f32; 2], f32) {
        debug_assert_eq!(self.kind, Kind::Density);
        let w = self.weights(param);
        let (nx, ny) = (self.nx, self.ny);
        let n = nx * ny;
        let [px, py] = self.patches();
        let x = pos[0].clamp(0.0, 1.0) * px;
        let y = pos[1].clamp(0.0, 1.0) * py;
        let (ix, iy) = ((x as usize).min(nx - 2), (y as usize).min(ny - 2));
        let (mut sx, mut sy) = (x - ix as f32, y - iy as f32);
        let offset = ix + iy * nx + w.slice * n;
        let [v00, v10, v01, v11] = self.corners(offset, &w);
        let c0 = (1.0 - sy) * v00 + sy * v01;
        let c1 = (1.0 - sy) * v10 + sy * v11;
        let pdf = (1.0 - sx) * c0 + sx * c1;

        // x: the integral along the interpolated row up to x, over the row's total
        let cdf = &self.conditional_cdf;
        sx *= c0 + 0.5 * sx * (c1 - c0);
        let v0 = self.lookup(cdf, offset, n, &w);
        let v1 = self.lookup(cdf, offset + nx, n, &w);
        sx += (1.0 - sy) * v0 + sy * v1;
        let row = iy * nx + w.slice * n;
        let r0 = self.lookup(cdf, row + nx - 1, n, &w);
        let r1 = self.lookup(cdf, row + 2 * nx - 1, n, &w);
        sx /= (1.0 - sy) * r0 + sy * r1;

        // y: the marginal CDF up to y
        sy *= r0 + 0.5 * sy * (r1 - r0);
        sy += self.lookup(&self.marginal_cdf, iy + w.slice * ny, ny, &w);
        ([sx, sy], pdf * self.scale())
    }
}

/// The t ∈ [0, 1] at which the integral of the linear density a(1 − t) + b·t from 0 reaches
/// `mass`, as Mitsuba computes it (nearly equal ends count as a constant density); where
/// both ends are 0 the numerator is returned undivided, as Mitsuba does for the column.
#[inline]
fn solve_linear_density(a: f32, b: f32, mass: f32) -> f32 {
    let (numerator, divisor) = if (a - b).abs() < 1e-4 * (a + b) {
        (2.0 * mass, a + b)
    } else {
        (a - (a * a - 2.0 * mass * (a - b)).max(0.0).sqrt(), a - b)
    };
    if divisor != 0.0 {
        numerator / divisor
    } else {
        numerator
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    /// A smooth, strongly varying 2-parameter table: 3 × 2 slices of 6 × 5.
    fn table() -> Marginal2D {
        let (nx, ny) = (6, 5);
        let mut data = Vec::new();
        for p in 0..3 {
            for q in 0..2 {
                for y in 0..ny {
                    for x in 0..nx {
                        let (fx, fy) = (x as f32 / 5.0, y as f32 / 4.0);
                        data.push(
                            0.05 + (-(3.0 * fx - p as f32).powi(2)).exp() * (1.0 + fy * q as f32),
                        );
                    }
                }
            }
        }
        Marginal2D::density(&data, nx, ny, vec![vec![0.0, 0.5, 2.0], vec![-1.0, 1.0]]).unwrap()
    }

    #[test]
    fn invert_undoes_sample_and_both_give_the_density() {
        let m = table();
        let mut rng = Pcg32::new(3, 1);
        for k in 0..2000 {
            let param = [rng.next_f32() * 2.4 - 0.2, rng.next_f32() * 2.4 - 1.2];
            let u = [rng.next_f32(), rng.next_f32()];
            let (p, pdf) = m.sample(u, &param);
            let (back, pdf_back) = m.invert(p, &param);
            let pdf_eval = m.eval(p, &param);
            for c in 0..2 {
                assert!((back[c] - u[c]).abs() < 2e-4, "{k}: u {u:?} -> {p:?} -> {back:?}");
            }
            assert!((pdf - pdf_eval).abs() <= 1e-4 * pdf_eval, "{k}: {pdf} vs {pdf_eval}");
            assert!((pdf_back - pdf_eval).abs() <= 1e-4 * pdf_eval);
        }
    }

    #[test]
    fn the_density_integrates_to_one_for_any_parameter() {
        let m = table();
        let n = 400;
        for param in [[0.0, -1.0], [0.3, 0.2], [1.7, 5.0], [-3.0, 0.9]] {
            let mut sum = 0f64;
            for j in 0..n {
                for i in 0..n {
                    let p = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                    sum += m.eval(p, &param) as f64;
                }
            }
            let integral = sum / (n * n) as f64;
            assert!((integral - 1.0).abs() < 1e-3, "{param:?}: {integral}");
        }
    }

    #[test]
    fn samples_follow_the_density() {
        // a histogram of 10⁶ samples over 8 × 8 bins against the density's integral per bin;
        // each bin's count is binomial, so a 5σ band holds for all 64 at this seed
        let m = table();
        let param = [0.9, 0.3];
        let (bins, samples) = (8usize, 1_000_000usize);
        let mut counts = vec![0f64; bins * bins];
        let mut rng = Pcg32::new(11, 2);
        for _ in 0..samples {
            let (p, _) = m.sample([rng.next_f32(), rng.next_f32()], &param);
            let b = ((p[0] * bins as f32) as usize).min(bins - 1)
                + ((p[1] * bins as f32) as usize).min(bins - 1) * bins;
            counts[b] += 1.0;
        }
        let sub = 50;
        for by in 0..bins {
            for bx in 0..bins {
                let mut mass = 0f64;
                for j in 0..sub {
                    for i in 0..sub {
                        let x = (bx as f32 + (i as f32 + 0.5) / sub as f32) / bins as f32;
                        let y = (by as f32 + (j as f32 + 0.5) / sub as f32) / bins as f32;
                        mass += m.eval([x, y], &param) as f64;
                    }
                }
                let p = mass / (sub * sub * bins * bins) as f64;
                let expected = p * samples as f64;
                let sigma = (samples as f64 * p * (1.0 - p)).sqrt();
                let got = counts[bx + by * bins];
                assert!(
                    (got - expected).abs() < 5.0 * sigma + 1e-3 * expected,
                    "bin ({bx}, {by}): {got} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn an_interpolant_returns_its_values_at_the_grid_points() {
        let data: Vec<f32> = (0..12).map(|i| i as f32 * 0.5).collect();
        let m = Marginal2D::interpolant(&data, 4, 3, vec![]).unwrap();
        assert_eq!(m.eval([1.0 / 3.0, 0.5], &[]), data[5]);
        // halfway between columns 1, 2 and rows 0, 1: the mean of the four values
        let mean = 0.25 * (data[1] + data[2] + data[5] + data[6]);
        assert!((m.eval([0.5, 0.25], &[]) - mean).abs() < 1e-6);
    }

    #[test]
    fn bad_tables_are_errors() {
        assert!(Marginal2D::density(&[1.0; 4], 1, 4, vec![]).is_err());
        assert!(Marginal2D::density(&[1.0, -1.0, 1.0, 1.0], 2, 2, vec![]).is_err());
        assert!(Marginal2D::density(&[0.0; 4], 2, 2, vec![]).is_err());
        assert!(Marginal2D::density(&[1.0; 8], 2, 2, vec![vec![1.0, 0.0]]).is_err());
        assert!(Marginal2D::density(&[1.0; 6], 2, 2, vec![vec![0.0, 1.0]]).is_err());
    }
}
