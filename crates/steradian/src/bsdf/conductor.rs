//! `conductor`: a perfectly smooth metal (Dirac delta reflection).
//!
//! | parameter              | type     | default | meaning |
//! |------------------------|----------|---------|---------|
//! | `material`             | string   | `none`  | preset complex IOR (`none`, `Ag`, `Al`, `Au`, `Cr`, `Cu`; see [`super::ior`]) |
//! | `eta`, `k`             | spectrum | 0, 1    | real and imaginary IOR (dimensionless); exclusive with a `material` other than `none` |
//! | `specular_reflectance` | spectrum | 1       | factor on the reflection (not physical; leave at 1) |
//!
//! The reflected direction is the mirror of `wo`, with weight F(cos θo)·specular_reflectance,
//! F the unpolarised conductor Fresnel reflectance per channel. The default `none`
//! (η = 0, k = 1) has F = 1 at every angle: a lossless mirror (Mitsuba 3's default, not
//! copper). One-sided: nothing reflects from below the surface.

use glam::{Vec2, Vec3};

use super::fresnel::{reflect, ConductorIor};
use super::{cos_theta, BsdfSample, Lobe, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Conductor {
    /// η + i·k.
    pub ior: ConductorIor,
    pub specular_reflectance: Texture,
}

impl Conductor {
    /// Default `material` (Mitsuba's): `none`, a perfect mirror; `roughconductor` shares the
    /// conductor defaults.
    pub const DEFAULT_MATERIAL: &'static str = "none";
    /// Default `eta` where `eta`/`k` are given instead of a material (dimensionless).
    pub const DEFAULT_ETA: f32 = 0.0;
    /// Default `k` where `eta`/`k` are given instead of a material (dimensionless).
    pub const DEFAULT_K: f32 = 1.0;
    /// Default `specular_reflectance` (dimensionless factor).
    pub const DEFAULT_SPECULAR_REFLECTANCE: f32 = 1.0;

    pub fn new(eta: Spectrum, k: Spectrum, specular_reflectance: Texture) -> Self {
        Conductor { ior: ConductorIor::new(eta, k), specular_reflectance }
    }

    /// Mitsuba's default: the perfect mirror (η = 0, k = 1).
    pub fn mirror() -> Self {
        Conductor::new(Spectrum::ZERO, Spectrum::ONE, Spectrum::ONE.into())
    }

    /// A delta BSDF has no finite value for any pair of directions.
    #[inline]
    pub fn eval(&self, _sp: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> Spectrum {
        Spectrum::ZERO
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, _u1: f32, _u2: Vec2) -> Option<BsdfSample> {
        let ct = cos_theta(wo);
        if ct <= 0.0 {
            return None;
        }
        let weight = self.specular_reflectance.eval(sp.tex()) * self.ior.fresnel(ct);
        Some(BsdfSample { wi: reflect(wo), pdf: 1.0, weight, lobe: Lobe::Delta, eta: 1.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    #[test]
    fn mirror_is_lossless_and_gold_matches_fresnel() {
        let b = Bsdf::Conductor(Conductor::mirror());
        for theta in [0.0, 30.0, 60.0, 89.0] {
            let wo = dir(theta, 40.0);
            let s = b.sample(&sp(), wo, 0.5, Vec2::splat(0.5)).unwrap();
            assert_eq!(s.lobe, Lobe::Delta);
            assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-6);
            assert!((s.weight - Spectrum::ONE).abs().max_element() < 1e-6, "{:?}", s.weight);
            let (m, _) = albedo(&b, wo, 100, 1);
            assert!(m.iter().all(|&x| (x - 1.0).abs() < 1e-6));
        }
        assert!(b.sample(&sp(), dir(120.0, 0.0), 0.5, Vec2::splat(0.5)).is_none());
        assert_eq!(b.eval(&sp(), dir(10.0, 0.0), dir(10.0, 180.0)), Spectrum::ZERO);
        let (eta, k) = super::super::ior::conductor_preset("Au").unwrap();
        let au = Bsdf::Conductor(Conductor::new(eta, k, Spectrum::splat(0.5).into()));
        let s = au.sample(&sp(), Vec3::Z, 0.1, Vec2::ZERO).unwrap();
        let f0 = ((eta - 1.0) * (eta - 1.0) + k * k) / ((eta + 1.0) * (eta + 1.0) + k * k);
        assert!((s.weight - 0.5 * f0).abs().max_element() < 1e-5);
        // albedo ≤ 1 at all angles
        for theta in [0.0, 45.0, 85.0] {
            let (m, _) = albedo(&au, dir(theta, 0.0), 10, 2);
            assert!(m.iter().all(|&x| x <= 1.0));
        }
    }
}
