//! `principledthin`: Mitsuba 3's thin-surface principled BSDF (Burley 2015's thin-shell
//! model): a sheet with no interior (leaves, paper, cloth, window panes), two-sided and
//! symmetric: both faces behave alike, and light passes without bending.
//!
//! | parameter                              | type             | default | meaning |
//! |----------------------------------------|------------------|---------|---------|
//! | `base_color`                           | spectrum/texture | 0.5     | colour of the diffuse lobes and of the transmission |
//! | `roughness`                            | float/texture    | 0.5     | r: GGX α = max(0.001, r²) |
//! | `anisotropic`                          | float/texture    | 0       | as in `principled` |
//! | `spec_trans`                           | float/texture    | 0       | t: share of the specular (glossy) lobes |
//! | `eta`                                  | float/texture    | 1.5     | IOR of the sheet (Fresnel and roughness scaling) |
//! | `spec_tint`                            | float/texture    | 0       | tints the specular reflection towards the base hue |
//! | `diff_trans`                           | float/texture    | 0       | d ∈ [0, 2]: diffuse transmission (d/2 of the diffuse) |
//! | `sheen`, `sheen_tint`, `flatness`      | float/texture    | 0       | as in `principled` |
//! | `specular_reflectance_sampling_rate`   | float            | 1       | relative rates of the four lobes in sampling |
//! | `specular_transmittance_sampling_rate` | float            | 1       | |
//! | `diffuse_reflectance_sampling_rate`    | float            | 1       | |
//! | `diffuse_transmittance_sampling_rate`  | float            | 1       | |
//!
//! Seen from the side of `wo` (both directions mirrored to it), with d' = d/2, h the half
//! vector of wo and wi mirrored to wo's side, and F the dielectric Fresnel term of η:
//! - specular reflection t·F_thin D G/(4 cos θo cos θi), F_thin = F blended by `spec_tint`
//!   towards Schlick(hue·R0(η));
//! - specular transmission t·base·(1 − F) D' G'/(4 cos θo cos θi), D' and G' of the roughness
//!   scaled by 0.65η − 0.35 (Burley 2015, fig. 15), wi on the far side;
//! - diffuse reflection (1 − t)(1 − d')·base/π·[`disney::diffuse_factor`], with sheen
//!   (1 − t)(1 − d')·sheen·[`disney::sheen`];
//! - diffuse transmission (1 − t)·d'·base/π.
//!
//! Sampling picks the lobes in proportion to t·rate/2, t·rate/2, (1 − t)(1 − d')·rate and
//! (1 − t)d'·rate, GGX visible normals for the glossy lobes and cosine-weighted directions
//! for the diffuse ones; the density is the mixture.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::disney::{self, faces_agree, schlick_fresnel, schlick_r0};
use super::fresnel::{fresnel_dielectric, reflect_about};
use super::{positive, BsdfSample, Lobe, ShadingPoint};
use crate::sampling::warp;
use crate::texture::{Texture, TexturePoint};
use crate::Spectrum;

/// The relative rates of the lobes in sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledThinSamplingRates {
    pub specular_reflection: f32,
    pub specular_transmission: f32,
    pub diffuse_reflection: f32,
    pub diffuse_transmission: f32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledThin {
    pub base_color: Texture,
    pub roughness: Texture,
    pub anisotropic: Texture,
    pub spec_trans: Texture,
    /// IOR of the sheet (dimensionless).
    pub eta: Texture,
    pub spec_tint: Texture,
    /// Diffuse transmission in [0, 2] (Mitsuba's range).
    pub diff_trans: Texture,
    pub sheen: Texture,
    pub sheen_tint: Texture,
    pub flatness: Texture,
    pub rates: PrincipledThinSamplingRates,
}

struct Point {
    base_color: Spectrum,
    roughness: f32,
    anisotropic: f32,
    spec_trans: f32,
    eta: f32,
    spec_tint: f32,
    /// Half of `diff_trans`: the diffuse light's share that is transmitted.
    diff_trans: f32,
    sheen: f32,
    sheen_tint: f32,
    flatness: f32,
}

