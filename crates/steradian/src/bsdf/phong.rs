//! `phong`: the Phong lighting equation read as an energy-conserving BRDF (steradian's own
//! plugin; Mitsuba 3 has none, Mitsuba 0.6's `phong` is the model and its defaults).
//!
//! | parameter              | type             | default | meaning |
//! |------------------------|------------------|---------|---------|
//! | `diffuse_reflectance`  | spectrum/texture | 0.5     | r_d: albedo of the Lambertian lobe (dimensionless) |
//! | `specular_reflectance` | spectrum/texture | 0.2     | r_s: albedo of the glossy lobe at normal incidence (dimensionless) |
//! | `exponent`             | float            | 30      | n ≥ 0: the Phong exponent (larger is sharper) |
//!
//! ρ(wo, wi) = r_d/π + r_s·(n+2)/(2π)·cosⁿα  (1/sr),
//!
//! α the angle between wi and the mirror direction of wo about the normal (cos α clamped at
//! 0): the *modified* Phong model of Lafortune & Willems (1994), reciprocal because
//! cos α = wi·reflect(wo) = wo·reflect(wi). The normalisation (n+2)/(2π)
//! ([`modified_phong_normalization`]) makes the glossy lobe's directional albedo exactly r_s
//! at normal incidence and less elsewhere (part of the lobe falls below the horizon), so the
//! albedo is at most r_d + r_s at every angle. The loader therefore refuses r_d + r_s > 1 in
//! any channel, naming the largest sum. One-sided like every steradian BRDF.
//!
//! Sampling picks the glossy lobe with probability s̄ = mean(r_s)/(mean(r_d) + mean(r_s))
//! (Mitsuba 0.6's choice), then draws wi ∝ cosⁿα about the mirror direction (density
//! cosⁿα/[`phong_lobe_integral`](n) = (n+1)/(2π)·cosⁿα, rejected when it falls below the
//! horizon) or cosine-weighted for the diffuse lobe; the pdf is the mixture of both.

use glam::{Vec2, Vec3};

use super::fresnel::reflect;
use super::plastic::specular_sampling_weight;
use super::{cos_theta, BsdfSample, ShadingPoint};
use crate::geometry::Frame;
use crate::param::ParamError;
use crate::radiometry::{modified_phong_normalization, phong_lobe_integral};
use crate::sampling::warp;
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Phong {
    pub diffuse_reflectance: Texture,
    pub specular_reflectance: Texture,
    /// The Phong exponent n (dimensionless, ≥ 0).
    pub exponent: f32,
    /// (n+2)/(2π) in 1/sr: the glossy lobe's normalisation.
    normalization: f32,
    /// (n+1)/(2π) in 1/sr: the density of the cosⁿα sampling lobe.
    sampling_normalization: f32,
    /// Probability of sampling the glossy lobe.
    specular_weight: f32,
}

/// Largest value of each channel of `t` anywhere: exact for constants; for other textures the
/// largest channel value is used for all three (a bound, so the check stays safe).
fn channel_max(t: &Texture) -> Spectrum {
    match t {
        Texture::Constant(v) => *v,
        #[allow(unreachable_patterns)]
        _ => Spectrum::splat(t.max_value()),
    }
}

impl Phong {
    /// Default `diffuse_reflectance` r_d (Mitsuba 0.6's; dimensionless).
    pub const DEFAULT_DIFFUSE_REFLECTANCE: f32 = 0.5;
    /// Default `specular_reflectance` r_s (Mitsuba 0.6's; dimensionless).
    pub const DEFAULT_SPECULAR_REFLECTANCE: f32 = 0.2;
    /// Default `exponent` n (Mitsuba 0.6's).
    pub const DEFAULT_EXPONENT: f32 = 30.0;

