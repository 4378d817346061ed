//! `blendphase`: a mix of two phase functions.
//!
//! | parameter | type  | default | meaning |
//! |-----------|-------|---------|---------|
//! | `weight`  | float | 0.5     | w in [0, 1]: 0 is the first nested phase function, 1 the second |
//! | (nested)  | phase | —       | exactly two phase functions, the first and the second in the order Mitsuba 3 takes them (their names' alphanumeric order) |
//!
//! p = (1 − w) p₀ + w p₁. Sampling picks the second with probability w (u₁ ≤ w, reused
//! rescaled by the component that draws), and the density of the sample is the mixture's, so
//! the weight p/pdf is 1. Differs from Mitsuba 3 on purpose: `weight` is a constant here (a
//! spatially varying weight belongs with heterogeneous media).

use glam::{Vec2, Vec3};

use super::{PhaseFunction, PhaseSample};
use crate::param::ParamError;

#[derive(Clone, Debug, PartialEq)]
pub struct BlendPhase {
    weight: f32,
    first: PhaseFunction,
    second: PhaseFunction,
}

impl BlendPhase {
    /// Default `weight` (Mitsuba 3's).
    pub const DEFAULT_WEIGHT: f32 = 0.5;

    pub fn new(
        weight: f32,
        first: PhaseFunction,
        second: PhaseFunction,
    ) -> Result<BlendPhase, ParamError> {
        if !(0.0..=1.0).contains(&weight) {
            return Err(ParamError::new(
                "weight",
                format!("weight must lie in [0, 1], got {weight}"),
            ));
        }
        Ok(BlendPhase { weight, first, second })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        (1.0 - self.weight) * self.first.eval(wo, wi) + self.weight * self.second.eval(wo, wi)
    }

    pub fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> PhaseSample {
        let w = self.weight;
        let s = if u1 <= w && w > 0.0 {
            self.second.sample(wo, u1 / w, u2)
        } else {
            self.first.sample(wo, ((u1 - w) / (1.0 - w)).clamp(0.0, 1.0), u2)
        };
        PhaseSample { wi: s.wi, pdf: self.eval(wo, s.wi), weight: 1.0 }
    }
}
