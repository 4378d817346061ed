//! `constant`: a uniform sky surrounding the scene.
//!
//! | parameter  | type     | default | unit      |
//! |------------|----------|---------|-----------|
//! | `radiance` | spectrum | 1       | W/(m²·sr) |
//! | `luminance` | float | — | cd/m², instead of `radiance` (steradian's own; with `color`, `photometric.rs`) |
//! | `color` | spectrum | 1 (white) | the colour of a photometric light |
//!
//! Every ray that escapes the scene sees radiance L; an unoccluded upward-facing surface
//! receives H = π·L. Directions are sampled uniformly on the sphere, as in Mitsuba 3.

use glam::{Vec2, Vec3};

use super::{EmitterSample, Support};
use crate::sampling::warp;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct ConstantEnvironment {
    pub radiance: Spectrum,
}

impl ConstantEnvironment {
    /// Default `radiance` (W/(m²·sr); Mitsuba's).
    pub const DEFAULT_RADIANCE: f32 = 1.0;

    pub fn new(radiance: Spectrum) -> Self {
        ConstantEnvironment { radiance }
    }

    #[inline]
    pub fn radiance(&self) -> Spectrum {
        self.radiance
    }

    #[inline]
    pub fn sample_direction(&self, _p: Vec3, u: Vec2) -> Option<EmitterSample> {
        let wi = warp::square_to_uniform_sphere(u);
        let pdf = warp::UNIFORM_SPHERE_PDF;
        Some(EmitterSample {
            wi,
            dist: f32::INFINITY,
            pdf,
            weight: self.radiance / pdf,
            support: Support::Extended,
        })
    }

    #[inline]
    pub fn pdf_direction(&self, _wi: Vec3) -> f32 {
        warp::UNIFORM_SPHERE_PDF
    }
}
