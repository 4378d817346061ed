//! Piecewise-constant distributions on [0, 1] and [0, 1]² (pbrt-v4's
//! `PiecewiseConstant1D/2D`): sampling by inversion of the tabulated CDF, with the exact
//! density of the sample.

/// A density on [0, 1] proportional to non-negative cell values f₀ … f_{n−1}, constant in
/// each of n equal cells.
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseConstant1D {
    /// The cell values (unnormalised).
    func: Vec<f32>,
    /// CDF at the n + 1 cell edges: cdf[0] = 0, cdf[n] = 1.
    cdf: Vec<f32>,
    /// ∫ f over [0, 1] = mean cell value.
    integral: f32,
}

impl PiecewiseConstant1D {
    /// The distribution of `func` (values ≥ 0; NaNs and infinities count as 0). An all-zero function gives
    /// the uniform distribution, so that sampling never fails.
    pub fn new(func: &[f32]) -> Self {
        let n = func.len().max(1);
        let mut func: Vec<f32> =
            func.iter().map(|&f| if f > 0.0 && f.is_finite() { f } else { 0.0 }).collect();
        func.resize(n, 0.0);
        let mut cdf = vec![0f32; n + 1];
        let mut acc = 0f64;
        for i in 0..n {
            acc += func[i] as f64 / n as f64;
            cdf[i + 1] = acc as f32;
        }
        // a sum of non-negative finite values: never NaN
        let integral = acc as f32;
        if integral <= 0.0 {
            func.iter_mut().for_each(|f| *f = 1.0);
            for (i, c) in cdf.iter_mut().enumerate() {
                *c = i as f32 / n as f32;
            }
            return PiecewiseConstant1D { func, cdf, integral: 1.0 };
        }
        for c in &mut cdf[1..] {
            *c = (*c as f64 / acc) as f32;
        }
        cdf[n] = 1.0;
        PiecewiseConstant1D { func, cdf, integral }
    }

    pub fn len(&self) -> usize {
        self.func.len()
    }

    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// ∫ f over [0, 1].
    pub fn integral(&self) -> f32 {
        self.integral
    }

    /// Draws x ∈ [0, 1) from u ∈ [0, 1); returns (x, density at x, cell index).
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let n = self.func.len();
        // the last cell edge ≤ u with a non-zero cell after it
        let i = self.cdf.partition_point(|&c| c <= u).saturating_sub(1).min(n - 1);
        let width = self.cdf[i + 1] - self.cdf[i];
        let du = if width > 0.0 { ((u - self.cdf[i]) / width).clamp(0.0, 1.0) } else { 0.5 };
        let x = ((i as f32 + du) / n as f32).min(1.0 - f32::EPSILON / 2.0);
        (x, self.func[i] / self.integral, i)
    }

    /// Density at x ∈ [0, 1].
    pub fn pdf(&self, x: f32) -> f32 {
        self.func[self.cell(x)] / self.integral
    }

    /// The cell x falls in.
    #[inline]
    pub fn cell(&self, x: f32) -> usize {
        let n = self.func.len();
        ((x * n as f32) as usize).min(n - 1)
    }
}

/// A density on [0, 1]² proportional to a grid of nu × nv non-negative values, constant in each
/// cell: a marginal distribution over rows u and a conditional one over v in each row.
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseConstant2D {
    conditional: Vec<PiecewiseConstant1D>,
    marginal: PiecewiseConstant1D,
}

impl PiecewiseConstant2D {
    /// `func[iu * nv + iv]`: the value of cell (iu, iv).
    pub fn new(func: &[f32], nu: usize, nv: usize) -> Self {
        assert_eq!(
            func.len(),
            nu * nv,
            "PiecewiseConstant2D: {} values for a {nu}×{nv} grid",
            func.len()
        );
        let conditional: Vec<PiecewiseConstant1D> =
            func.chunks(nv).map(PiecewiseConstant1D::new).collect();
        // rows that are all zero became uniform: give them zero marginal weight
        let row_weight: Vec<f32> = func
            .chunks(nv)
            .map(|row| row.iter().map(|&f| f.max(0.0) as f64).sum::<f64>() as f32 / nv as f32)
            .collect();
        let marginal = PiecewiseConstant1D::new(&row_weight);
        PiecewiseConstant2D { conditional, marginal }
    }

    /// Draws (u, v) from two uniforms; returns the point and its density on [0, 1]².
    pub fn sample(&self, u: [f32; 2]) -> ([f32; 2], f32) {
        let (x, pdf_u, iu) = self.marginal.sample(u[0]);
        let (y, pdf_v, _) = self.conditional[iu].sample(u[1]);
        ([x, y], pdf_u * pdf_v)
    }

    /// Density at (u, v) ∈ [0, 1]².
    pub fn pdf(&self, p: [f32; 2]) -> f32 {
        let iu = self.marginal.cell(p[0]);
        self.marginal.pdf(p[0]) * self.conditional[iu].pdf(p[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    #[test]
    fn one_d_density_matches_values_and_integrates_to_one() {
        let d = PiecewiseConstant1D::new(&[1.0, 0.0, 3.0, 4.0]);
        assert!((d.integral() - 2.0).abs() < 1e-6);
        assert!(
            (d.pdf(0.1) - 0.5).abs() < 1e-6 && d.pdf(0.3) == 0.0 && (d.pdf(0.9) - 2.0).abs() < 1e-6
        );
        let mut rng = Pcg32::new(1, 2);
        let mut counts = [0usize; 4];
        let n = 100_000;
        for _ in 0..n {
            let (x, pdf, i) = d.sample(rng.next_f32());
            assert_eq!(i, d.cell(x));
            assert_eq!(pdf, d.pdf(x));
            counts[i] += 1;
        }
        assert_eq!(counts[1], 0);
        for (i, p) in [(0, 0.125), (2, 0.375), (3, 0.5)] {
            let se = (p * (1.0 - p) / n as f64).sqrt();
            assert!((counts[i] as f64 / n as f64 - p).abs() < 5.0 * se, "cell {i}: {counts:?}");
        }
    }

    #[test]
    fn two_d_pdf_matches_samples() {
        let f: Vec<f32> = (0..12).map(|i| (i % 5) as f32).collect();
        let d = PiecewiseConstant2D::new(&f, 3, 4);
        let total: f32 = f.iter().sum();
        let mut rng = Pcg32::new(3, 4);
        for _ in 0..1000 {
            let (p, pdf) = d.sample([rng.next_f32(), rng.next_f32()]);
            assert!((pdf - d.pdf(p)).abs() < 1e-5 * pdf);
            let cell = f[(p[0] * 3.0) as usize * 4 + (p[1] * 4.0) as usize];
            assert!((pdf - cell * 12.0 / total).abs() < 1e-5 * pdf, "{pdf} vs {cell}");
        }
        let zero = PiecewiseConstant2D::new(&[0.0; 6], 2, 3);
        assert!((zero.pdf([0.3, 0.8]) - 1.0).abs() < 1e-6);
    }
}
