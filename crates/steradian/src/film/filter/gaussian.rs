//! # `gaussian` — truncated Gaussian reconstruction filter (Mitsuba's default)
//!
//! Mitsuba plugin `gaussian`; the default `rfilter` of `hdrfilm`.
//!
//! | parameter | type  | default | unit   | meaning                        |
//! |-----------|-------|---------|--------|--------------------------------|
//! | `stddev`  | float | 0.5     | pixels | standard deviation σ           |
//!
//! - radius: **4σ** (2 px with the default σ = 0.5).
//! - weight: `w(x) = max(0, exp(−x²/(2σ²)) − exp(−r²/(2σ²)))`, x in pixels from a pixel centre:
//!   the Gaussian shifted down so that it reaches exactly 0 at the radius. It is not normalised
//!   (w(0) = 1 − exp(−8) for the default); films divide by the summed weights, so the scale
//!   cancels.
//! - the 2D kernel is separable: `w(dx)·w(dy)`.
//! - Mitsuba's CPU variants evaluate a degree-9 (in x²) Remez fit of this function; steradian
//!   evaluates `exp` by range reduction to 2ⁿ·2^f and a degree-6 polynomial for 2^f on
//!   [−½, ½] (relative error below 10⁻⁶, a few f32 ulps, over the default filter's range;
//!   the weights are only ever used relative to their sum); `libm`'s `expf` was 2 % of a
//!   Cornell-box render (2026-12-01, AMD EPYC, 2 cores).
//! - `stddev` must be positive and finite, with 4σ at most
//!   [`MAX_FILTER_RADIUS`](super::MAX_FILTER_RADIUS) pixels.

use super::check_radius;

/// The truncated, shifted Gaussian filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussianFilter {
    stddev: f32,
    radius: f32,
    /// 1 / (2σ²)
    alpha: f32,
    /// exp(−r²/(2σ²)), the shift that makes w(r) = 0.
    bias: f32,
}

impl GaussianFilter {
    /// Default standard deviation in pixels.
    pub const DEFAULT_STDDEV: f32 = 0.5;

    /// A Gaussian filter with standard deviation `stddev` pixels (radius 4σ).
    pub fn new(stddev: f32) -> Result<Self, String> {
        if !(stddev.is_finite() && stddev > 0.0) {
            return Err(format!(
                "gaussian filter: `stddev` must be a positive finite number of pixels, got {stddev}"
            ));
        }
        let radius = 4.0 * stddev;
        check_radius("gaussian", "4·stddev", radius)?;
        let alpha = 1.0 / (2.0 * stddev * stddev);
        let bias = (-alpha * radius * radius).exp();
        Ok(GaussianFilter { stddev, radius, alpha, bias })
    }

    /// Standard deviation σ in pixels.
    #[inline]
    pub fn stddev(&self) -> f32 {
        self.stddev
    }

    /// Filter radius in pixels (4σ).
    #[inline]
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// 1D weight at offset `x` pixels from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        if x.abs() >= self.radius {
            return 0.0;
        }
        self.eval_inside(x)
    }

    /// The weight at `|x| < radius` (no range test, so that loops over taps stay branch-free).
    #[inline]
    pub(super) fn eval_inside(&self, x: f32) -> f32 {
        (exp_neg(self.alpha * x * x) - self.bias).max(0.0)
    }
}

/// e^(−y) for 0 ≤ y ≤ 80 (the filter's argument is at most 8 with the default σ, and
/// `stddev` is bounded through the radius): 2^(−y·log₂e) split into an integer power n, put
/// into the exponent bits, and 2^f, f ∈ [−½, ½], from its Taylor polynomial to degree 6
/// (remainder < (ln 2 / 2)⁷/7! ≈ 3·10⁻⁷ relative; the rounding of y·log₂e adds about
/// 2⁻²⁴·y·ln 2 more).
#[inline]
fn exp_neg(y: f32) -> f32 {
    let z = -y.clamp(0.0, 80.0) * std::f32::consts::LOG2_E;
    // round to nearest without SSE4.1's `roundss` (`f32::round` is a libm call on baseline
    // x86-64): adding 1.5·2²³ pushes the fraction bits out; |z| < 2²² here
    const ROUND: f32 = 12_582_912.0;
    let shifted = z + ROUND;
    let n = shifted - ROUND;
    let f = (z - n) * std::f32::consts::LN_2;
    // e^f, Horner form
    let p = 1.0
        + f * (1.0
            + f * (0.5
                + f * (1.0 / 6.0 + f * (1.0 / 24.0 + f * (1.0 / 120.0 + f * (1.0 / 720.0))))));
    // n as an integer, read from the mantissa of `shifted` (integer operations only, so that
    // loops over taps vectorise; a float-to-int `as` cast saturates and does not);
    // n ≥ −116 keeps 2ⁿ a normal number
    let n_int = (shifted.to_bits() as i32).wrapping_sub(ROUND.to_bits() as i32);
    p * f32::from_bits(((n_int + 127) as u32) << 23)
}

impl Default for GaussianFilter {
    fn default() -> Self {
        GaussianFilter::new(Self::DEFAULT_STDDEV).expect("default gaussian stddev is valid")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polynomial exponential agrees with the f64 exponential to 10⁻⁶ relative over the
    /// range the default filter uses (y ≤ 8) and to 2·10⁻⁶ up to y = 16, and is exactly 1 at 0.
    #[test]
    fn exp_neg_matches_libm() {
        assert_eq!(exp_neg(0.0), 1.0);
        for (range, bound) in [(8.0f32, 1e-6), (16.0, 2e-6)] {
            let mut worst = 0.0f64;
            for i in 0..=200_000 {
                let y = i as f32 * (range / 200_000.0);
                let exact = (-(y as f64)).exp();
                worst = worst.max(((exp_neg(y) as f64 - exact) / exact).abs());
            }
            assert!(worst < bound, "y ≤ {range}: worst relative error {worst}");
        }
    }

    /// Weights: 1 − e^(−8) at the centre, 0 at and beyond the radius, symmetric.
    #[test]
    fn weights_at_centre_edge_and_symmetry() {
        let g = GaussianFilter::default();
        assert!((g.eval(0.0) - (1.0 - (-8.0f32).exp())).abs() < 1e-6);
        assert_eq!(g.eval(2.0), 0.0);
        assert_eq!(g.eval(-2.5), 0.0);
        for x in [0.1f32, 0.7, 1.3, 1.99] {
            assert_eq!(g.eval(x), g.eval(-x));
            let exact = ((-2.0 * x * x).exp() - (-8.0f32).exp()).max(0.0);
            assert!((g.eval(x) - exact).abs() < 1e-6, "x {x}: {} vs {exact}", g.eval(x));
        }
    }
}
