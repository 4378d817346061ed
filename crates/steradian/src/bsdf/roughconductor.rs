//! `roughconductor`: a rough metal, Cook–Torrance/Walter microfacet reflection.
//!
//! | parameter              | type     | default    | meaning |
//! |------------------------|----------|------------|---------|
//! | `distribution`         | string   | `beckmann` | `beckmann` or `ggx` |
//! | `alpha`                | float/texture | 0.1   | isotropic roughness α (used directly, no remapping; a texture's `eval_1`, clamped to ≥ 10⁻⁴) |
//! | `alpha_u`, `alpha_v`   | float/texture | —     | anisotropic roughness (both required; exclusive with `alpha`) |
//! | `sample_visible`       | boolean  | true       | sample visible normals |
//! | `material`             | string   | `none`     | conductor preset (see `conductor`) |
//! | `eta`, `k`             | spectrum | 0, 1       | complex IOR (dimensionless) |
//! | `specular_reflectance` | spectrum | 1          | factor on the reflection |
//!
//! ρ(wo, wi) = F(wo·h)·D(h)·G1(wo,h)·G1(wi,h) / (4 cos θo cos θi) with h = (wo + wi)/|wo + wi|,
//! F the conductor Fresnel term per channel (Mitsuba 3's `roughconductor`). One-sided:
//! 0 unless both directions lie above the surface. With η = 0, k = 1 (the default) F = 1,
//! and the only energy lost is the single-scattering shadowing–masking.
//!
//! Sampling draws h from the microfacet distribution (visible normals by default) and
//! mirrors `wo` about it.

use glam::{Vec2, Vec3};

use super::fresnel::{reflect_about, ConductorIor};
use super::microfacet::MicrofacetDistribution;
use super::{positive, BsdfSample, Lobe, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct RoughConductor {
    pub distribution: MicrofacetDistribution,
    /// Spatially varying α_u, α_v (Mitsuba accepts textures); `None` when both are constant,
    /// which `distribution` then holds.
    pub alpha_textures: Option<Box<(Texture, Texture)>>,
    /// η + i·k.
    pub ior: ConductorIor,
    pub specular_reflectance: Texture,
}

impl RoughConductor {
    pub fn new(
        distribution: MicrofacetDistribution,
        eta: Spectrum,
        k: Spectrum,
        specular_reflectance: Texture,
    ) -> Self {
        RoughConductor {
            distribution,
            alpha_textures: None,
            ior: ConductorIor::new(eta, k),
            specular_reflectance,
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

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Spectrum::ZERO;
        }
        let h = (wo + wi).normalize();
        let distr = self.distribution_at(sp);
        let d = distr.d(h);
        if d == 0.0 {
            return Spectrum::ZERO;
        }
        let g = distr.g(wo, wi, h);
        let f = self.ior.fresnel(wo.dot(h));
        self.specular_reflectance.eval(sp.tex()) * f * (d * g / (4.0 * wo.z * wi.z))
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        self.distribution_at(sp).reflection_pdf(wo, wi, (wo + wi).normalize())
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let distr = &self.distribution_at(sp);
        let (m, pdf_m) = distr.sample(wo, u2);
        let wi = reflect_about(wo, m);
        if !positive(pdf_m) || wi.z <= 0.0 {
            return None;
        }
        let w = if distr.sample_visible {
            distr.g1(wi, m)
        } else {
            distr.g(wo, wi, m) * wo.dot(m) / (wo.z * m.z)
        };
        if !positive(w) {
            return None;
        }
        let pdf = pdf_m / (4.0 * wi.dot(m));
        let f = self.ior.fresnel(wo.dot(m));
        let weight = self.specular_reflectance.eval(sp.tex()) * f * w;
        Some(BsdfSample { wi, pdf, weight, lobe: Lobe::Smooth, eta: 1.0 })
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

    fn gold(d: MicrofacetDistribution) -> Bsdf {
        let (eta, k) = super::super::ior::conductor_preset("Au").unwrap();
        Bsdf::RoughConductor(RoughConductor::new(d, eta, k, Spectrum::ONE.into()))
    }

    fn mirror(d: MicrofacetDistribution) -> Bsdf {
        Bsdf::RoughConductor(RoughConductor::new(
            d,
            Spectrum::ZERO,
            Spectrum::ONE,
            Spectrum::ONE.into(),
        ))
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        assert_chi2_over_grid(&configs(), &[0.0, 30.0, 60.0, 80.0], gold);
    }

    #[test]
    fn weight_consistency_and_reciprocity() {
        for (i, d) in configs().into_iter().enumerate() {
            let b = gold(d);
            for theta in [0.0, 40.0, 75.0] {
                check_sample_consistency(&b, dir(theta, 20.0), i as u64);
            }
            let s = sp();
            for (a, c) in [
                (dir(20.0, 10.0), dir(50.0, 200.0)),
                (dir(70.0, 0.0), dir(65.0, 170.0)),
                (dir(5.0, 0.0), dir(10.0, 150.0)),
            ] {
                let (x, y) = (b.eval(&s, a, c), b.eval(&s, c, a));
                assert!(
                    (x - y).abs().max_element() <= 1e-5 * x.max_element().max(1e-6),
                    "{x:?} vs {y:?}"
                );
            }
            assert_eq!(b.eval(&s, dir(30.0, 0.0), dir(100.0, 0.0)), Spectrum::ZERO);
            assert_eq!(b.eval(&s, dir(100.0, 0.0), dir(30.0, 0.0)), Spectrum::ZERO);
            assert!(b.sample(&s, dir(100.0, 0.0), 0.5, Vec2::splat(0.3)).is_none());
        }
    }

    #[test]
    fn white_furnace_loses_only_shadowing() {
        for d in configs() {
            for theta in [0.0, 30.0, 60.0, 80.0] {
                let (m, se) = albedo(&mirror(d), dir(theta, 10.0), 40_000, 5);
                assert!(
                    m[0] <= 1.0 + 4.0 * se[0] + 1e-6,
                    "{d:?} θ={theta}: albedo {} ± {}",
                    m[0],
                    se[0]
                );
                // smooth-ish surfaces at moderate angles keep nearly everything
                if d.alpha_u <= 0.05 && d.alpha_v <= 0.05 && theta <= 60.0 {
                    assert!(m[0] > 0.97, "{d:?} θ={theta}: albedo {}", m[0]);
                }
                let (g, gse) = albedo(&gold(d), dir(theta, 10.0), 20_000, 6);
                assert!(g.iter().zip(gse).all(|(x, s)| *x <= 1.0 + 4.0 * s + 1e-6));
            }
        }
    }
}