/// The lobes, in Mitsuba's sampling order.
const SPECULAR_REFLECTION: usize = 0;
const SPECULAR_TRANSMISSION: usize = 1;
const DIFFUSE_REFLECTION: usize = 2;

impl PrincipledThin {
    pub const DEFAULT_BASE_COLOR: f32 = 0.5;
    pub const DEFAULT_ROUGHNESS: f32 = 0.5;
    pub const DEFAULT_ETA: f32 = 1.5;
    /// Default of `anisotropic`, `spec_trans`, `spec_tint`, `diff_trans`, `sheen`,
    /// `sheen_tint` and `flatness`.
    pub const DEFAULT_WEIGHT: f32 = 0.0;
    pub const DEFAULT_SAMPLING_RATES: PrincipledThinSamplingRates = PrincipledThinSamplingRates {
        specular_reflection: 1.0,
        specular_transmission: 1.0,
        diffuse_reflection: 1.0,
        diffuse_transmission: 1.0,
    };

    /// The material with every parameter at Mitsuba's default.
    pub fn new() -> Self {
        let c = |v: f32| Texture::Constant(Spectrum::splat(v));
        let w = c(Self::DEFAULT_WEIGHT);
        PrincipledThin {
            base_color: c(Self::DEFAULT_BASE_COLOR),
            roughness: c(Self::DEFAULT_ROUGHNESS),
            anisotropic: w.clone(),
            spec_trans: w.clone(),
            eta: c(Self::DEFAULT_ETA),
            spec_tint: w.clone(),
            diff_trans: w.clone(),
            sheen: w.clone(),
            sheen_tint: w.clone(),
            flatness: w,
            rates: Self::DEFAULT_SAMPLING_RATES,
        }
    }

    #[inline]
    fn at(&self, p: TexturePoint) -> Point {
        Point {
            base_color: self.base_color.eval(p),
            roughness: self.roughness.eval_1(p),
            anisotropic: self.anisotropic.eval_1(p),
            spec_trans: self.spec_trans.eval_1(p),
            eta: self.eta.eval_1(p),
            spec_tint: self.spec_tint.eval_1(p),
            diff_trans: self.diff_trans.eval_1(p) / 2.0,
            sheen: self.sheen.eval_1(p),
            sheen_tint: self.sheen_tint.eval_1(p),
            flatness: self.flatness.eval_1(p),
        }
    }

    #[inline]
    fn lobe_probabilities(&self, p: &Point) -> [f32; 4] {
        let r = &self.rates;
        let (t, d) = (p.spec_trans, p.diff_trans);
        disney::normalised([
            t * r.specular_reflection / 2.0,
            t * r.specular_transmission / 2.0,
            r.diffuse_reflection * (1.0 - t) * (1.0 - d),
            r.diffuse_transmission * (1.0 - t) * d,
        ])
    }

    /// The GGX lobe of the transmission: roughness scaled by 0.65η − 0.35.
    #[inline]
    fn transmission_ggx(p: &Point) -> super::MicrofacetDistribution {
        disney::ggx((0.65 * p.eta - 0.35) * p.roughness, p.anisotropic)
    }

    /// `wo` and `wi` mirrored so that `wo` is above the surface, and the half vector of wo
    /// and wi's reflection into wo's hemisphere. `None` for grazing `wo`.
    #[inline]
    fn frame(wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3, Vec3)> {
        if wo.z == 0.0 {
            return None;
        }
        let s = if wo.z < 0.0 { -1.0 } else { 1.0 };
        let (v, l) = (wo * s, wi * s);
        let h = (v + Vec3::new(l.x, l.y, l.z.abs())).normalize_or_zero();
        positive(h.length()).then_some((v, l, h))
    }

