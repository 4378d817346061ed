//! `principled`: Mitsuba 3's Disney-based "principled" BSDF (Burley 2012, 2015), an artist's
//! material that blends a retro-reflective diffuse base, sheen, a metallic/dielectric GGX
//! specular lobe, a GGX specular transmission and a GTR1 clearcoat.
//!
//! | parameter                            | type             | default | meaning |
//! |--------------------------------------|------------------|---------|---------|
//! | `base_color`                         | spectrum/texture | 0.5     | colour of the diffuse base and of metals |
//! | `roughness`                          | float/texture    | 0.5     | r: GGX α = max(0.001, r²) |
//! | `anisotropic`                        | float/texture    | 0       | a: α_u = α/√(1 − 0.9a), α_v = α·√(1 − 0.9a) |
//! | `metallic`                           | float/texture    | 0       | m: blend towards a Schlick metal of colour `base_color` |
//! | `spec_trans`                         | float/texture    | 0       | t: share of the dielectric that transmits (glass) |
//! | `eta`                                | float            | from `specular` | relative IOR of the dielectric |
//! | `specular`                           | float            | 0.5     | s: η = 2/(1 − √(0.08 s)) − 1 (1.5 for 0.5); exclusive with `eta` |
//! | `spec_tint`                          | float/texture    | 0       | tints the dielectric reflection towards the base hue |
//! | `sheen`, `sheen_tint`                | float/texture    | 0, 0    | grazing sheen and its tint |
//! | `flatness`                           | float/texture    | 0       | blend of the diffuse towards fake subsurface |
//! | `clearcoat`, `clearcoat_gloss`       | float/texture    | 0, 0    | GTR1 coat (α 0.1 → 0.001 with gloss) |
//! | `diffuse_reflectance_sampling_rate`  | float            | 1       | relative rate of the cosine lobe in sampling |
//! | `main_specular_sampling_rate`        | float            | 1       | relative rate of the GGX lobes in sampling |
//! | `clearcoat_sampling_rate`            | float            | 1       | relative rate of the clearcoat in sampling |
//!
//! With the weights b = (1 − m)(1 − t) of the diffuse base and τ = (1 − m) t of the
//! transmission, h the (generalised) half vector and F the exact dielectric Fresnel term:
//! - specular reflection F_p D G/(4|cos θo cos θi|), F_p = (1 − m)(1 − tint) F + m·Schlick(base)
//!   + (1 − m)·tint·Schlick(hue·R0(η)) seen from outside, τF from inside;
//! - transmission √base·τ(1 − F) D G |wo·h||wi·h| /(|cos θo cos θi| (wo·h + η wi·h)²), the
//!   radiance compression included (steradian traces radiance);
//! - clearcoat ¼·clearcoat·Schlick(0.04) D_GTR1 G(α 0.25) (Mitsuba's form: it has no
//!   1/(4 cos θo cos θi));
//! - diffuse b·base/π · [`disney::diffuse_factor`] and sheen sheen·(1 − m)·[`disney::sheen`],
//!   above the surface only.
//!
//! `wo` below the surface (inside glass) sees only the dielectric. Sampling picks diffuse,
//! clearcoat, transmission or reflection with Mitsuba's probabilities (the sampling rates
//! times b, ¼·clearcoat, τ(1 − F), 1 − τ(1 − F) outside; 1 − F and F inside, F at the
//! sampled normal), and the density is the mixture of all four. Where steradian differs on
//! purpose: sheen is added wherever its own conditions hold, as in Mitsuba's vectorised
//! (`llvm`/`cuda`) variants; its scalar variants skip it where the diffuse weight b is 0.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::disney::{self, faces_agree, schlick_fresnel, schlick_r0, Gtr1};
use super::fresnel::{fresnel_dielectric, reflect_about, refract_about};
use super::{positive, BsdfSample, Lobe, ShadingPoint};
use crate::sampling::warp;
use crate::texture::{Texture, TexturePoint};
use crate::Spectrum;

