//! `hg`: the Henyey–Greenstein phase function (1941).
//!
//! | parameter | type  | default | meaning |
//! |-----------|-------|---------|---------|
//! | `g`       | float | 0.8     | the mean cosine of the scattering angle, in (−1, 1): > 0 forward, < 0 backward, 0 isotropic |
//!
//! p(θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}), θ the scattering angle (cos θ = −wo·wi).
//! Sampled exactly by inverting its cumulative distribution in cos θ:
//! cos θ = (1 + g² − ((1 − g²)/(1 − g + 2g ξ))²)/(2g), evaluated in f64 (in f32 it cancels to
//! an error of ~10⁻⁷/|g| in cos θ for small g); g = 0 draws cos θ = 1 − 2ξ. The density of a
//! sample is p itself, so its weight p/pdf is 1.

use glam::{Vec2, Vec3};

use super::{scattered, PhaseSample};
use crate::param::ParamError;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    g: f32,
}

impl HenyeyGreenstein {
    /// Default `g` (Mitsuba 3's).
    pub const DEFAULT_G: f32 = 0.8;

    pub fn new(g: f32) -> Result<HenyeyGreenstein, ParamError> {
        if !(g > -1.0 && g < 1.0) {
            return Err(ParamError::new("g", format!("g must lie in (-1, 1), got {g}")));
        }
        Ok(HenyeyGreenstein { g })
    }

    pub fn g(&self) -> f32 {
        self.g
    }

    /// p as a function of the scattering angle's cosine.
    fn density(&self, cos_theta: f32) -> f32 {
        let g = self.g;
        let denom = 1.0 + g * g - 2.0 * g * cos_theta;
        (1.0 - g * g) / (4.0 * std::f32::consts::PI * denom * denom.sqrt())
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.density(-wo.dot(wi))
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> PhaseSample {
        let cos_theta = if self.g == 0.0 {
            1.0 - 2.0 * u.x
        } else {
            let (g, xi) = (self.g as f64, u.x as f64);
            let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
            ((1.0 + g * g - s * s) / (2.0 * g)) as f32
        };
        let wi = scattered(wo, cos_theta, u.y);
        PhaseSample { wi, pdf: self.eval(wo, wi), weight: 1.0 }
    }
}