    /// The BRDF with its parameters checked: n ≥ 0 finite, reflectances ≥ 0, and
    /// r_d + r_s ≤ 1 in every channel (energy conservation; the message gives the bound). A
    /// negative reflectance is reported against itself (and the other reflectance as
    /// related); a sum above 1 against `diffuse_reflectance`, with `specular_reflectance`
    /// related.
    pub fn new(
        diffuse_reflectance: Texture,
        specular_reflectance: Texture,
        exponent: f32,
    ) -> Result<Self, ParamError> {
        if !(exponent >= 0.0 && exponent.is_finite()) {
            return Err(ParamError::new(
                "exponent",
                format!("exponent must be a finite number ≥ 0, got {exponent}"),
            ));
        }
        let (d, s) = (channel_max(&diffuse_reflectance), channel_max(&specular_reflectance));
        if !(d.min_element() >= 0.0 && s.min_element() >= 0.0) {
            let (param, related) = if d.min_element() >= 0.0 {
                ("specular_reflectance", "diffuse_reflectance")
            } else {
                ("diffuse_reflectance", "specular_reflectance")
            };
            let reason = format!(
                "diffuse_reflectance and specular_reflectance must be ≥ 0, got {:?} and {:?}",
                d.to_array(),
                s.to_array()
            );
            return Err(ParamError::new(param, reason).with_related(related));
        }
        let sum = d + s;
        if sum.max_element() > 1.0 {
            let reason = format!(
                "energy conservation requires diffuse_reflectance + specular_reflectance ≤ 1 in every channel \
                 (the albedo of this BRDF at normal incidence is their sum), but the sum reaches {} (per channel {:?})",
                sum.max_element(),
                sum.to_array()
            );
            return Err(
                ParamError::new("diffuse_reflectance", reason).with_related("specular_reflectance")
            );
        }
        let n = exponent as f64;
        let w = specular_sampling_weight(&diffuse_reflectance, &specular_reflectance);
        Ok(Phong {
            normalization: modified_phong_normalization(n) as f32,
            sampling_normalization: (1.0 / phong_lobe_integral(n)) as f32,
            specular_weight: if w.is_finite() { w } else { 0.0 },
            diffuse_reflectance,
            specular_reflectance,
            exponent,
        })
    }

