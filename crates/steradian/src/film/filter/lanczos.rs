//! # `lanczos` — Lanczos-windowed sinc reconstruction filter
//!
//! Mitsuba plugin `lanczos`.
//!
//! | parameter | type    | default | unit | meaning                                 |
//! |-----------|---------|---------|------|-----------------------------------------|
//! | `lobes`   | integer | 3       | —    | side lobes; the radius in pixels        |
//!
//! - weight, x in pixels from a pixel centre, r = `lobes`:
//!   `sin(πx)·sin(πx/r) / ((πx)·(πx/r))` for |x| ≤ r (1 at |x| < ε, ε = 2⁻²⁴, as Mitsuba), 0
//!   beyond. Its lobes alternate in sign; films divide by the summed weights, as Mitsuba's do.
//! - Mitsuba's scalar variants look weights up in a 32-step table of this function; its JIT
//!   variants (and steradian) evaluate it exactly.
//! - `lobes` must be at least 1 and at most [`MAX_FILTER_RADIUS`](super::MAX_FILTER_RADIUS).

use std::f32::consts::PI;

use super::check_radius;

/// The Lanczos sinc filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LanczosFilter {
    radius: f32,
}

impl LanczosFilter {
    /// Default number of lobes.
    pub const DEFAULT_LOBES: i64 = 3;

    /// The filter with `lobes` side lobes (radius `lobes` pixels).
    pub fn new(lobes: i64) -> Result<Self, String> {
        if lobes < 1 {
            return Err(format!("lanczos filter: `lobes` must be at least 1, got {lobes}"));
        }
        let radius = lobes as f32;
        check_radius("lanczos", "lobes", radius)?;
        Ok(LanczosFilter { radius })
    }

    /// Filter radius in pixels.
    #[inline]
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// 1D weight at offset `x` pixels from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        let x = x.abs();
        if x < f32::EPSILON / 2.0 {
            return 1.0;
        }
        if x > self.radius {
            return 0.0;
        }
        let x1 = PI * x;
        let x2 = x1 / self.radius;
        (x1.sin() * x2.sin()) / (x1 * x2)
    }
}

impl Default for LanczosFilter {
    fn default() -> Self {
        LanczosFilter::new(Self::DEFAULT_LOBES).expect("default lobes are valid")
    }
}
