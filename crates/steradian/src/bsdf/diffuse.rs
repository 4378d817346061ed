//! `diffuse`: the ideal Lambertian reflector.
//!
//! | parameter     | type             | default | meaning |
//! |---------------|------------------|---------|---------|
//! | `reflectance` | spectrum/texture | 0.5     | albedo a ∈ [0, 1] (dimensionless) |
//!
//! ρ(wo, wi) = a/π for wo and wi above the surface, 0 otherwise (one-sided, as in Mitsuba 3:
//! a back face is black; wrap it in `twosided` to reflect on both sides). Energy is conserved
//! because ∫ a/π · cos θ dω = a ≤ 1. Sampling is cosine-weighted, so the sample weight is
//! exactly a.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::{cos_theta, BsdfSample, Lobe, ShadingPoint};
use crate::sampling::warp;
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Diffuse {
    pub reflectance: Texture,
}

impl Diffuse {
    /// Default `reflectance` (Mitsuba's): 0.5, also the BSDF of a shape that has none.
    pub const DEFAULT_REFLECTANCE: f32 = 0.5;

    pub fn new(reflectance: Texture) -> Self {
        Diffuse { reflectance }
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return Spectrum::ZERO;
        }
        self.reflectance.eval(sp.tex()) * FRAC_1_PI
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if cos_theta(wo) <= 0.0 {
            return 0.0;
        }
        warp::square_to_cosine_hemisphere_pdf(wi)
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if cos_theta(wo) <= 0.0 {
            return None;
        }
        let wi = warp::square_to_cosine_hemisphere(u2);
        let pdf = warp::square_to_cosine_hemisphere_pdf(wi);
        if pdf <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            pdf,
            weight: self.reflectance.eval(sp.tex()),
            lobe: Lobe::Smooth,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    fn bsdf(a: f32) -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(Spectrum::new(a, 0.5 * a, 0.25 * a).into()))
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        for theta in [0.0, 30.0, 60.0, 85.0] {
            let p = chi2_pvalue(&bsdf(0.8), dir(theta, 20.0), 200_000, 3);
            assert!(p > 0.01 / 4.0, "θ={theta}: p-value {p}");
        }
    }

    #[test]
    fn sample_weight_is_eval_cos_over_pdf() {
        check_sample_consistency(&bsdf(0.7), dir(40.0, 10.0), 1);
    }

    #[test]
    fn reciprocal_and_one_sided() {
        let b = bsdf(0.9);
        let s = sp();
        let (a, c) = (dir(20.0, 0.0), dir(70.0, 130.0));
        assert_eq!(b.eval(&s, a, c), b.eval(&s, c, a));
        assert_eq!(b.eval(&s, -a, c), Spectrum::ZERO);
        assert_eq!(b.eval(&s, a, -c), Spectrum::ZERO);
        assert!(b.sample(&s, -a, 0.5, Vec2::splat(0.5)).is_none());
    }

    #[test]
    fn albedo_equals_reflectance() {
        // white furnace: ∫ρ cos dω = a at every angle (cosine sampling makes it exact)
        for theta in [0.0, 45.0, 89.0] {
            let (m, _) = albedo(&bsdf(1.0), dir(theta, 0.0), 10_000, 2);
            assert!((m[0] - 1.0).abs() < 1e-6 && (m[1] - 0.5).abs() < 1e-6, "{m:?}");
        }
    }
}
