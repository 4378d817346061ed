//! `plastic`: a diffuse base under a smooth dielectric coating (Mitsuba 3's `plastic`).
//!
//! | parameter              | type             | default         | meaning |
//! |------------------------|------------------|-----------------|---------|
//! | `int_ior`              | float or name    | `polypropylene` (1.49) | IOR of the coating |
//! | `ext_ior`              | float or name    | `air` (1.000277)       | IOR outside |
//! | `diffuse_reflectance`  | spectrum/texture | 0.5             | albedo a of the base (dimensionless) |
//! | `specular_reflectance` | spectrum/texture | 1               | factor on the coating's mirror reflection |
//! | `nonlinear`            | boolean          | false           | account for the colour shift of internal scattering |
//!
//! With η = int_ior/ext_ior and F(μ) the dielectric Fresnel reflectance, the BSDF is a mirror
//! lobe of weight F(cos θo)·specular_reflectance plus the diffuse term
//!
//! ρ(wo, wi) = a / (1 − F_dr,int) · (1 − F(cos θo))(1 − F(cos θi)) / (π η²),
//!
//! where F_dr,int is the diffuse Fresnel reflectance seen from inside the coating
//! ([`fresnel_diffuse_reflectance`](super::fresnel::fresnel_diffuse_reflectance)(1/η)):
//! light enters through the interface, scatters off the base and bounces between base and
//! coating before leaving. With `nonlinear = true` the denominator is 1 − a·F_dr,int (the
//! geometric series of internal bounces), which darkens and saturates colours as real
//! varnish does; the default keeps textures' colours (Mitsuba's default). One-sided.
//!
//! Sampling picks the mirror lobe with probability ∝ F(cos θo)·s̄ against (1 − F)·(1 − s̄)
//! for the diffuse lobe, where s̄ = mean(specular)/(mean(diffuse) + mean(specular)), and
//! samples the diffuse lobe by the cosine. Mitsuba's choice, kept so that noise matches.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, fresnel_diffuse_reflectance, reflect};
use super::{cos_theta, positive, BsdfSample, Lobe, ShadingPoint};
use crate::sampling::warp;
use crate::texture::Texture;
use crate::Spectrum;

/// How the diffuse base's albedo enters the internal-scattering denominator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InternalScattering {
    /// a / (1 − F_dr): colours preserved (Mitsuba's `nonlinear = false`).
    Linear,
    /// a / (1 − a·F_dr): the physically summed series (`nonlinear = true`).
    Nonlinear,
}

impl InternalScattering {
    /// The albedo a seen through a coating whose internal diffuse reflectance is `fdr`.
    #[inline]
    pub fn effective_albedo(self, a: Spectrum, fdr: f32) -> Spectrum {
        match self {
            InternalScattering::Linear => a / (1.0 - fdr),
            InternalScattering::Nonlinear => a / (Spectrum::ONE - a * fdr),
        }
    }
}

/// The chance of sampling the specular lobe given a specular weight `s` (from
/// [`specular_sampling_weight`]) and the fraction of light the coating lets through `t`.
#[inline]
pub(crate) fn specular_probability(s: f32, t: f32) -> f32 {
    let ps = (1.0 - t) * s;
    let pd = t * (1.0 - s);
    ps / (ps + pd)
}

/// s̄ = mean(specular)/(mean(diffuse) + mean(specular)), Mitsuba's lobe-selection weight.
pub(crate) fn specular_sampling_weight(diffuse: &Texture, specular: &Texture) -> f32 {
    let mean = |t: &Texture| t.mean().element_sum() / 3.0;
    let (d, s) = (mean(diffuse), mean(specular));
    s / (d + s)
}

#[derive(Clone, Debug, PartialEq)]
pub struct Plastic {
    /// Relative IOR η = int_ior/ext_ior (dimensionless).
    pub eta: f32,
    pub diffuse_reflectance: Texture,
    pub specular_reflectance: Texture,
    pub internal: InternalScattering,
    /// F_dr seen from inside the coating, F_dr(1/η).
    fdr_int: f32,
    /// 1/η²: radiance leaving the denser coating is spread over a wider solid angle.
    inv_eta_2: f32,
    specular_weight: f32,
}

