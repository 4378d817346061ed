//! `rayleigh`: scattering by particles much smaller than the wavelength (air molecules),
//! unpolarised.
//!
//! No parameters (Mitsuba 3's). p(θ) = 3 (1 + cos² θ) / (16π), symmetric front to back.
//! Sampled exactly: the cumulative distribution in μ = cos θ is (μ³ + 3μ + 4)/8, whose
//! inverse at ξ is Cardano's root of μ³ + 3μ − 2q = 0 with q = 4ξ − 2:
//! μ = ∛(q + √(q² + 1)) + ∛(q − √(q² + 1)).

use glam::{Vec2, Vec3};

use super::{scattered, PhaseSample};

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayleigh;

impl Rayleigh {
    fn density(cos_theta: f32) -> f32 {
        3.0 * (1.0 + cos_theta * cos_theta) / (16.0 * std::f32::consts::PI)
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        Rayleigh::density(-wo.dot(wi))
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> PhaseSample {
        let q = 4.0 * u.x as f64 - 2.0;
        let r = (q * q + 1.0).sqrt();
        let mu = ((q + r).cbrt() + (q - r).cbrt()) as f32;
        let wi = scattered(wo, mu, u.y);
        PhaseSample { wi, pdf: self.eval(wo, wi), weight: 1.0 }
    }
}