/// The relative rates of the lobes in sampling (Mitsuba's `*_sampling_rate`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledSamplingRates {
    pub diffuse: f32,
    pub specular: f32,
    pub clearcoat: f32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Principled {
    pub base_color: Texture,
    pub roughness: Texture,
    pub anisotropic: Texture,
    pub metallic: Texture,
    pub spec_trans: Texture,
    pub spec_tint: Texture,
    pub sheen: Texture,
    pub sheen_tint: Texture,
    pub flatness: Texture,
    pub clearcoat: Texture,
    pub clearcoat_gloss: Texture,
    /// Relative IOR of the dielectric part (dimensionless).
    pub eta: f32,
    pub rates: PrincipledSamplingRates,
}

/// The parameters read at one shading point.
struct Point {
    base_color: Spectrum,
    roughness: f32,
    anisotropic: f32,
    metallic: f32,
    spec_tint: f32,
    sheen: f32,
    sheen_tint: f32,
    flatness: f32,
    clearcoat: f32,
    clearcoat_gloss: f32,
    /// Weight of the diffuse base, (1 − m)(1 − t).
    brdf: f32,
    /// Weight of the specular transmission, (1 − m) t.
    btdf: f32,
}

/// The lobes, in Mitsuba's sampling order.
const DIFFUSE: usize = 0;
const CLEARCOAT: usize = 1;
const TRANSMISSION: usize = 2;
const REFLECTION: usize = 3;

impl Principled {
    pub const DEFAULT_BASE_COLOR: f32 = 0.5;
    pub const DEFAULT_ROUGHNESS: f32 = 0.5;
    /// Default `specular` (gives η = 1.5).
    pub const DEFAULT_SPECULAR: f32 = 0.5;
    /// Default of `anisotropic`, `metallic`, `spec_trans`, `spec_tint`, `sheen`,
    /// `sheen_tint`, `flatness`, `clearcoat` and `clearcoat_gloss`.
    pub const DEFAULT_WEIGHT: f32 = 0.0;
    pub const DEFAULT_SAMPLING_RATES: PrincipledSamplingRates =
        PrincipledSamplingRates { diffuse: 1.0, specular: 1.0, clearcoat: 1.0 };

    /// Mitsuba's map from `specular` s to the relative IOR: 2/(1 − √(0.08 s)) − 1.
    pub fn eta_from_specular(specular: f32) -> f32 {
        2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
    }

    /// The material with every parameter at Mitsuba's default.
    pub fn new() -> Self {
        let c = |v: f32| Texture::Constant(Spectrum::splat(v));
        let w = c(Self::DEFAULT_WEIGHT);
        Principled {
            base_color: c(Self::DEFAULT_BASE_COLOR),
            roughness: c(Self::DEFAULT_ROUGHNESS),
            anisotropic: w.clone(),
            metallic: w.clone(),
            spec_trans: w.clone(),
            spec_tint: w.clone(),
            sheen: w.clone(),
            sheen_tint: w.clone(),
            flatness: w.clone(),
            clearcoat: w.clone(),
            clearcoat_gloss: w,
            eta: Self::eta_from_specular(Self::DEFAULT_SPECULAR),
            rates: Self::DEFAULT_SAMPLING_RATES,
        }
    }

    #[inline]
    fn at(&self, p: TexturePoint) -> Point {
        let metallic = self.metallic.eval_1(p);
        let spec_trans = self.spec_trans.eval_1(p);
        Point {
            base_color: self.base_color.eval(p),
            roughness: self.roughness.eval_1(p),
            anisotropic: self.anisotropic.eval_1(p),
            metallic,
            spec_tint: self.spec_tint.eval_1(p),
            sheen: self.sheen.eval_1(p),
            sheen_tint: self.sheen_tint.eval_1(p),
            flatness: self.flatness.eval_1(p),
            clearcoat: self.clearcoat.eval_1(p),
            clearcoat_gloss: self.clearcoat_gloss.eval_1(p),
            brdf: (1.0 - metallic) * (1.0 - spec_trans),
            btdf: (1.0 - metallic) * spec_trans,
        }
    }

