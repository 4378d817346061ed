//! `mask`: an opacity mask over a nested BSDF (cut-out leaves, fences).
//!
//! | parameter | type            | default    | meaning |
//! |-----------|-----------------|------------|---------|
//! | `opacity` | float/texture   | 0.5        | a ∈ [0, 1] (clamped): 1 = the nested BSDF, 0 = fully transparent |
//! | (nested)  | BSDF            | (required) | the material of the opaque part |
//!
//! The surface scatters as a·ρ_nested and lets the fraction 1 − a of the light through
//! unchanged: a "null" lobe, a forward Dirac delta wi = −wo with weight 1 (Mitsuba's
//! `BSDFFlags::Null`, which its `Delta` flag includes). `sample` picks the null lobe with
//! probability 1 − a and the nested BSDF with probability a (reusing the lobe uniform);
//! nested samples report the density a·p_nested, so `sample` and `pdf` agree and MIS stays
//! consistent, as in Mitsuba 3.9.1.
//!
//! Integrators treat the null lobe as any delta lobe: a path passes straight through (the
//! crossing counts as a bounce for `max_depth`, as in Mitsuba's `path`), emitters hit after
//! it take full weight. Shadow rays are **not** transmitted through masks: Mitsuba's `path`
//! and `direct` test visibility with `ray_test`, for which a masked surface is opaque
//! (only `volpath` traces through null interfaces), and steradian does the same.
//!
//! Under `path` a mask of fractional opacity a renders at about a² of the opaque surface
//! where nothing lies behind it, as in Mitsuba 3.9.1 (its `path` counts a sample only once
//! the path scatters off a lobe that is not null: `integrator/path.rs`, "Null surfaces");
//! `volpath` and `direct` give a.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample, Lobe, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Mask {
    pub opacity: Texture,
    pub nested: Box<Bsdf>,
}

impl Mask {
    /// Default `opacity` (Mitsuba's).
    pub const DEFAULT_OPACITY: f32 = 0.5;

    pub fn new(opacity: Texture, nested: Bsdf) -> Self {
        Mask { opacity, nested: Box::new(nested) }
    }

    /// The opacity at the shading point, clamped to [0, 1] as Mitsuba does.
    #[inline]
    fn opacity(&self, sp: &ShadingPoint) -> f32 {
        let a = self.opacity.eval_1(sp.tex());
        if a.is_nan() {
            0.0
        } else {
            a.clamp(0.0, 1.0)
        }
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        let a = self.opacity(sp);
        if a == 0.0 {
            return Spectrum::ZERO;
        }
        self.nested.eval(sp, wo, wi) * a
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        let a = self.opacity(sp);
        if a == 0.0 {
            return 0.0;
        }
        self.nested.pdf(sp, wo, wi) * a
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let a = self.opacity(sp);
        if u1 < a {
            let mut s = self.nested.sample(sp, wo, (u1 / a).min(1.0 - f32::EPSILON / 2.0), u2)?;
            s.pdf *= a;
            Some(s)
        } else {
            Some(BsdfSample {
                wi: -wo,
                pdf: 1.0 - a,
                weight: Spectrum::ONE,
                lobe: Lobe::Null,
                eta: 1.0,
            })
        }
    }

    /// The fraction of light passing straight through, 1 − opacity (Mitsuba's
    /// `eval_null_transmission`).
    #[inline]
    pub fn null_transmission(&self, sp: &ShadingPoint) -> Spectrum {
        Spectrum::splat(self.null_chance(sp))
    }

    /// The chance that `sample` passes straight through: 1 − opacity.
    pub fn null_chance(&self, sp: &ShadingPoint) -> f32 {
        1.0 - self.opacity(sp)
    }

    pub fn has_smooth_lobe(&self) -> bool {
        self.nested.has_smooth_lobe()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Diffuse, MicrofacetDistribution, MicrofacetKind, RoughConductor, TwoSided};
    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::bsdf::*;

    fn rough() -> Bsdf {
        let d = MicrofacetDistribution::new(MicrofacetKind::Ggx, 0.3, 0.3, true);
        Bsdf::RoughConductor(RoughConductor::new(
            d,
            Spectrum::new(0.2, 0.9, 1.1),
            Spectrum::new(3.9, 2.4, 2.1),
            Spectrum::ONE.into(),
        ))
    }