    /// ρ(wo, wi) (1/sr) with the parameters `p`.
    #[inline]
    fn eval_at(&self, p: &Point, wo: Vec3, wi: Vec3) -> Spectrum {
        let Some((v, l, h)) = Self::frame(wo, wi) else { return Spectrum::ZERO };
        if l.z == 0.0 {
            return Spectrum::ZERO;
        }
        let (cv, cl) = (v.z, l.z.abs());
        let reflect = l.z > 0.0;
        let t = p.spec_trans;
        let mut value = Spectrum::ZERO;
        if t > 0.0 {
            let f = fresnel_dielectric(v.dot(h), p.eta).r;
            if reflect && faces_agree(h, v, l, false) {
                let distr = disney::ggx(p.roughness, p.anisotropic);
                let tinted = schlick_fresnel(
                    disney::tint(p.base_color) * schlick_r0(p.eta),
                    v.dot(h),
                    p.eta,
                );
                let f_thin = Spectrum::splat(f) * (1.0 - p.spec_tint) + tinted * p.spec_tint;
                value += f_thin * (t * distr.d(h) * distr.g(v, l, h) / (4.0 * cv * cl));
            } else if !reflect && faces_agree(h, v, l, true) {
                let distr = Self::transmission_ggx(p);
                value += p.base_color
                    * (t * (1.0 - f) * distr.d(h) * distr.g(v, l, h) / (4.0 * cv * cl));
            }
        }
        if t < 1.0 {
            if reflect && p.diff_trans < 1.0 {
                let cos_d = h.dot(l);
                let k = disney::diffuse_factor(cv, cl, cos_d, p.roughness, p.flatness);
                let w = (1.0 - t) * (1.0 - p.diff_trans);
                value += p.base_color * (w * FRAC_1_PI * k);
                if p.sheen > 0.0 {
                    value += disney::sheen(p.base_color, p.sheen_tint, cos_d) * (w * p.sheen);
                }
            } else if !reflect && p.diff_trans > 0.0 {
                value += p.base_color * ((1.0 - t) * p.diff_trans * FRAC_1_PI);
            }
        }
        value
    }

    #[inline]
    fn pdf_at(&self, p: &Point, wo: Vec3, wi: Vec3) -> f32 {
        let Some((v, l, h)) = Self::frame(wo, wi) else { return 0.0 };
        let prob = self.lobe_probabilities(p);
        let l_r = Vec3::new(l.x, l.y, l.z.abs());
        let dh_dwi = (1.0 / (4.0 * l_r.dot(h))).abs();
        let mut pdf = 0.0;
        if l.z > 0.0 {
            if faces_agree(h, v, l, false) {
                let distr = disney::ggx(p.roughness, p.anisotropic);
                pdf += prob[SPECULAR_REFLECTION] * distr.pdf(v, h) * dh_dwi;
            }
            pdf += prob[DIFFUSE_REFLECTION] * l.z * FRAC_1_PI;
        } else if l.z < 0.0 {
            if faces_agree(h, v, l, true) {
                pdf += prob[SPECULAR_TRANSMISSION] * Self::transmission_ggx(p).pdf(v, h) * dh_dwi;
            }
            pdf += prob[3] * -l.z * FRAC_1_PI;
        }
        pdf
    }

    /// ρ(wo, wi) in 1/sr, without the cosine.
    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        self.eval_at(&self.at(sp.tex()), wo, wi)
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        self.pdf_at(&self.at(sp.tex()), wo, wi)
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let s = if wo.z < 0.0 { -1.0 } else { 1.0 };
        let v = wo * s;
        let p = self.at(sp.tex());
        let prob = self.lobe_probabilities(&p);
        let l = match disney::choose(&prob, u1) {
            SPECULAR_REFLECTION => {
                let m = disney::ggx(p.roughness, p.anisotropic).sample_normal(v, u2);
                let l = reflect_about(v, m);
                if l.z <= 0.0 || !faces_agree(m, v, l, false) {
                    return None;
                }
                l
            }
            SPECULAR_TRANSMISSION => {
                let m = Self::transmission_ggx(&p).sample_normal(v, u2);
                let r = reflect_about(v, m);
                let l = Vec3::new(r.x, r.y, -r.z);
                if l.z >= 0.0 || !faces_agree(m, v, l, true) {
                    return None;
                }
                l
            }
            DIFFUSE_REFLECTION => warp::square_to_cosine_hemisphere(u2),
            _ => {
                if !positive(prob[3]) {
                    return None;
                }
                -warp::square_to_cosine_hemisphere(u2)
            }
        };
        let wi = l * s;
        let pdf = self.pdf_at(&p, wo, wi);
        if !positive(pdf) {
            return None;
        }
        let weight = self.eval_at(&p, wo, wi) * (wi.z.abs() / pdf);
        Some(BsdfSample { wi, pdf, weight, lobe: Lobe::Smooth, eta: 1.0 })
    }
}

