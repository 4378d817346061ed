//! `isotropic`: scattering equally in every direction.
//!
//! No parameters (Mitsuba 3's). p = 1/(4π) sr⁻¹; directions are drawn uniformly on the sphere.

use glam::{Vec2, Vec3};

use super::PhaseSample;
use crate::sampling::warp;

/// 1/(4π), sr⁻¹.
const INV_FOUR_PI: f32 = 1.0 / (4.0 * std::f32::consts::PI);

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Isotropic;

impl Isotropic {
    pub fn eval(&self, _wo: Vec3, _wi: Vec3) -> f32 {
        INV_FOUR_PI
    }

    pub fn sample(&self, _wo: Vec3, u: Vec2) -> PhaseSample {
        PhaseSample { wi: warp::square_to_uniform_sphere(u), pdf: INV_FOUR_PI, weight: 1.0 }
    }
}
