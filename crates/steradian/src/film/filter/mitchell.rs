//! # `mitchell` — Mitchell–Netravali cubic reconstruction filter
//!
//! Mitsuba plugin `mitchell` (Mitchell and Netravali, "Reconstruction filters in computer
//! graphics", SIGGRAPH 1988).
//!
//! | parameter | type  | default | unit | meaning                         |
//! |-----------|-------|---------|------|---------------------------------|
//! | `B`       | float | 1/3     | —    | the paper's B (blur)            |
//! | `C`       | float | 1/3     | —    | the paper's C (ringing)         |
//!
//! - radius: 2 pixels.
//! - weight, x in pixels from a pixel centre, |x| < 1:
//!   `((12 − 9B − 6C)|x|³ + (−18 + 12B + 6C)|x|² + (6 − 2B)) / 6`;
//!   1 ≤ |x| < 2: `((−B − 6C)|x|³ + (6B + 30C)|x|² + (−12B − 48C)|x| + (8B + 24C)) / 6`;
//!   0 beyond. The weight is negative between 1 and 2 pixels for C > 0 (sharpening); films
//!   divide by the summed weights, as Mitsuba's do.
//! - Mitsuba's scalar variants look weights up in a 32-step table of this function; its JIT
//!   variants (and steradian) evaluate it exactly.
//! - `B` and `C` must be finite.

/// The Mitchell–Netravali filter with parameters B and C.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MitchellFilter {
    b: f32,
    c: f32,
}

impl MitchellFilter {
    /// Default B and C: 1/3 each (the paper's recommendation).
    pub const DEFAULT_B: f32 = 1.0 / 3.0;
    pub const DEFAULT_C: f32 = 1.0 / 3.0;
    /// Radius in pixels.
    pub const RADIUS: f32 = 2.0;

    /// The filter with parameters `b` and `c`; errors on non-finite values.
    pub fn new(b: f32, c: f32) -> Result<Self, String> {
        if !(b.is_finite() && c.is_finite()) {
            return Err(format!("mitchell filter: `B` and `C` must be finite, got {b} and {c}"));
        }
        Ok(MitchellFilter { b, c })
    }

    /// Filter radius in pixels.
    #[inline]
    pub fn radius(&self) -> f32 {
        Self::RADIUS
    }

    /// 1D weight at offset `x` pixels from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        let (b, c) = (self.b, self.c);
        let x = x.abs();
        let (x2, x3) = (x * x, x * x * x);
        let w = if x < 1.0 {
            (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
        } else if x < 2.0 {
            (-b - 6.0 * c) * x3
                + (6.0 * b + 30.0 * c) * x2
                + (-12.0 * b - 48.0 * c) * x
                + (8.0 * b + 24.0 * c)
        } else {
            0.0
        };
        w * (1.0 / 6.0)
    }
}

impl Default for MitchellFilter {
    fn default() -> Self {
        MitchellFilter { b: Self::DEFAULT_B, c: Self::DEFAULT_C }
    }
}
