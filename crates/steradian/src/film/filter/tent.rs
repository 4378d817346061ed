//! # `tent` — tent (triangle) reconstruction filter
//!
//! Mitsuba plugin `tent`.
//!
//! | parameter | type  | default | unit   | meaning                         |
//! |-----------|-------|---------|--------|---------------------------------|
//! | `radius`  | float | 1.0     | pixels | half-width of the triangle      |
//!
//! - weight: `w(x) = max(0, 1 − |x|/radius)` (x in pixels from a pixel centre); it reaches 0 at
//!   the radius.
//! - the 2D kernel is separable: `w(dx)·w(dy)`.
//! - `radius` must be positive and finite (and at most
//!   [`MAX_FILTER_RADIUS`](super::MAX_FILTER_RADIUS) pixels).

use super::check_radius;

/// The tent filter: `w(x) = max(0, 1 − |x|/r)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TentFilter {
    radius: f32,
    inv_radius: f32,
}

impl TentFilter {
    /// Default radius in pixels.
    pub const DEFAULT_RADIUS: f32 = 1.0;

    /// A tent filter of the given radius (pixels). Errors on a non-positive, non-finite or
    /// oversized radius.
    pub fn new(radius: f32) -> Result<Self, String> {
        check_radius("tent", "radius", radius)?;
        Ok(TentFilter { radius, inv_radius: 1.0 / radius })
    }

    /// Filter radius in pixels.
    #[inline]
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// 1D weight at offset `x` pixels from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        (1.0 - x.abs() * self.inv_radius).max(0.0)
    }
}

impl Default for TentFilter {
    fn default() -> Self {
        TentFilter::new(Self::DEFAULT_RADIUS).expect("default tent radius is valid")
    }
}