impl Default for PrincipledThin {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    /// The configurations of `scripts/bsdf_table.py principledthin`, in its order.
    fn table_configs() -> Vec<PrincipledThin> {
        let c = |v: f32| Texture::Constant(Spectrum::splat(v));
        let rgb = |r, g, b| Texture::Constant(Spectrum::new(r, g, b));
        let mut v = vec![PrincipledThin::new()];
        let mut p = PrincipledThin::new();
        p.base_color = rgb(0.8, 0.3, 0.1);
        p.roughness = c(0.3);
        p.spec_trans = c(0.6);
        p.eta = c(1.4);
        p.spec_tint = c(0.5);
        p.anisotropic = c(0.4);
        p.sheen = c(0.5);
        p.sheen_tint = c(0.3);
        p.diff_trans = c(0.8);
        p.flatness = c(0.4);
        v.push(p);
        let mut p = PrincipledThin::new();
        p.base_color = rgb(0.2, 0.5, 0.9);
        p.roughness = c(0.6);
        p.diff_trans = c(1.5);
        v.push(p);
        let mut p = PrincipledThin::new();
        p.base_color = rgb(0.5, 0.9, 0.4);
        p.roughness = c(0.1);
        p.spec_trans = c(1.0);
        p.eta = c(1.6);
        p.rates = PrincipledThinSamplingRates {
            specular_reflection: 0.5,
            specular_transmission: 2.0,
            diffuse_reflection: 0.8,
            diffuse_transmission: 0.3,
        };
        v.push(p);
        v
    }

    #[test]
    fn matches_mitsuba_eval_and_pdf() {
        let bsdfs: Vec<Bsdf> = table_configs().into_iter().map(Bsdf::PrincipledThin).collect();
        compare_with_mitsuba_table(&bsdfs, include_str!("testdata/principledthin.csv"));
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let configs: Vec<PrincipledThin> = table_configs()
            .into_iter()
            .map(|mut c| {
                let r = c.roughness.eval_1(TexturePoint::at_uv(Vec2::ZERO)).max(0.3);
                c.roughness = Texture::Constant(Spectrum::splat(r));
                c
            })
            .collect();
        let thetas = [10.0, 60.0, 130.0];
        let tests = configs.len() * thetas.len();
        for (i, c) in configs.into_iter().enumerate() {
            let b = Bsdf::PrincipledThin(c);
            for (j, &theta) in thetas.iter().enumerate() {
                let p = chi2_pvalue_sub(&b, dir(theta, 35.0), 200_000, (i * 10 + j) as u64, 32);
                assert!(p > 0.01 / tests as f64, "config {i} θ={theta}: p-value {p}");
            }
        }
    }

    #[test]
    fn symmetric_sides_and_consistent_samples() {
        for (i, c) in table_configs().into_iter().enumerate() {
            let b = Bsdf::PrincipledThin(c);
            for theta in [0.0, 40.0, 75.0, 140.0] {
                check_sample_consistency(&b, dir(theta, 20.0), i as u64);
            }
            // a sheet: seen from below it is the same as seen from above
            let (wo, wi) = (dir(30.0, 10.0), dir(110.0, 250.0));
            let s = sp();
            assert_eq!(b.eval(&s, wo, wi), b.eval(&s, -wo, -wi));
        }
    }

    /// A white sheet that only transmits diffusely (diff_trans 2, spec_trans 0) sends all
    /// the light through: albedo 1, every sample below.
    #[test]
    fn white_diffuse_transmitter_passes_everything() {
        let mut p = PrincipledThin::new();
        p.base_color = Texture::Constant(Spectrum::ONE);
        p.diff_trans = Texture::Constant(Spectrum::splat(2.0));
        let (m, se) = albedo(&Bsdf::PrincipledThin(p), dir(30.0, 0.0), 50_000, 3);
        assert!((m[0] - 1.0).abs() < 1e-5 && se[0] < 1e-5, "albedo {} ± {}", m[0], se[0]);
    }
}
