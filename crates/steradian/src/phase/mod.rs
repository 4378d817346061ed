//! Phase functions: how a participating medium scatters light by angle, p(wo, wi) in 1/sr,
//! normalised (∫ p dω = 1 over the sphere) and reciprocal.
//!
//! Conventions, as the BSDFs': `wo` and `wi` are unit vectors pointing away from the
//! scattering point, `wo` towards where the light goes (the camera's side of a path), `wi`
//! towards where it comes from. Light that keeps its direction has wi = −wo, so the scattering
//! angle θ has cos θ = −wo·wi. A phase function is a density in wi: sampling draws wi with
//! pdf = p exactly, so every sample's weight p/pdf is 1.
//!
//! One file per Mitsuba 3 plugin, each opening with its manual: `isotropic`, `hg`
//! (Henyey–Greenstein), `rayleigh`, `tabphase` (a table over cos θ), `blendphase`. Phase functions are scalar (the same in
//! every channel), as in Mitsuba 3.

mod blendphase;
mod hg;
mod isotropic;
mod rayleigh;
mod tabphase;

pub use blendphase::BlendPhase;
pub use hg::HenyeyGreenstein;
pub use isotropic::Isotropic;
pub use rayleigh::Rayleigh;
pub use tabphase::TabulatedPhase;

use glam::{Vec2, Vec3};

use crate::geometry::Frame;

/// A phase function.
#[derive(Clone, Debug, PartialEq)]
pub enum PhaseFunction {
    Isotropic(Isotropic),
    HenyeyGreenstein(HenyeyGreenstein),
    Rayleigh(Rayleigh),
    Tabulated(TabulatedPhase),
    /// Two phase functions mixed (boxed: the family is recursive).
    Blend(Box<BlendPhase>),
}

/// A sampled incident direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseSample {
    /// Unit direction towards where the light comes from.
    pub wi: Vec3,
    /// Density of `wi`, 1/sr.
    pub pdf: f32,
    /// p(wo, wi)/pdf: 1 for every phase function here (each is sampled exactly).
    pub weight: f32,
}

impl PhaseFunction {
    /// p(wo, wi), 1/sr.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            PhaseFunction::Isotropic(p) => p.eval(wo, wi),
            PhaseFunction::HenyeyGreenstein(p) => p.eval(wo, wi),
            PhaseFunction::Rayleigh(p) => p.eval(wo, wi),
            PhaseFunction::Tabulated(p) => p.eval(wo, wi),
            PhaseFunction::Blend(p) => p.eval(wo, wi),
        }
    }

    /// Density of [`PhaseFunction::sample`] drawing `wi` (equal to [`PhaseFunction::eval`]).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval(wo, wi)
    }

    /// Draws `wi` given `wo`: `u1` chooses among mixed components (`blendphase`), `u2` the
    /// direction.
    pub fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> PhaseSample {
        match self {
            PhaseFunction::Isotropic(p) => p.sample(wo, u2),
            PhaseFunction::HenyeyGreenstein(p) => p.sample(wo, u2),
            PhaseFunction::Rayleigh(p) => p.sample(wo, u2),
            PhaseFunction::Tabulated(p) => p.sample(wo, u2),
            PhaseFunction::Blend(p) => p.sample(wo, u1, u2),
        }
    }
}

/// The direction at scattering angle θ (cos θ = `cos_theta`) from the forward direction −`wo`,
/// at azimuth 2π·`u_phi` about it.
fn scattered(wo: Vec3, cos_theta: f32, u_phi: f32) -> Vec3 {
    let cos_theta = cos_theta.clamp(-1.0, 1.0);
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (sin_phi, cos_phi) = (2.0 * std::f32::consts::PI * u_phi).sin_cos();
    Frame::from_normal(-wo).to_world(Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta))
}

#[cfg(test)]
mod tests;