impl Plastic {
    /// Default `int_ior` (Mitsuba's): polypropylene, 1.49; `roughplastic` shares the plastic
    /// defaults.
    pub const DEFAULT_INT_IOR: &'static str = "polypropylene";
    /// Default `ext_ior` (Mitsuba's): air, 1.000277.
    pub const DEFAULT_EXT_IOR: &'static str = "air";
    /// Default `diffuse_reflectance` (dimensionless).
    pub const DEFAULT_DIFFUSE_REFLECTANCE: f32 = 0.5;
    /// Default `specular_reflectance` (dimensionless factor).
    pub const DEFAULT_SPECULAR_REFLECTANCE: f32 = 1.0;
    /// Default `nonlinear`.
    pub const DEFAULT_NONLINEAR: bool = false;

    pub fn new(
        eta: f32,
        diffuse_reflectance: Texture,
        specular_reflectance: Texture,
        internal: InternalScattering,
    ) -> Self {
        let specular_weight = specular_sampling_weight(&diffuse_reflectance, &specular_reflectance);
        Plastic {
            eta,
            fdr_int: fresnel_diffuse_reflectance(1.0 / eta),
            inv_eta_2: 1.0 / (eta * eta),
            specular_weight,
            diffuse_reflectance,
            specular_reflectance,
            internal,
        }
    }

