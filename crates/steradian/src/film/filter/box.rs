//! # `box` — box reconstruction filter
//!
//! Mitsuba plugin `box`. No parameters.
//!
//! - radius: **0.5 px** (fixed).
//! - weight: `w(x) = 1` for `|x| ≤ 0.5`, 0 outside (x in pixels, measured from a pixel centre).
//!
//! With this filter a film sample lands only in the pixel that contains it, with weight 1: there
//! is no splatting, and each pixel is the plain mean of its own samples. [`crate::film::ImageBlock`]
//! takes a fast path for it.

/// The box filter (radius 0.5 px, weight 1 inside).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BoxFilter;

impl BoxFilter {
    /// Radius in pixels: always 0.5.
    pub const RADIUS: f32 = 0.5;

    pub fn new() -> Self {
        BoxFilter
    }

    /// Filter radius in pixels (0.5).
    #[inline]
    pub fn radius(&self) -> f32 {
        Self::RADIUS
    }

    /// 1D weight at offset `x` pixels from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        if x.abs() <= Self::RADIUS {
            1.0
        } else {
            0.0
        }
    }
}