    fn mask(a: f32, nested: Bsdf) -> Bsdf {
        Bsdf::Mask(Mask::new(Spectrum::splat(a).into(), nested))
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let diffuse = Bsdf::Diffuse(Diffuse::new(Spectrum::splat(0.8).into()));
        let mut k = 0;
        for (a, nested) in [
            (0.3, diffuse.clone()),
            (0.8, rough()),
            (0.5, Bsdf::TwoSided(TwoSided::new(diffuse.clone(), diffuse))),
        ] {
            for theta in [10.0, 50.0, 80.0] {
                let p = chi2_pvalue_with_delta(
                    &mask(a, nested.clone()),
                    dir(theta, 30.0),
                    200_000,
                    7 + k,
                );
                k += 1;
                eprintln!("χ² p-value {p:.3}");
                assert!(p > 0.01 / 9.0, "a={a} θ={theta}: p-value {p}");
            }
        }
    }

    #[test]
    fn null_lobe_passes_straight_through_with_probability_one_minus_opacity() {
        let b = mask(0.3, rough());
        let s = sp();
        let wo = dir(40.0, 70.0);
        let n = 100_000;
        let mut rng = Pcg32::new(3, 1);
        let mut null = 0usize;
        for _ in 0..n {
            let smp = b.sample(&s, wo, rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
            if let Some(x) = smp.filter(|x| x.lobe == Lobe::Null) {
                assert_eq!((x.wi, x.weight, x.pdf, x.eta), (-wo, Spectrum::ONE, 0.7, 1.0));
                null += 1;
            }
        }
        // binomial: mean 0.7 n, σ = sqrt(n·0.7·0.3); 5σ
        let sigma = (n as f64 * 0.21).sqrt();
        assert!((null as f64 - 0.7 * n as f64).abs() < 5.0 * sigma, "{null}");
        // fully opaque / fully transparent
        assert!(
            mask(1.0, rough()).sample(&s, wo, 0.999, Vec2::splat(0.4)).unwrap().lobe
                == Lobe::Smooth
        );
        assert_eq!(mask(0.0, rough()).sample(&s, wo, 0.0, Vec2::splat(0.4)).unwrap().wi, -wo);
        // from below, the null lobe still passes through
        assert_eq!(mask(0.0, rough()).sample(&s, -wo, 0.5, Vec2::splat(0.4)).unwrap().wi, wo);
    }

    #[test]
    fn eval_pdf_scale_with_opacity_consistency_reciprocity() {
        let (b, nested) = (mask(0.3, rough()), rough());
        let s = sp();
        let (wo, wi) = (dir(25.0, 10.0), dir(60.0, 200.0));
        assert!((b.eval(&s, wo, wi) - nested.eval(&s, wo, wi) * 0.3).abs().max_element() < 1e-6);
        assert!((b.pdf(&s, wo, wi) - nested.pdf(&s, wo, wi) * 0.3).abs() < 1e-6);
        assert!(
            (b.eval(&s, wo, wi) - b.eval(&s, wi, wo)).abs().max_element()
                < 1e-5 * b.eval(&s, wo, wi).max_element()
        );
        for theta in [20.0, 70.0] {
            check_sample_consistency(&b, dir(theta, 45.0), 2);
        }
    }

    #[test]
    fn furnace() {
        // the scattered part plus the transmitted 1 − a never exceeds 1
        for theta in [0.0, 45.0, 80.0, 89.0] {
            let (m, se) = albedo(
                &mask(0.6, Bsdf::Diffuse(Diffuse::new(Spectrum::ONE.into()))),
                dir(theta, 0.0),
                50_000,
                4,
            );
            assert!(m[0] <= 1.0 + 5.0 * se[0] + 1e-6, "θ={theta}: {m:?}");
            // white nested diffuse: exactly 1 (every sample has weight 1)
            assert!((m[0] - 1.0).abs() < 1e-6, "θ={theta}: {m:?}");
            let (m, se) = albedo(&mask(0.6, rough()), dir(theta, 0.0), 50_000, 5);
            assert!(m.iter().zip(se).all(|(m, se)| *m <= 1.0 + 5.0 * se), "θ={theta}: {m:?}");
        }
    }
}
