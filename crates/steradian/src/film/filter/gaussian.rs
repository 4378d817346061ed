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
//!   evaluates `exp` directly, like Mitsuba's CUDA/Metal variants.
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
        Ok(GaussianFilter {
            stddev,
            radius,
            alpha,
            bias,
        })
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
        ((-self.alpha * x * x).exp() - self.bias).max(0.0)
    }
}

impl Default for GaussianFilter {
    fn default() -> Self {
        GaussianFilter::new(Self::DEFAULT_STDDEV).expect("default gaussian stddev is valid")
    }
}
