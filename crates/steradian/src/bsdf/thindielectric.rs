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
//! direction. Both lobes are Dirac deltas; the surface behaves the same from both sides.

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
        let (wi, weight) = if u1 <= r {
            (reflect(wo), self.specular_reflectance.eval(sp.tex()))
        } else {
            (-wo, self.specular_transmittance.eval(sp.tex()))
        };
        Some(BsdfSample { wi, pdf: 1.0, weight, lobe: Lobe::Delta, eta: 1.0 })
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
}