    /// The lobe probabilities for `wo` on the `front` side, `f` the dielectric Fresnel term.
    #[inline]
    fn lobe_probabilities(&self, p: &Point, front: bool, f: f32) -> [f32; 4] {
        let r = &self.rates;
        if front {
            disney::normalised([
                p.brdf * r.diffuse,
                0.25 * p.clearcoat * r.clearcoat,
                r.specular * p.btdf * (1.0 - f),
                r.specular * (1.0 - p.btdf * (1.0 - f)),
            ])
        } else if p.btdf > 0.0 {
            disney::normalised([0.0, 0.0, 1.0 - f, f])
        } else {
            // no transmission: nothing to see from inside (Mitsuba's density is the
            // reflection's alone there)
            [0.0, 0.0, 0.0, 1.0]
        }
    }

    /// The half vector of (wo, wi), turned to the upper hemisphere: wo + wi for a reflection,
    /// wo + η wi for a transmission (η seen from wo). `None` when it is degenerate.
    #[inline]
    fn half_vector(&self, wo: Vec3, wi: Vec3, reflect: bool) -> Option<Vec3> {
        let eta_path = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
        let h = wo + wi * if reflect { 1.0 } else { eta_path };
        let len = h.length();
        if !positive(len) {
            return None;
        }
        Some(if h.z < 0.0 { -h / len } else { h / len })
    }

    /// The Fresnel factor of the main specular reflection at cos θ = wo·h.
    #[inline]
    fn specular_fresnel(
        &self,
        p: &Point,
        f_dielectric: f32,
        cos_theta: f32,
        front: bool,
    ) -> Spectrum {
        if !front {
            return Spectrum::splat(p.btdf * f_dielectric);
        }
        let eta_it = if cos_theta >= 0.0 { self.eta } else { 1.0 / self.eta };
        let metal = schlick_fresnel(p.base_color, cos_theta, self.eta) * p.metallic;
        let tinted =
            schlick_fresnel(disney::tint(p.base_color) * schlick_r0(eta_it), cos_theta, self.eta)
                * ((1.0 - p.metallic) * p.spec_tint);
        Spectrum::splat((1.0 - p.metallic) * (1.0 - p.spec_tint) * f_dielectric) + metal + tinted
    }

    #[inline]
    /// ρ(wo, wi) (1/sr) with the parameters `p`.
    fn eval_at(&self, p: &Point, wo: Vec3, wi: Vec3) -> Spectrum {
        let (cos_o, cos_i) = (wo.z, wi.z);
        if cos_o == 0.0 || cos_i == 0.0 {
            return Spectrum::ZERO;
        }
        let reflect = cos_o * cos_i > 0.0;
        let front = cos_o > 0.0;
        let Some(h) = self.half_vector(wo, wi, reflect) else { return Spectrum::ZERO };
        let (oh, ih) = (wo.dot(h), wi.dot(h));
        let f = fresnel_dielectric(oh, self.eta).r;
        let distr = disney::ggx(p.roughness, p.anisotropic);
        let (d, g) = (distr.d(h), distr.g(wo, wi, h));
        let (ao, ai) = (cos_o.abs(), cos_i.abs());
        let mut value = Spectrum::ZERO;
        if reflect && faces_agree(h, wo, wi, false) {
            if f > 0.0 {
                value += self.specular_fresnel(p, f, oh, front) * (d * g / (4.0 * ao * ai));
            }
            if front && p.clearcoat > 0.0 {
                let f_cc = schlick_fresnel(Spectrum::splat(0.04), oh, self.eta).x;
                let d_cc = Gtr1::clearcoat(p.clearcoat_gloss).d(h);
                value += Spectrum::splat(
                    0.25 * p.clearcoat * f_cc * d_cc * disney::clearcoat_g(wo, wi, h),
                );
            }
        }
        if !reflect && p.btdf > 0.0 && f < 1.0 && faces_agree(h, wo, wi, true) {
            let eta_path = if front { self.eta } else { 1.0 / self.eta };
            let denom = oh + eta_path * ih;
            // the radiance compression 1/η² cancels the Jacobian's η²
            let t = ((1.0 - f) * d * g * oh * ih / (ao * ai * denom * denom)).abs();
            value += p.base_color.max(Spectrum::ZERO).powf(0.5) * (p.btdf * t);
        }
        if front && reflect {
            let cos_d = ih;
            if p.brdf > 0.0 {
                let k = disney::diffuse_factor(ao, ai, cos_d, p.roughness, p.flatness);
                value += p.base_color * (p.brdf * FRAC_1_PI * k);
            }
            if p.sheen > 0.0 && 1.0 - p.metallic > 0.0 {
                value += disney::sheen(p.base_color, p.sheen_tint, cos_d)
                    * (p.sheen * (1.0 - p.metallic));
            }
        }
        value
    }