    /// cosⁿα, α the angle between wi and the mirror direction of wo (0 beyond 90°).
    #[inline]
    fn lobe(&self, wo: Vec3, wi: Vec3) -> f32 {
        let cos_alpha = reflect(wo).dot(wi);
        if cos_alpha <= 0.0 {
            0.0
        } else {
            cos_alpha.min(1.0).powf(self.exponent)
        }
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return Spectrum::ZERO;
        }
        self.diffuse_reflectance.eval(sp.tex()) * std::f32::consts::FRAC_1_PI
            + self.specular_reflectance.eval(sp.tex()) * (self.normalization * self.lobe(wo, wi))
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return 0.0;
        }
        let ps = self.specular_weight;
        ps * self.sampling_normalization * self.lobe(wo, wi)
            + (1.0 - ps) * warp::square_to_cosine_hemisphere_pdf(wi)
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if cos_theta(wo) <= 0.0 {
            return None;
        }
        let wi = if u1 < self.specular_weight {
            // cos α = u^(1/(n+1)) has density (n+1)/(2π)·cosⁿα about the lobe axis
            let cos_alpha = u2.x.powf(1.0 / (self.exponent + 1.0));
            let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
            let (s, c) = warp::sin_cos_turns(u2.y);
            Frame::from_normal(reflect(wo)).to_world(Vec3::new(
                sin_alpha * c,
                sin_alpha * s,
                cos_alpha,
            ))
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

    fn phong(rd: Spectrum, rs: Spectrum, n: f32) -> Bsdf {
        Bsdf::Phong(Phong::new(rd.into(), rs.into(), n).unwrap())
    }

    fn configs() -> Vec<(Spectrum, Spectrum, f32)> {
        let mut v = vec![];
        for n in [0.0, 1.0, 10.0, 100.0, 1000.0] {
            v.push((Spectrum::new(0.5, 0.3, 0.1), Spectrum::new(0.2, 0.3, 0.6), n));
        }
        // a pure glossy lobe (n > 0: at n = 0 its density jumps to 0 at α = 90°, inside
        // the χ² cells, which the midpoint quadrature of expected counts cannot resolve)
        for n in [1.0, 10.0, 100.0, 1000.0] {
            v.push((Spectrum::ZERO, Spectrum::splat(0.9), n));
        }
        v.push((Spectrum::splat(0.8), Spectrum::ZERO, 30.0));
        v
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let cfg = configs();
        let angles = [0.0, 30.0, 60.0, 85.0];
        let tests = (cfg.len() * angles.len()) as f64;
        let mut min_p = 1f64;
        for (i, &(rd, rs, n)) in cfg.iter().enumerate() {
            for (j, theta) in angles.into_iter().enumerate() {
                // sharp lobes need a fine quadrature of the expected counts
                let sub = if n >= 1000.0 {
                    48
                } else if n >= 100.0 {
                    16
                } else {
                    8
                };
                let p = chi2_pvalue_sub(
                    &phong(rd, rs, n),
                    dir(theta, 35.0),
                    200_000,
                    (i * 10 + j) as u64,
                    sub,
                );
                min_p = min_p.min(p);
                assert!(p > 0.01 / tests, "rd {rd} rs {rs} n {n} θ={theta}: p-value {p}");
            }
        }
        eprintln!("smallest χ² p-value over {tests} tests: {min_p:.4}");
    }

    #[test]
    fn consistency_reciprocity_one_sided() {
        let s = sp();
        for (i, (rd, rs, n)) in configs().into_iter().enumerate() {
            let b = phong(rd, rs, n);
            for theta in [0.0, 40.0, 80.0] {
                check_sample_consistency(&b, dir(theta, 20.0), i as u64);
            }
            for (a, c) in [
                (dir(20.0, 10.0), dir(25.0, 185.0)),
                (dir(70.0, 0.0), dir(65.0, 170.0)),
                (dir(5.0, 0.0), dir(80.0, 30.0)),
            ] {
                let (x, y) = (b.eval(&s, a, c), b.eval(&s, c, a));
                assert!(
                    (x - y).abs().max_element() <= 1e-5 * x.max_element().max(1e-6),
                    "{x:?} vs {y:?}"
                );
                assert_eq!(b.eval(&s, -a, c), Spectrum::ZERO);
                assert_eq!(b.eval(&s, a, -c), Spectrum::ZERO);
                assert_eq!(b.pdf(&s, a, -c), 0.0);
            }
            assert!(b.sample(&s, -dir(30.0, 0.0), 0.1, Vec2::splat(0.4)).is_none());
        }
    }

    #[test]
    fn eval_is_the_formula() {
        // at the mirror direction cos α = 1: ρ = r_d/π + r_s (n+2)/(2π)
        let b = phong(Spectrum::splat(0.3), Spectrum::splat(0.5), 20.0);
        let s = sp();
        let wo = dir(40.0, 30.0);
        let expect = 0.3 / std::f32::consts::PI + 0.5 * 22.0 / std::f32::consts::TAU;
        assert!((b.eval(&s, wo, reflect(wo)).x - expect).abs() < 1e-5 * expect);
        // 90° away from the mirror direction: the Lambertian part only
        let wi = dir(60.0, 30.0);
        assert!(reflect(wo).dot(wi) < 0.0);
        assert!((b.eval(&s, wo, wi).x - 0.3 / std::f32::consts::PI).abs() < 1e-7);
    }

    #[test]
    fn white_furnace_albedo_at_most_one() {
        // r_d + r_s = 1: the albedo is exactly 1 at normal incidence and ≤ 1 at every angle
        for n in [0.0, 1.0, 5.0, 30.0, 300.0] {
            for (rd, rs) in [(0.0, 1.0), (0.5, 0.5)] {
                let b = phong(Spectrum::splat(rd), Spectrum::splat(rs), n);
                for theta in [0.0, 30.0, 60.0, 80.0, 89.0] {
                    let (m, se) = albedo(&b, dir(theta, 10.0), 100_000, 7);
                    assert!(
                        m[0] <= 1.0 + 5.0 * se[0],
                        "n {n} rs {rs} θ={theta}: albedo {} ± {}",
                        m[0],
                        se[0]
                    );
                    if theta == 0.0 {
                        assert!(
                            (m[0] - 1.0).abs() <= 5.0 * se[0] + 1e-5,
                            "n {n}: normal-incidence albedo {} ± {}",
                            m[0],
                            se[0]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn parameters_checked() {
        let e = Phong::new(Spectrum::new(0.5, 0.7, 0.1).into(), Spectrum::splat(0.4).into(), 10.0)
            .unwrap_err();
        assert!(e.reason.contains("≤ 1") && e.reason.contains("1.1"), "{e}");
        assert_eq!((e.param, e.related), ("diffuse_reflectance", Some("specular_reflectance")));
        assert!(Phong::new(Spectrum::splat(0.5).into(), Spectrum::splat(0.5).into(), 10.0).is_ok());
        // per channel, not the sum of maxima
        assert!(Phong::new(
            Spectrum::new(0.9, 0.0, 0.0).into(),
            Spectrum::new(0.0, 0.9, 0.0).into(),
            10.0
        )
        .is_ok());
        assert!(Phong::new(Spectrum::splat(0.5).into(), Spectrum::splat(0.2).into(), -1.0)
            .unwrap_err()
            .reason
            .contains("exponent"));
        let e = Phong::new(Spectrum::splat(-0.1).into(), Spectrum::splat(0.2).into(), 1.0);
        assert_eq!(e.unwrap_err().param, "diffuse_reflectance");
        let e = Phong::new(Spectrum::splat(0.1).into(), Spectrum::splat(-0.2).into(), 1.0);
        assert_eq!(e.unwrap_err().param, "specular_reflectance");
    }
}