    /// ρ of the diffuse term divided by (1 − F(cos θi)), i.e. without the exit transmittance.
    #[inline]
    fn diffuse(&self, sp: &ShadingPoint, f_o: f32) -> Spectrum {
        let a =
            self.internal.effective_albedo(self.diffuse_reflectance.eval(sp.tex()), self.fdr_int);
        a * (self.inv_eta_2 * (1.0 - f_o))
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return Spectrum::ZERO;
        }
        let f_o = fresnel_dielectric(cos_theta(wo), self.eta).r;
        let f_i = fresnel_dielectric(cos_theta(wi), self.eta).r;
        self.diffuse(sp, f_o) * ((1.0 - f_i) * FRAC_1_PI)
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return 0.0;
        }
        let f_o = fresnel_dielectric(cos_theta(wo), self.eta).r;
        let p_diffuse = 1.0 - specular_probability(self.specular_weight, 1.0 - f_o);
        p_diffuse * warp::square_to_cosine_hemisphere_pdf(wi)
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if cos_theta(wo) <= 0.0 {
            return None;
        }
        let f_o = fresnel_dielectric(cos_theta(wo), self.eta).r;
        let p_specular = specular_probability(self.specular_weight, 1.0 - f_o);
        if u1 < p_specular {
            let weight = self.specular_reflectance.eval(sp.tex()) * (f_o / p_specular);
            return Some(BsdfSample {
                wi: reflect(wo),
                pdf: p_specular,
                weight,
                lobe: Lobe::Delta,
                eta: 1.0,
            });
        }
        let p_diffuse = 1.0 - p_specular;
        let wi = warp::square_to_cosine_hemisphere(u2);
        let pdf = p_diffuse * warp::square_to_cosine_hemisphere_pdf(wi);
        if !positive(pdf) || cos_theta(wi) <= 0.0 {
            return None;
        }
        let f_i = fresnel_dielectric(cos_theta(wi), self.eta).r;
        let weight = self.diffuse(sp, f_o) * ((1.0 - f_i) / p_diffuse);
        Some(BsdfSample { wi, pdf, weight, lobe: Lobe::Smooth, eta: 1.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    fn plastic(a: f32, internal: InternalScattering) -> Bsdf {
        Bsdf::Plastic(Plastic::new(
            1.49 / 1.000277,
            Spectrum::new(a, 0.5 * a, 0.2).into(),
            Spectrum::ONE.into(),
            internal,
        ))
    }

    #[test]
    fn diffuse_lobe_sampling_matches_pdf_chi2() {
        // The χ² test covers the smooth lobe: condition on it by using u1 past the specular
        // probability (specular weight 0 makes the diffuse lobe the only one).
        let b = Bsdf::Plastic(Plastic::new(
            1.5,
            Spectrum::splat(0.5).into(),
            Spectrum::ZERO.into(),
            InternalScattering::Linear,
        ));
        for theta in [0.0, 45.0, 80.0] {
            let p = chi2_pvalue(&b, dir(theta, 10.0), 100_000, 3);
            assert!(p > 0.01 / 3.0, "θ={theta}: p-value {p}");
        }
    }

    #[test]
    fn consistency_reciprocity_and_furnace() {
        for internal in [InternalScattering::Linear, InternalScattering::Nonlinear] {
            let b = plastic(0.8, internal);
            for theta in [0.0, 40.0, 75.0, 89.0] {
                check_sample_consistency(&b, dir(theta, 20.0), 1);
            }
            let s = sp();
            for (a, c) in [(dir(20.0, 10.0), dir(50.0, 200.0)), (dir(80.0, 0.0), dir(5.0, 170.0))] {
                let (x, y) = (b.eval(&s, a, c), b.eval(&s, c, a));
                assert!((x - y).abs().max_element() <= 1e-6 * x.max_element(), "{x:?} vs {y:?}");
            }
        }
        // White base, white coating, nonlinear series: the model is lossless, so the albedo
        // is 1 except for the error of the F_dr fit, whose effect is bounded exactly:
        // albedo − 1 = (1 − F_o)(F_dr,fit − F_dr)/(1 − F_dr,fit) with F_dr by quadrature.
        let eta = 1.5f32;
        let white = Bsdf::Plastic(Plastic::new(
            eta,
            Spectrum::ONE.into(),
            Spectrum::ONE.into(),
            InternalScattering::Nonlinear,
        ));
        let (x, w) = crate::radiometry::gauss_legendre::<256>();
        let fdr: f64 = x
            .iter()
            .zip(&w)
            .map(|(&xi, &wi)| {
                let mu = 0.5 * (xi + 1.0);
                wi * fresnel_dielectric(mu as f32, 1.0 / eta).r as f64 * mu
            })
            .sum();
        let fit = fresnel_diffuse_reflectance(1.0 / eta) as f64;
        let bias = (fit - fdr).abs() / (1.0 - fit);
        for theta in [0.0, 30.0, 60.0, 85.0] {
            let (m, se) = albedo(&white, dir(theta, 0.0), 200_000, 9);
            assert!(
                (m[0] - 1.0).abs() <= 4.0 * se[0] + bias,
                "θ={theta}: albedo {} ± {} (fit bias ≤ {bias})",
                m[0],
                se[0]
            );
        }
    }

    #[test]
    fn specular_lobe_is_the_fresnel_mirror() {
        let b = plastic(0.5, InternalScattering::Linear);
        let s = sp();
        let wo = dir(60.0, 30.0);
        let f = fresnel_dielectric(wo.z, 1.49 / 1.000277).r;
        let mut n = 0;
        for i in 0..1000 {
            let u1 = (i as f32 + 0.5) / 1000.0;
            if let Some(bs) = b.sample(&s, wo, u1, Vec2::new(0.3, 0.7)) {
                if bs.lobe == Lobe::Delta {
                    n += 1;
                    assert!((bs.wi - reflect(wo)).length() < 1e-6);
                    assert!(
                        (bs.weight.x * bs.pdf - f).abs() < 1e-6,
                        "{} vs F = {f}",
                        bs.weight.x * bs.pdf
                    );
                }
            }
        }
        // the fraction of u1 values choosing the mirror is the specular probability
        let Bsdf::Plastic(p) = &b else { unreachable!() };
        let expect = specular_probability(p.specular_weight, 1.0 - f) * 1000.0;
        assert!((n as f32 - expect).abs() <= 1.0, "{n} mirror samples, expected {expect}");
    }
}