    #[inline]
    fn pdf_at(&self, p: &Point, wo: Vec3, wi: Vec3) -> f32 {
        let (cos_o, cos_i) = (wo.z, wi.z);
        if cos_o == 0.0 || cos_i == 0.0 {
            return 0.0;
        }
        let reflect = cos_o * cos_i > 0.0;
        let front = cos_o > 0.0;
        let Some(h) = self.half_vector(wo, wi, reflect) else { return 0.0 };
        let (oh, ih) = (wo.dot(h), wi.dot(h));
        let f = fresnel_dielectric(oh, self.eta).r;
        let prob = self.lobe_probabilities(p, front, f);
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let dh_dwi = if reflect {
            1.0 / (4.0 * ih)
        } else {
            eta_path * eta_path * ih / (oh + eta_path * ih).powi(2)
        }
        .abs();
        let distr = disney::ggx(p.roughness, p.anisotropic);
        let side = if front { wo } else { -wo };
        let mut pdf = 0.0;
        if reflect {
            if faces_agree(h, wo, wi, false) {
                pdf += prob[REFLECTION] * distr.pdf(side, h) * dh_dwi;
                pdf += prob[CLEARCOAT] * Gtr1::clearcoat(p.clearcoat_gloss).pdf(h) * dh_dwi;
            }
            pdf += prob[DIFFUSE] * cos_i.abs() * FRAC_1_PI;
        } else if faces_agree(h, wo, wi, true) {
            pdf += prob[TRANSMISSION] * distr.pdf(side, h) * dh_dwi;
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
        let cos_o = wo.z;
        if cos_o == 0.0 {
            return None;
        }
        let p = self.at(sp.tex());
        let front = cos_o > 0.0;
        if !front && !positive(p.btdf) {
            return None;
        }
        let side = if front { wo } else { -wo };
        let m = disney::ggx(p.roughness, p.anisotropic).sample_normal(side, u2);
        let fr = fresnel_dielectric(wo.dot(m), self.eta);
        let prob = self.lobe_probabilities(&p, front, fr.r);
        let reflected = |m: Vec3| {
            let wi = reflect_about(wo, m);
            (cos_o * wi.z > 0.0 && faces_agree(m, wo, wi, false)).then_some((wi, 1.0))
        };
        let (wi, eta) = match disney::choose(&prob, u1) {
            DIFFUSE => (warp::square_to_cosine_hemisphere(u2), 1.0),
            CLEARCOAT => reflected(Gtr1::clearcoat(p.clearcoat_gloss).sample(u2))?,
            TRANSMISSION => {
                let wi = refract_about(wo, m, fr.cos_theta_t, fr.eta_ti);
                if cos_o * wi.z >= 0.0 || !faces_agree(m, wo, wi, true) {
                    return None;
                }
                (wi, fr.eta_it)
            }
            _ => reflected(m)?,
        };
        let pdf = self.pdf_at(&p, wo, wi);
        if !positive(pdf) {
            return None;
        }
        let weight = self.eval_at(&p, wo, wi) * (wi.z.abs() / pdf);
        Some(BsdfSample { wi, pdf, weight, lobe: Lobe::Smooth, eta })
    }
}

impl Default for Principled {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    /// The configurations of `scripts/bsdf_table.py principled`, in its order.
    pub(super) fn table_configs() -> Vec<Principled> {
        let c = |v: f32| Texture::Constant(Spectrum::splat(v));
        let rgb = |r, g, b| Texture::Constant(Spectrum::new(r, g, b));
        let mut v = vec![Principled::new()];
        let mut p = Principled::new();
        p.base_color = rgb(0.8, 0.3, 0.1);
        p.roughness = c(0.3);
        p.metallic = c(0.7);
        p.eta = Principled::eta_from_specular(0.6);
        p.spec_tint = c(0.4);
        p.anisotropic = c(0.5);
        p.sheen = c(0.3);
        p.sheen_tint = c(0.2);
        p.clearcoat = c(0.6);
        p.clearcoat_gloss = c(0.3);
        p.spec_trans = c(0.4);
        v.push(p);
        let mut p = Principled::new();
        p.base_color = rgb(0.2, 0.5, 0.9);
        p.roughness = c(0.15);
        p.spec_trans = c(0.9);
        p.eta = 1.33;
        v.push(p);
        let mut p = Principled::new();
        p.base_color = rgb(0.9, 0.9, 0.2);
        p.roughness = c(0.8);
        p.flatness = c(0.6);
        p.sheen = c(1.0);
        p.sheen_tint = c(0.7);
        v.push(p);
        let mut p = Principled::new();
        p.base_color = rgb(0.6, 0.6, 0.6);
        p.roughness = c(0.05);
        p.clearcoat = c(1.0);
        p.clearcoat_gloss = c(0.9);
        p.rates = PrincipledSamplingRates { diffuse: 0.7, specular: 0.5, clearcoat: 2.0 };
        v.push(p);
        let mut p = Principled::new();
        p.base_color = rgb(0.95, 0.64, 0.54);
        p.roughness = c(0.4);
        p.metallic = c(1.0);
        p.anisotropic = c(0.9);
        v.push(p);
        v
    }

