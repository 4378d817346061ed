//! `dielectric`: a smooth interface between two dielectrics (glass, water), with delta
//! reflection and refraction.
//!
//! | parameter                | type            | default | meaning |
//! |--------------------------|-----------------|---------|---------|
//! | `int_ior`                | float or name   | `bk7` (1.5046) | IOR on the inside (the side the normal points away from) |
//! | `ext_ior`                | float or name   | `air` (1.000277) | IOR on the outside |
//! | `specular_reflectance`   | spectrum        | 1       | factor on reflection (not physical) |
//! | `specular_transmittance` | spectrum        | 1       | factor on transmission (not physical) |
//!
//! η = int_ior/ext_ior (default 1.50418). Reflection or refraction is chosen with
//! probability F and 1 − F, F the exact unpolarised Fresnel reflectance, so the sample
//! weight is specular_reflectance for reflection and specular_transmittance·(η_i/η_t)² for
//! refraction: radiance is compressed by the solid-angle change across the interface. The
//! sample's `eta` is η_t/η_i of the crossing (1 for reflection), which Russian roulette uses.
//! Two-sided by nature: light inside (cos θ < 0) sees the relative IOR 1/η and may be totally
//! internally reflected.

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, reflect, refract};
use super::{BsdfSample, Lobe, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Dielectric {
    /// Relative IOR int_ior/ext_ior.
    pub eta: f32,
    pub specular_reflectance: Texture,
    pub specular_transmittance: Texture,
}

impl Dielectric {
    /// Default `int_ior` (Mitsuba's): BK7 glass, 1.5046; `thindielectric` and
    /// `roughdielectric` share the dielectric defaults.
    pub const DEFAULT_INT_IOR: &'static str = "bk7";
    /// Default `ext_ior` (Mitsuba's): air, 1.000277.
    pub const DEFAULT_EXT_IOR: &'static str = "air";
    /// Default `specular_reflectance` (dimensionless factor).
    pub const DEFAULT_SPECULAR_REFLECTANCE: f32 = 1.0;
    /// Default `specular_transmittance` (dimensionless factor).
    pub const DEFAULT_SPECULAR_TRANSMITTANCE: f32 = 1.0;

    pub fn new(eta: f32, specular_reflectance: Texture, specular_transmittance: Texture) -> Self {
        Dielectric { eta, specular_reflectance, specular_transmittance }
    }

    #[inline]
    pub fn eval(&self, _sp: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> Spectrum {
        Spectrum::ZERO
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, _u2: Vec2) -> Option<BsdfSample> {
        let f = fresnel_dielectric(wo.z, self.eta);
        if u1 <= f.r {
            let weight = self.specular_reflectance.eval(sp.tex());
            Some(BsdfSample { wi: reflect(wo), pdf: 1.0, weight, lobe: Lobe::Delta, eta: 1.0 })
        } else {
            let wi = refract(wo, f.cos_theta_t, f.eta_ti);
            let weight = self.specular_transmittance.eval(sp.tex()) * (f.eta_ti * f.eta_ti);
            Some(BsdfSample { wi, pdf: 1.0, weight, lobe: Lobe::Delta, eta: f.eta_it })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::bsdf::*;

    fn glass() -> Bsdf {
        Bsdf::Dielectric(Dielectric::new(
            1.5046 / 1.000277,
            Spectrum::ONE.into(),
            Spectrum::ONE.into(),
        ))
    }

    /// Fraction reflected, and R + T counted with the 1/η² radiance factor undone.
    fn energy(b: &Bsdf, wo: Vec3, n: usize) -> (f64, f64) {
        let mut rng = Pcg32::new(7, 3);
        let (mut refl, mut total) = (0.0, 0.0);
        for _ in 0..n {
            let s = b.sample(&sp(), wo, rng.next_f32(), Vec2::ZERO).unwrap();
            assert!((s.wi.length() - 1.0).abs() < 1e-5);
            if s.wi.z * wo.z > 0.0 {
                refl += 1.0;
                assert_eq!(s.eta, 1.0);
                total += s.weight.x as f64;
            } else {
                // weight·η² = 1: the radiance scaling is exactly (η_i/η_t)²
                total += (s.weight.x * s.eta * s.eta) as f64;
            }
        }
        (refl / n as f64, total / n as f64)
    }

    #[test]
    fn white_furnace_and_fresnel_split() {
        let b = glass();
        let eta = 1.5046f32 / 1.000277;
        for theta in [0.0, 30.0, 60.0, 80.0, 89.0] {
            for side in [1.0f32, -1.0] {
                let mut wo = dir(theta, 25.0);
                wo.z *= side;
                let n = 100_000;
                let (r, total) = energy(&b, wo, n);
                assert!((total - 1.0).abs() < 1e-5, "θ={theta} side {side}: R+T = {total}");
                let f = fresnel_dielectric(wo.z, eta).r as f64;
                let se = (f * (1.0 - f) / n as f64).sqrt();
                assert!((r - f).abs() <= 5.0 * se + 1e-9, "θ={theta}: reflected {r} vs F {f}");
            }
        }
        // beyond the critical angle from inside: all reflected
        let mut wo = dir(60.0, 0.0);
        wo.z = -wo.z;
        let (r, _) = energy(&b, wo, 1000);
        assert_eq!(r, 1.0);
    }

    #[test]
    fn refraction_follows_snell_and_reports_eta() {
        let b = glass();
        let eta = 1.5046f32 / 1.000277;
        let wo = dir(50.0, 10.0);
        let s = b.sample(&sp(), wo, 0.99, Vec2::ZERO).unwrap();
        assert!(s.wi.z < 0.0 && s.lobe == Lobe::Delta);
        let (si, st) = ((1.0 - wo.z * wo.z).sqrt(), (1.0 - s.wi.z * s.wi.z).sqrt());
        assert!((si - eta * st).abs() < 1e-5);
        assert!((s.eta - eta).abs() < 1e-6);
        assert!((s.weight.x - 1.0 / (eta * eta)).abs() < 1e-6);
        // the transmitted direction is opposite to wo in the tangent plane
        assert!(s.wi.x * wo.x < 0.0);
        // from inside out, the weight is η²
        let s = b.sample(&sp(), -dir(20.0, 0.0), 0.99, Vec2::ZERO).unwrap();
        assert!(
            s.wi.z > 0.0
                && (s.weight.x - eta * eta).abs() < 1e-4
                && (s.eta - 1.0 / eta).abs() < 1e-6
        );
    }
}
