//! `thindielectric`: a thin slab of dielectric (window pane, soap film) modelled as one
//! surface, as in Mitsuba 3.
//!
//! | parameter                | type          | default | meaning |
//! |--------------------------|---------------|---------|---------|
//! | `int_ior`                | float or name | `bk7`   | IOR of the slab |
//! | `ext_ior`                | float or name | `air`   | IOR around it |
//! | `specular_reflectance`   | spectrum      | 1       | factor on reflection |
//! | `specular_transmittance` | spectrum      | 1       | factor on transmission |
//!
//! With R = F(|cos θo|, η) the single-interface reflectance, internal interreflections give
//! the total reflectance R' = R + T²R + T²R³ + … = 2R/(1 + R) and transmittance 1 − R'.
//! Transmitted light continues **straight through** (wi = −wo: the two refractions cancel),
//! so no radiance scaling applies and the sample's `eta` is 1. Reflection is the mirror
//! direction (a Dirac delta); the surface behaves the same from both sides.
//!
//! As in Mitsuba 3.9.1, the transmission is a **null** lobe (its `BSDFFlags::Null`, weight
//! (1 − R')·`specular_transmittance`), with what that means there:
//! - `volpath`'s shadow rays cross the pane, weighted by (1 − R'(|cos θ|))·
//!   `specular_transmittance` at the angle they cross it (Mitsuba's
//!   `eval_null_transmission`), where `path`'s stop at it; `volpath` does not count the
//!   crossing as a scattering event (path depth, the MIS vertex).
//! - Under `path`, a camera path that only crosses panes counts once it scatters off
//!   something else (module docs of `integrator/path.rs`, "Null surfaces"): a light seen
//!   through a pane alone is black, as in Mitsuba.
//!
//! Measured against Mitsuba 3.9.1 (`tests/thindielectric.rs`, 64 spp, its render-test rule,
//! 99.75 % of the pixels must pass): with the transmission a delta lobe, 90.1 % of the
//! pixels passed under `volpath` (the panes' shadows black) and 97.6 % under `path` (the
//! light behind the clear pane shown); as a null lobe, 99.97 % and 100 %.

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, reflect};
use super::{BsdfSample, Lobe, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct ThinDielectric {
    /// Relative IOR int_ior/ext_ior.
    pub eta: f32,
    pub specular_reflectance: Texture,
    pub specular_transmittance: Texture,
}

impl ThinDielectric {
    pub fn new(eta: f32, specular_reflectance: Texture, specular_transmittance: Texture) -> Self {
        ThinDielectric { eta, specular_reflectance, specular_transmittance }
    }

    /// Total reflectance R' = 2R/(1+R) of the slab seen at cos θ.
    pub fn reflectance(&self, cos_theta: f32) -> f32 {
        let r = fresnel_dielectric(cos_theta.abs(), self.eta).r;
        r * 2.0 / (1.0 + r)
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
        let r = self.reflectance(wo.z);
        let (wi, weight, lobe) = if u1 <= r {
            (reflect(wo), self.specular_reflectance.eval(sp.tex()), Lobe::Delta)
        } else {
            (-wo, self.specular_transmittance.eval(sp.tex()), Lobe::Null)
        };
        Some(BsdfSample { wi, pdf: 1.0, weight, lobe, eta: 1.0 })
    }

    /// The fraction of light that crosses the pane straight through at |cos θ| = |wo.z|:
    /// (1 − R')·`specular_transmittance` (Mitsuba's `eval_null_transmission`).
    #[inline]
    pub fn null_transmission(&self, sp: &ShadingPoint, wo: Vec3) -> Spectrum {
        self.specular_transmittance.eval(sp.tex()) * self.null_chance(wo)
    }

    /// The chance that [`sample`](Self::sample) takes the null (transmission) lobe: 1 − R'.
    #[inline]
    pub fn null_chance(&self, wo: Vec3) -> f32 {
        1.0 - self.reflectance(wo.z)
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::bsdf::*;

    #[test]
    fn lossless_with_interreflection_split() {
        let t = ThinDielectric::new(1.5046 / 1.000277, Spectrum::ONE.into(), Spectrum::ONE.into());
        let b = Bsdf::ThinDielectric(t.clone());
        for theta in [0.0, 45.0, 80.0] {
            for side in [1.0f32, -1.0] {
                let mut wo = dir(theta, 60.0);
                wo.z *= side;
                let (m, _) = albedo(&b, wo, 1000, 3);
                assert!(m.iter().all(|&x| (x - 1.0).abs() < 1e-9), "{m:?}");
                let n = 100_000;
                let mut rng = Pcg32::new(1, 1);
                let mut refl = 0usize;
                for _ in 0..n {
                    let s = b.sample(&sp(), wo, rng.next_f32(), Vec2::ZERO).unwrap();
                    if s.wi.z * wo.z > 0.0 {
                        refl += 1;
                        assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-6);
                    } else {
                        assert_eq!(s.wi, -wo);
                    }
                }
                let r = t.reflectance(wo.z) as f64;
                let se = (r * (1.0 - r) / n as f64).sqrt();
                assert!((refl as f64 / n as f64 - r).abs() < 5.0 * se);
            }
        }
        // normal incidence: R' = 2R/(1+R) with R = ((η−1)/(η+1))²
        let eta = 1.5046f32 / 1.000277;
        let r0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        assert!((t.reflectance(1.0) - 2.0 * r0 / (1.0 + r0)).abs() < 1e-6);
    }

    #[test]
    fn transmission_is_a_null_lobe_weighted_by_the_pane() {
        let tint = Spectrum::new(0.9, 0.6, 0.3);
        let pane = ThinDielectric::new(1.7, Spectrum::ONE.into(), tint.into());
        let b = Bsdf::ThinDielectric(pane.clone());
        assert!(b.may_pass_light());
        for theta in [0.0, 60.0, 84.0] {
            for side in [1.0f32, -1.0] {
                let mut wo = dir(theta, 30.0);
                wo.z *= side;
                let r = pane.reflectance(wo.z);
                // u1 above R' takes the transmission: straight through, null, weight the tint
                let s = b.sample(&sp(), wo, (r + 1.0) / 2.0, Vec2::ZERO).unwrap();
                assert_eq!((s.lobe, s.weight), (Lobe::Null, tint));
                assert!((s.wi + wo).length() < 1e-6);
                let s = b.sample(&sp(), wo, r / 2.0, Vec2::ZERO).unwrap();
                assert_eq!(s.lobe, Lobe::Delta);
                // what a shadow ray keeps, and how often sampling passes: 1 − R' at this angle
                let t = b.null_transmission(&sp(), wo);
                assert!((t - tint * (1.0 - r)).abs().max_element() < 1e-6, "{t}");
                assert!((b.null_chance(&sp(), wo) - (1.0 - r)).abs() < 1e-6);
            }
        }
        // grazing light is mostly reflected
        assert!(pane.reflectance(0.1) > 2.0 * pane.reflectance(1.0));
    }
}
