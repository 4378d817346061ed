//! # `catmullrom` — Catmull–Rom cubic reconstruction filter
//!
//! Mitsuba plugin `catmullrom`: the Mitchell–Netravali filter (`mitchell.rs`) with B = 0 and
//! C = 1/2, the cubic that interpolates (w(0) = 1, w(±1) = 0). No parameters; radius 2 pixels;
//! negative lobes between 1 and 2 pixels, which films divide out with the summed weights as
//! Mitsuba's do.

use super::MitchellFilter;

/// The Catmull–Rom filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CatmullRomFilter {
    cubic: MitchellFilter,
}

impl CatmullRomFilter {
    pub fn new() -> Self {
        CatmullRomFilter { cubic: MitchellFilter::new(0.0, 0.5).expect("finite constants") }
    }

    /// Filter radius in pixels.
    #[inline]
    pub fn radius(&self) -> f32 {
        self.cubic.radius()
    }

    /// 1D weight at offset `x` pixels from the pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        self.cubic.eval(x)
    }
}

impl Default for CatmullRomFilter {
    fn default() -> Self {
        Self::new()
    }
}