    #[test]
    fn matches_mitsuba_eval_and_pdf() {
        let bsdfs: Vec<Bsdf> = table_configs().into_iter().map(Bsdf::Principled).collect();
        compare_with_mitsuba_table(&bsdfs, include_str!("testdata/principled.csv"));
    }

    fn grid_configs() -> Vec<Bsdf> {
        table_configs().into_iter().map(Bsdf::Principled).collect()
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        // the table's configurations with lobes broad enough for a (θ, φ) histogram
        let configs: Vec<Principled> = table_configs()
            .into_iter()
            .map(|mut c| {
                let r = c.roughness.eval_1(TexturePoint::at_uv(Vec2::ZERO)).max(0.3);
                let g = c.clearcoat_gloss.eval_1(TexturePoint::at_uv(Vec2::ZERO)).min(0.3);
                c.roughness = Texture::Constant(Spectrum::splat(r));
                c.clearcoat_gloss = Texture::Constant(Spectrum::splat(g));
                c
            })
            .collect();
        let tests = configs.len() * 3;
        for (i, c) in configs.into_iter().enumerate() {
            // from inside only where there is a transmission to see
            let inside = c.spec_trans.eval_1(TexturePoint::at_uv(Vec2::ZERO)) > 0.0;
            let b = &Bsdf::Principled(c);
            let thetas: &[f32] = if inside { &[10.0, 60.0, 150.0] } else { &[10.0, 60.0] };
            for (j, &theta) in thetas.iter().enumerate() {
                // 32² pdf evaluations per cell: the lobes of α 0.09 need them for exact expected counts
                let p = chi2_pvalue_sub(b, dir(theta, 35.0), 200_000, (i * 10 + j) as u64, 32);
                assert!(p > 0.01 / tests as f64, "config {i} θ={theta}: p-value {p}");
            }
        }
    }

    #[test]
    fn sample_weights_and_pdfs_are_consistent() {
        for (i, b) in grid_configs().iter().enumerate() {
            for theta in [0.0, 40.0, 75.0, 120.0] {
                check_sample_consistency(b, dir(theta, 20.0), i as u64);
            }
        }
    }

    /// A black base under a nearly smooth dielectric (r = 0.001) reflects the Fresnel
    /// reflectance F(θ) of η = 1.5 and nothing else: 0.04 at normal incidence.
    #[test]
    fn smooth_dielectric_limit_reflects_fresnel() {
        let mut p = Principled::new();
        p.base_color = Texture::Constant(Spectrum::ZERO);
        p.roughness = Texture::Constant(Spectrum::splat(0.001));
        let b = Bsdf::Principled(p);
        for theta in [0.0f32, 60.0] {
            let (m, se) = albedo(&b, dir(theta, 0.0), 100_000, 5);
            let f = fresnel_dielectric(theta.to_radians().cos(), 1.5).r as f64;
            assert!(
                (m[0] - f).abs() < 4.0 * se[0] + 1e-3,
                "θ={theta}: {} ± {} vs {f}",
                m[0],
                se[0]
            );
        }
    }
}
