//! `point`: an isotropic point light.
//!
//! | parameter   | type     | default | unit |
//! |-------------|----------|---------|------|
//! | `intensity` | spectrum | 1       | W/sr (radiant intensity, not power) |
//! | `luminous_intensity` | float | — | cd, instead of `intensity` (steradian's own; with `color`, `photometric.rs`) |
//! | `luminous_flux` | float | — | lm, instead of `intensity`: I = Φ/4π (steradian's own) |
//! | `color` | spectrum | 1 (white) | the colour of a photometric light; its luminance does not change the candela or lumen |
//! | `position`  | point    | (0,0,0) | m; or the translation of `to_world` |
//!
//! Irradiance at distance r on a surface whose normal makes angle θ with the direction to the
//! light: H = I·cos θ / r². Flux Φ = 4π·I.

use glam::Vec3;

use super::{EmitterSample, Support};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    pub intensity: Spectrum,
}

impl PointLight {
    /// Default `intensity` (W/sr; Mitsuba's).
    pub const DEFAULT_INTENSITY: f32 = 1.0;

    pub fn new(position: Vec3, intensity: Spectrum) -> Self {
        PointLight { position, intensity }
    }

    #[inline]
    pub fn sample_direction(&self, p: Vec3) -> Option<EmitterSample> {
        let (wi, dist, dist2) = super::towards(self.position, p)?;
        Some(EmitterSample {
            wi,
            dist,
            pdf: 1.0,
            weight: self.intensity / dist2,
            support: Support::Delta,
        })
    }
}
