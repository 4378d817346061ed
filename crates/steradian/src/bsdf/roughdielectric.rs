//! `roughdielectric`: a rough interface between two dielectrics (frosted glass), after
//! Walter et al. 2007 as implemented in Mitsuba 3.
//!
//! | parameter                | type          | default    | meaning |
//! |--------------------------|---------------|------------|---------|
//! | `distribution`           | string        | `beckmann` | `beckmann` or `ggx` |
//! | `alpha`                  | float         | 0.1        | isotropic roughness α |
//! | `alpha_u`, `alpha_v`     | float         | —          | anisotropic roughness (exclusive with `alpha`) |
//! | `sample_visible`         | boolean       | true       | sample visible normals |
//! | `int_ior`, `ext_ior`     | float or name | `bk7`, `air` | IORs inside / outside (must differ) |
//! | `specular_reflectance`   | spectrum      | 1          | factor on reflection |
//! | `specular_transmittance` | spectrum      | 1          | factor on transmission |
//!
//! With η the relative IOR seen from `wo` (int/ext above the surface, its inverse below):
//! - reflection (wo, wi on one side): ρ = F·D(h)·G / (4 |cos θo| |cos θi|), h ∝ wo + wi;
//! - transmission: ρ = (1/η²)·(1 − F)·D(h)·G·η²·|wo·h| |wi·h| / (|cos θo| |cos θi| (wo·h + η wi·h)²),
//!   h ∝ wo + η wi. The leading 1/η² is the radiance compression across the interface, so
//!   ρ(wo,wi)/η_o² = ρ(wi,wo)/η_i² (η_o, η_i the absolute IORs on each direction's side).
//!
//! F = F(wo·h) is the exact dielectric Fresnel term, G Smith's separable shadowing–masking.
//! Sampling draws h (visible normals by default; otherwise D·cos with Walter's roughness
//! widening 1.2 − 0.2·√|cos θo|) and reflects with probability F, refracts otherwise; the
//! sample's `eta` is η_t/η_i of the crossing.

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, reflect_about, refract_about};
use super::microfacet::MicrofacetDistribution;
use super::{positive, BsdfSample, Lobe, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct RoughDielectric {
    pub distribution: MicrofacetDistribution,
    /// Spatially varying α_u, α_v (Mitsuba accepts textures); `None` when both are constant,
    /// which `distribution` then holds.
    pub alpha_textures: Option<Box<(Texture, Texture)>>,
    /// Relative IOR int_ior/ext_ior (≠ 1).
    pub eta: f32,
    pub specular_reflectance: Texture,
    pub specular_transmittance: Texture,
}

#[inline]
fn sign(x: f32) -> f32 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

impl RoughDielectric {
    pub fn new(
        distribution: MicrofacetDistribution,
        eta: f32,
        specular_reflectance: Texture,
        specular_transmittance: Texture,
    ) -> Self {
        RoughDielectric {
            distribution,
            alpha_textures: None,
            eta,
            specular_reflectance,
            specular_transmittance,
        }
    }

    /// Spatially varying roughness: α_u, α_v read from textures (their `eval_1`).
    pub fn with_alpha_textures(mut self, alpha_u: Texture, alpha_v: Texture) -> Self {
        self.alpha_textures = Some(Box::new((alpha_u, alpha_v)));
        self
    }

    /// The microfacet distribution at the shading point.
    #[inline]
    fn distribution_at(&self, sp: &ShadingPoint) -> MicrofacetDistribution {
        self.distribution.with_alpha_at(self.alpha_textures.as_deref(), sp.tex())
    }

    /// The distribution normals are drawn from for viewing cosine `cos_o`.
    fn sampling_distribution(distr: MicrofacetDistribution, cos_o: f32) -> MicrofacetDistribution {
        if distr.sample_visible {
            distr
        } else {
            distr.scaled(1.2 - 0.2 * cos_o.abs().sqrt())
        }
    }

    /// The microfacet normal linking wo and wi (upper hemisphere), whether it is a
    /// reflection, and η seen from wo.
    fn half_vector(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, bool, f32)> {
        let reflect = wo.z * wi.z > 0.0;
        let eta = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
        let h = wo + wi * if reflect { 1.0 } else { eta };
        let len = h.length();
        if !positive(len) {
            return None;
        }
        let h = h / len;
        Some((h * sign(h.z), reflect, eta))
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if wo.z == 0.0 || wi.z == 0.0 {
            return Spectrum::ZERO;
        }
        let Some((m, reflect, eta)) = self.half_vector(wo, wi) else { return Spectrum::ZERO };
        let distr = &self.distribution_at(sp);
        let d = distr.d(m);
        let g = distr.g(wo, wi, m);
        if !positive(d * g) {
            return Spectrum::ZERO;
        }
        let f = fresnel_dielectric(wo.dot(m), self.eta).r;
        if reflect {
            self.specular_reflectance.eval(sp.tex()) * (f * d * g / (4.0 * wo.z.abs() * wi.z.abs()))
        } else {
            let (om, im) = (wo.dot(m), wi.dot(m));
            let denom = om + eta * im;
            // (1/η²)·η² cancel: the radiance-scaled BTDF
            let v = ((1.0 - f) * d * g * om * im / (wo.z * wi.z * denom * denom)).abs();
            self.specular_transmittance.eval(sp.tex()) * v
        }
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let Some((m, reflect, eta)) = self.half_vector(wo, wi) else { return 0.0 };
        let (om, im) = (wo.dot(m), wi.dot(m));
        if om * wo.z <= 0.0 || im * wi.z <= 0.0 {
            return 0.0;
        }
        let dwh_dwi =
            if reflect { 1.0 / (4.0 * im) } else { eta * eta * im / (om + eta * im).powi(2) };
        let f = fresnel_dielectric(om, self.eta).r;
        let prob = Self::sampling_distribution(self.distribution_at(sp), wo.z)
            .pdf(wo * sign(wo.z), m)
            * if reflect { f } else { 1.0 - f };
        (prob * dwh_dwi).abs()
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let sdistr = Self::sampling_distribution(self.distribution_at(sp), wo.z);
        let (m, pdf_m) = sdistr.sample(wo * sign(wo.z), u2);
        if !positive(pdf_m) {
            return None;
        }
        let om = wo.dot(m);
        let fr = fresnel_dielectric(om, self.eta);
        let distr = &self.distribution_at(sp);
        let (wi, mut weight, pdf, eta) = if u1 <= fr.r {
            let wi = reflect_about(wo, m);
            if wi.z * wo.z <= 0.0 {
                return None;
            }
            (
                wi,
                self.specular_reflectance.eval(sp.tex()),
                pdf_m * fr.r / (4.0 * wi.dot(m)).abs(),
                1.0,
            )
        } else {
            let wi = refract_about(wo, m, fr.cos_theta_t, fr.eta_ti);
            if wi.z * wo.z >= 0.0 {
                return None;
            }
            let im = wi.dot(m);
            let dwh = fr.eta_it * fr.eta_it * im / (om + fr.eta_it * im).powi(2);
            let w = self.specular_transmittance.eval(sp.tex()) * (fr.eta_ti * fr.eta_ti);
            (wi, w, pdf_m * (1.0 - fr.r) * dwh.abs(), fr.eta_it)
        };
        let g = if distr.sample_visible {
            distr.g1(wi, m)
        } else {
            // D/D_sample corrects for the widened sampling roughness, so that the weight is
            // exactly ρ·|cos θi|/pdf (Mitsuba 3 omits this ratio).
            distr.g(wo, wi, m) * om / (wo.z * m.z) * distr.d(m) / sdistr.d(m)
        };
        if !positive(g) || !positive(pdf) {
            return None;
        }
        weight *= g;
        Some(BsdfSample { wi, pdf, weight, lobe: Lobe::Smooth, eta })
    }
}

#[cfg(test)]
mod tests {
    use super::super::Bsdf;
    use super::*;
    use crate::testkit::bsdf::*;

    fn configs() -> Vec<MicrofacetDistribution> {
        microfacet_grid(&ALPHAS)
    }

    const ETA: f32 = 1.5046 / 1.000277;

    fn glass(d: MicrofacetDistribution) -> Bsdf {
        Bsdf::RoughDielectric(RoughDielectric::new(
            d,
            ETA,
            Spectrum::ONE.into(),
            Spectrum::ONE.into(),
        ))
    }

    fn wo_at(theta: f32, inside: bool) -> Vec3 {
        let mut w = dir(theta, 35.0);
        if inside {
            w.z = -w.z;
        }
        w
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let cfg = configs();
        let tests = cfg.len() * 4 * 2;
        for (i, d) in cfg.into_iter().enumerate() {
            for (j, theta) in [0.0, 30.0, 60.0, 80.0].into_iter().enumerate() {
                for inside in [false, true] {
                    let p = chi2_pvalue_sub(
                        &glass(d),
                        wo_at(theta, inside),
                        200_000,
                        (i * 100 + j * 2 + inside as usize) as u64,
                        chi2_sub(&d),
                    );
                    assert!(
                        p > 0.01 / tests as f64,
                        "{d:?} θ={theta} inside={inside}: p-value {p}"
                    );
                }
            }
        }
    }

    #[test]
    fn weight_consistency() {
        for (i, d) in configs().into_iter().enumerate() {
            for theta in [0.0, 40.0, 75.0] {
                for inside in [false, true] {
                    check_sample_consistency(&glass(d), wo_at(theta, inside), i as u64);
                }
            }
        }
    }

    #[test]
    fn generalised_reciprocity() {
        let s = sp();
        for d in configs() {
            let b = glass(d);
            let pairs = [
                (dir(20.0, 10.0), dir(50.0, 200.0)),
                (dir(40.0, 0.0), dir(160.0, 170.0)),
                (dir(10.0, 30.0), dir(150.0, 200.0)),
                (dir(130.0, 0.0), dir(170.0, 150.0)),
            ];
            let mut nonzero = 0;
            for (a, c) in pairs {
                // absolute IOR on each direction's side (exterior 1, interior η)
                let n = |w: Vec3| if w.z > 0.0 { 1.0 } else { ETA };
                let (x, y) = (b.eval(&s, a, c) / (n(a) * n(a)), b.eval(&s, c, a) / (n(c) * n(c)));
                nonzero += (x.max_element() > 0.0) as usize;
                assert!(
                    (x - y).abs().max_element() <= 1e-4 * x.max_element(),
                    "{d:?}: {x:?} vs {y:?}"
                );
            }
            assert!(nonzero >= 2, "{d:?}: only {nonzero} non-zero pairs");
        }
    }

    #[test]
    fn white_furnace() {
        // energy with the 1/η² radiance factor undone (weight·η²) is ≤ 1 and close to 1 for
        // smooth surfaces; the raw albedo from outside is < 1 (transmitted radiance shrinks)
        for d in configs() {
            for theta in [0.0, 30.0, 60.0, 80.0] {
                for inside in [false, true] {
                    let b = glass(d);
                    let wo = wo_at(theta, inside);
                    let mut rng = crate::sampling::Pcg32::new(4, 4);
                    let n = 40_000;
                    let (mut s1, mut s2) = (0.0f64, 0.0f64);
                    for _ in 0..n {
                        let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
                        if let Some(smp) = b.sample(&sp(), wo, rng.next_f32(), u2) {
                            let v = (smp.weight.x * smp.eta * smp.eta) as f64;
                            s1 += v;
                            s2 += v * v;
                        }
                    }
                    let m = s1 / n as f64;
                    let se = ((s2 / n as f64 - m * m).max(0.0) / (n as f64 - 1.0)).sqrt();
                    assert!(
                        m <= 1.0 + 4.0 * se + 1e-6,
                        "{d:?} θ={theta} inside={inside}: {m} ± {se}"
                    );
                    if d.alpha_u <= 0.05 && d.alpha_v <= 0.05 && theta <= 30.0 {
                        assert!(m > 0.97, "{d:?} θ={theta} inside={inside}: {m}");
                    }
                }
            }
        }
    }
}
