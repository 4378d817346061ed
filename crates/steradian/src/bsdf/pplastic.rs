//! `pplastic`: Mitsuba 3's "polarized plastic", in its unpolarised form: a rough specular
//! reflection added to a Lambertian base seen through two smooth refractions.
//!
//! | parameter              | type             | default         | meaning |
//! |------------------------|------------------|-----------------|---------|
//! | `distribution`         | string           | `beckmann`      | `beckmann` or `ggx` |
//! | `alpha` or `alpha_u`/`alpha_v` | float    | 0.1             | roughness α of the specular lobe (anisotropic allowed) |
//! | `sample_visible`       | boolean          | true            | sample visible normals |
//! | `int_ior`              | float or name    | `polypropylene` (1.49) | IOR inside (must differ from `ext_ior`) |
//! | `ext_ior`              | float or name    | `air` (1.000277)       | IOR outside |
//! | `diffuse_reflectance`  | spectrum/texture | 0.5             | albedo a of the base (dimensionless) |
//! | `specular_reflectance` | spectrum/texture | 1               | factor s on the specular lobe |
//!
//! ρ(wo, wi) = s·F(wo·h, η) D(h) G(wo, wi, h) / (4 cos θo cos θi)
//!           + a·(1 − F(cos θo, η))(1 − F(cos θi, η)) / π,
//!
//! one-sided (0 unless both directions are above the surface), h the half vector and F the
//! unpolarised dielectric Fresnel reflectance. Unlike `roughplastic` the two terms are simply
//! added (Mitsuba: "not energy conserving"); steradian evaluates what Mitsuba's unpolarised
//! variants evaluate. Polarisation itself (Stokes vectors, Mueller matrices) is not modelled:
//! steradian renders unpolarised radiance.
//!
//! Sampling picks the specular lobe with probability s̄/(ā + s̄) (texture means, fixed per
//! material as in Mitsuba), samples h from the microfacet distribution and reflects, else draws
//! a cosine-weighted direction; the density is the mixture of both.

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, reflect_about};
use super::microfacet::MicrofacetDistribution;
use super::plastic::specular_sampling_weight;
use super::{cos_theta, BsdfSample, ShadingPoint};
use crate::sampling::warp;
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct PPlastic {
    pub distribution: MicrofacetDistribution,
    /// Relative IOR η = int_ior/ext_ior (dimensionless, ≠ 1).
    pub eta: f32,
    pub diffuse_reflectance: Texture,
    pub specular_reflectance: Texture,
    /// Probability of sampling the specular lobe.
    specular_weight: f32,
}

impl PPlastic {
    /// Default `diffuse_reflectance` (Mitsuba's).
    pub const DEFAULT_DIFFUSE_REFLECTANCE: f32 = 0.5;
    /// Default `specular_reflectance` (Mitsuba's: none, i.e. 1).
    pub const DEFAULT_SPECULAR_REFLECTANCE: f32 = 1.0;
    /// Default `int_ior` (Mitsuba's).
    pub const DEFAULT_INT_IOR: &'static str = "polypropylene";
    /// Default `ext_ior` (Mitsuba's).
    pub const DEFAULT_EXT_IOR: &'static str = "air";

    pub fn new(
        distribution: MicrofacetDistribution,
        eta: f32,
        diffuse_reflectance: Texture,
        specular_reflectance: Texture,
    ) -> Self {
        let specular_weight = specular_sampling_weight(&diffuse_reflectance, &specular_reflectance);
        PPlastic { distribution, eta, diffuse_reflectance, specular_reflectance, specular_weight }
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        let (cos_o, cos_i) = (cos_theta(wo), cos_theta(wi));
        if cos_o <= 0.0 || cos_i <= 0.0 {
            return Spectrum::ZERO;
        }
        let h = (wo + wi).normalize();
        let distr = &self.distribution;
        let f = fresnel_dielectric(wo.dot(h), self.eta).r;
        let specular = self.specular_reflectance.eval(sp.tex())
            * (f * distr.d(h) * distr.g(wo, wi, h) / (4.0 * cos_o * cos_i));
        let t_o = 1.0 - fresnel_dielectric(cos_o, self.eta).r;
        let t_i = 1.0 - fresnel_dielectric(cos_i, self.eta).r;
        let diffuse =
            self.diffuse_reflectance.eval(sp.tex()) * (t_o * t_i * std::f32::consts::FRAC_1_PI);
        specular + diffuse
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return 0.0;
        }
        let specular = self.distribution.reflection_pdf(wo, wi, (wo + wi).normalize());
        let p = self.specular_weight;
        p * specular + (1.0 - p) * warp::square_to_cosine_hemisphere_pdf(wi)
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if cos_theta(wo) <= 0.0 {
            return None;
        }
        let wi = if u1 < self.specular_weight {
            reflect_about(wo, self.distribution.sample_normal(wo, u2))
        } else {
            warp::square_to_cosine_hemisphere(u2)
        };
        super::smooth_sample(wi, self.pdf(sp, wo, wi), || self.eval(sp, wo, wi))
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    fn configs() -> Vec<MicrofacetDistribution> {
        microfacet_grid(&[(0.05, 0.05), (0.1, 0.3), (0.3, 0.3), (0.7, 0.7)])
    }

    fn pplastic(d: MicrofacetDistribution) -> Bsdf {
        Bsdf::PPlastic(PPlastic::new(
            d,
            1.49,
            Spectrum::new(0.1, 0.25, 0.7).into(),
            Spectrum::ONE.into(),
        ))
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        assert_chi2_over_grid(&configs(), &[0.0, 45.0, 80.0], pplastic);
    }

    #[test]
    fn consistency_and_reciprocity() {
        for (i, d) in configs().into_iter().enumerate() {
            let b = pplastic(d);
            for theta in [0.0, 40.0, 75.0] {
                check_sample_consistency(&b, dir(theta, 20.0), i as u64);
            }
            let pairs = [(dir(20.0, 10.0), dir(50.0, 200.0)), (dir(70.0, 0.0), dir(65.0, 170.0))];
            assert_reciprocal(&b, &pairs, 1e-5);
        }
    }

    /// A white base under a nearly smooth interface at normal incidence: the diffuse term's
    /// albedo is (1 − F(1))·∫(1 − F(cos θ)) cos θ/π dω, below 1, and the sum stays finite.
    #[test]
    fn smooth_limit_diffuse_albedo() {
        let d = MicrofacetDistribution::new(super::super::MicrofacetKind::Ggx, 1e-3, 1e-3, true);
        let b = Bsdf::PPlastic(PPlastic::new(d, 1.5, Spectrum::ONE.into(), Spectrum::ZERO.into()));
        let (m, se) = albedo(&b, dir(0.0, 0.0), 200_000, 3);
        // 1 − F(1) = 0.96 for η 1.5; the hemispherical transmittance 1 − F_dr(1.5) = 0.908
        let expect = 0.96 * (1.0 - super::super::fresnel::fresnel_diffuse_reflectance(1.5));
        assert!(
            (m[0] - expect as f64).abs() < 4.0 * se[0] + 2e-3,
            "albedo {} ± {} vs {expect}",
            m[0],
            se[0]
        );
    }
}
