//! `directional`: a distant light whose parallel rays arrive from one direction (the sun).
//!
//! | parameter    | type      | default  | unit |
//! |--------------|-----------|----------|------|
//! | `irradiance` | spectrum  | 1        | W/m² on a surface perpendicular to the beam |
//! | `direction`  | vector    | —        | the direction the light travels; or `to_world` mapping +z to it |
//! | `illuminance` | float | — | lx on a surface perpendicular to the beam, instead of `irradiance` (steradian's own; with `color`, `photometric.rs`) |
//! | `color` | spectrum | 1 (white) | the colour of a photometric light |
//!
//! A surface whose normal makes angle θ with the direction towards the light receives
//! H·cos θ.

use glam::Vec3;

use super::{EmitterSample, Support};
use crate::geometry::is_positive;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction of propagation.
    pub direction: Vec3,
    pub irradiance: Spectrum,
}

impl DirectionalLight {
    /// Default `irradiance` (W/m²; Mitsuba's).
    pub const DEFAULT_IRRADIANCE: f32 = 1.0;
    /// Default direction of propagation, without `direction` or `to_world`: +z.
    pub const DEFAULT_DIRECTION: Vec3 = Vec3::Z;

    pub fn new(direction: Vec3, irradiance: Spectrum) -> Result<Self, String> {
        let len = direction.length();
        if !is_positive(len) || !len.is_finite() {
            return Err("direction must be a non-zero finite vector".into());
        }
        Ok(DirectionalLight { direction: direction / len, irradiance })
    }

    #[inline]
    pub fn sample_direction(&self, _p: Vec3) -> Option<EmitterSample> {
        Some(EmitterSample {
            wi: -self.direction,
            dist: f32::INFINITY,
            pdf: 1.0,
            weight: self.irradiance,
            support: Support::Delta,
        })
    }
}
