//! `bumpmap`: perturbs the shading frame of a nested BSDF by a height field.
//!
//! | parameter | type      | default    | meaning |
//! |-----------|-----------|------------|---------|
//! | (nested)  | texture   | (required) | the height h(u, v) (m; its `eval_1`, i.e. the luminance of a colour bitmap; usually `raw`) |
//! | (nested)  | BSDF      | (required) | the material being bumped |
//! | `scale`   | float     | 1          | multiplies the height gradient |
//! | `flip_invalid_normals`   | boolean | true | mirror bumped normals that face away from the viewer (see `perturbed.rs`) |
//! | `use_shadowing_function` | boolean | true | the bump-terminator shadowing term (see `perturbed.rs`) |
//!
//! Mitsuba 3's construction, ignoring the derivative of the base normal: with (hu, hv) =
//! scale·∇h, the displaced tangents are ∂p'/∂u = ∂p/∂u + n·(hu − n·∂p/∂u) and ∂p'/∂v =
//! ∂p/∂v + n·(hv − n·∂p/∂v) (n the shading normal) and the bumped normal n' = ∂p'/∂u × ∂p'/∂v,
//! flipped onto the geometric normal's side. A constant offset of h changes nothing. The
//! height texture must be differentiable: a `bitmap` (bilinear: exact derivative of the
//! interpolant; nearest: 0) or a constant; like Mitsuba, a `checkerboard` is refused at load.
//! See `perturbed.rs` for the frame built on n' and how the nested BSDF is evaluated in it.

use glam::{Vec2, Vec3};

use super::perturbed::{PerturbOptions, Perturbed};
use super::{Bsdf, BsdfSample, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct BumpMap {
    pub height: Texture,
    pub scale: f32,
    pub nested: Box<Bsdf>,
    pub options: PerturbOptions,
}

impl BumpMap {
    /// Default `scale` of the height gradient (Mitsuba's).
    pub const DEFAULT_SCALE: f32 = 1.0;

    /// `height` must have a gradient ([`Texture::has_gradient`]).
    pub fn new(
        height: Texture,
        scale: f32,
        nested: Bsdf,
        options: PerturbOptions,
    ) -> Result<Self, String> {
        if !height.has_gradient() {
            return Err(
                "the height texture of a bumpmap must be a bitmap (a checkerboard or mesh_attribute has no gradient)"
                    .into(),
            );
        }
        Ok(BumpMap { height, scale, nested: Box::new(nested), options })
    }

    /// The bumped normal n' in the local shading frame (unnormalised).
    pub fn normal(&self, sp: &ShadingPoint) -> Vec3 {
        let g = self.height.eval_1_grad(sp.tex()).unwrap_or(Vec2::ZERO) * self.scale;
        let dpdu = Vec3::new(sp.dpdu.x, sp.dpdu.y, g.x);
        let dpdv = Vec3::new(sp.dpdv.x, sp.dpdv.y, g.y);
        let n = dpdu.cross(dpdv);
        if n.dot(sp.ng) < 0.0 {
            -n
        } else {
            n
        }
    }

    #[inline]
    fn frame(&self, sp: &ShadingPoint, wo: Vec3) -> Perturbed {
        Perturbed::new(sp, self.normal(sp), wo, self.options)
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        self.frame(sp, wo).eval(&self.nested, wo, wi)
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        self.frame(sp, wo).pdf(&self.nested, wo, wi)
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        self.frame(sp, wo).sample(&self.nested, wo, u1, u2)
    }

    pub fn has_smooth_lobe(&self) -> bool {
        self.nested.has_smooth_lobe()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::super::perturbed::shadow_terminator;
    use super::super::{ior, Diffuse, MicrofacetDistribution, MicrofacetKind, RoughConductor};
    use super::*;
    use crate::testkit::bsdf::*;
    use crate::texture::{Bitmap, FilterType, ImageFormat, LoadedImage, UvTransform, WrapMode};

    /// A 4×4 grey height field 0.1·((37 i) mod 11)/11 (bilinear, repeat, raw).
    pub fn heights() -> Texture {
        let data: Vec<f32> = (0..16).map(|i| 0.1 * ((i * 37) % 11) as f32 / 11.0).collect();
        let img = LoadedImage { width: 4, height: 4, channels: 1, data, format: ImageFormat::Exr };
        Texture::Bitmap(
            Bitmap::new(
                "h",
                img,
                true,
                FilterType::Bilinear,
                WrapMode::Repeat,
                UvTransform::IDENTITY,
            )
            .unwrap(),
        )
    }

    /// Mitsuba's `Cu` roughconductor, GGX.
    pub fn copper(alpha: f32) -> Bsdf {
        copper_with(MicrofacetKind::Ggx, alpha)
    }

    pub fn copper_with(kind: MicrofacetKind, alpha: f32) -> Bsdf {
        let (eta, k) = ior::conductor_preset("Cu").unwrap();
        let d = MicrofacetDistribution::new(kind, alpha, alpha, true);
        Bsdf::RoughConductor(RoughConductor::new(d, eta, k, Spectrum::ONE.into()))
    }

    fn bump(scale: f32, nested: Bsdf) -> Bsdf {
        Bsdf::BumpMap(BumpMap::new(heights(), scale, nested, PerturbOptions::default()).unwrap())
    }

    #[test]
    fn matches_mitsuba_values() {
        // mi.load_dict({'type': 'bumpmap', 'scale': 2, bitmap of heights() (raw), 'bsdf':
        // Cu roughconductor GGX α 0.3}).eval/pdf at uv (0.3, 0.6) on a flat frame
        // (dp/du = x, dp/dv = y), Mitsuba 3.9.1 scalar_rgb; eval includes the cosine.
        let b = bump(2.0, copper(0.3));
        let cases = [
            ((30.0, 10.0), (50.0, 200.0), [0.033557598, 0.021859251, 0.018096492], 0.044778746),
            ((0.0, 0.0), (40.0, 100.0), [0.090650007, 0.059014767, 0.048627928], 0.097221948),
            ((70.0, 300.0), (20.0, 90.0), [0.17741863, 0.11564894, 0.095979489], 0.18772991),
        ];
        for (o, i, f, p) in cases {
            let (wo, wi) = (dir(o.0, o.1), dir(i.0, i.1));
            let v = b.eval(&sp(), wo, wi) * wi.z;
            assert!(
                (v - Spectrum::from(f)).abs().max_element() < 2e-4 * f[0].max(1.0),
                "{o:?} {i:?}: {v} vs {f:?}"
            );
            let q = b.pdf(&sp(), wo, wi);
            assert!((q - p).abs() < 1e-4 * p.max(1.0), "{o:?} {i:?}: pdf {q} vs {p}");
        }
    }

    #[test]
    fn normal_follows_the_height_gradient() {
        // h = a·u on a flat patch: n' ∝ (−a, 0, 1)
        let img = LoadedImage {
            width: 2,
            height: 1,
            channels: 1,
            data: vec![0.0, 0.5],
            format: ImageFormat::Exr,
        };
        let ramp = Texture::Bitmap(
            Bitmap::new(
                "r",
                img,
                true,
                FilterType::Bilinear,
                WrapMode::Clamp,
                UvTransform::IDENTITY,
            )
            .unwrap(),
        );
        let b = BumpMap::new(ramp, 2.0, copper(0.3), PerturbOptions::default()).unwrap();
        let s = ShadingPoint::at_uv(Vec2::new(0.5, 0.5));
        // slope of the interpolant: 0.5 per half texel width = 1 per unit u; times scale 2
        let n = b.normal(&s).normalize();
        assert!((n - Vec3::new(-2.0, 0.0, 1.0).normalize()).length() < 1e-5, "{n}");
        // flipped onto the geometric side
        let below = ShadingPoint { ng: -Vec3::Z, ..s };
        assert!(b.normal(&below).z < 0.0);
        // a constant height changes nothing
        let flat = Bsdf::BumpMap(
            BumpMap::new(Spectrum::splat(3.0).into(), 1.0, copper(0.3), PerturbOptions::default())
                .unwrap(),
        );
        let (wo, wi) = (dir(30.0, 10.0), dir(50.0, 200.0));
        let e = flat.eval(&sp(), wo, wi) - copper(0.3).eval(&sp(), wo, wi);
        assert!(e.abs().max_element() < 1e-5, "{e}");
        let check = crate::texture::Checkerboard::new(
            Spectrum::ONE.into(),
            Spectrum::ZERO.into(),
            UvTransform::IDENTITY,
        );
        assert!(BumpMap::new(
            Texture::Checkerboard(check),
            1.0,
            copper(0.3),
            PerturbOptions::default()
        )
        .is_err());
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let mut k = 0;
        for (scale, nested) in [
            (1.0, copper(0.3)),
            (3.0, copper(0.5)),
            (2.0, Bsdf::Diffuse(Diffuse::new(Spectrum::splat(0.7).into()))),
        ] {
            for theta in [0.0, 45.0, 80.0] {
                let p = chi2_pvalue_sub(
                    &bump(scale, nested.clone()),
                    dir(theta, 100.0),
                    200_000,
                    40 + k,
                    32,
                );
                k += 1;
                eprintln!("χ² p-value {p:.3}");
                assert!(p > 0.01 / 9.0, "scale {scale} θ={theta}: p-value {p}");
            }
        }
    }

    #[test]
    fn consistency_adjoint_reciprocity_and_furnace() {
        let b = bump(2.0, copper(0.3));
        let s = sp();
        let Bsdf::BumpMap(bm) = &b else { unreachable!() };
        let n = bm.normal(&s).normalize();
        assert!(n.z < 0.999, "the test needs a tilted normal: {n}");
        for theta in [5.0, 50.0, 85.0] {
            check_sample_consistency(&b, dir(theta, 0.0), 8);
        }
        // ρ(wo, wi)·|cos θi| / (|cos θ'i|·G(wi)) is symmetric (directions facing n: no flip)
        let sym =
            |wo: Vec3, wi: Vec3| b.eval(&s, wo, wi) * wi.z / (wi.dot(n) * shadow_terminator(n, wi));
        for (wo, wi) in [(dir(20.0, 0.0), dir(40.0, 150.0)), (dir(60.0, 30.0), dir(10.0, 250.0))] {
            assert!(wo.dot(n) > 0.0 && wi.dot(n) > 0.0);
            let (f, g) = (sym(wo, wi), sym(wi, wo));
            assert!(
                f.max_element() > 0.0 && (f - g).abs().max_element() <= 1e-4 * f.max_element(),
                "{f} vs {g}"
            );
        }
        for theta in [0.0, 45.0, 80.0, 89.0] {
            for nested in [copper(0.3), Bsdf::Diffuse(Diffuse::new(Spectrum::ONE.into()))] {
                let (m, se) = albedo(&bump(3.0, nested), dir(theta, 45.0), 50_000, 9);
                assert!(
                    m.iter().zip(se).all(|(m, se)| *m <= 1.0 + 5.0 * se),
                    "θ={theta}: {m:?} ± {se:?}"
                );
            }
        }
    }

    #[test]
    fn options_off_give_the_textbook_adapter() {
        let plain = PerturbOptions { flip_invalid_normals: false, use_shadowing_function: false };
        let b = BumpMap::new(heights(), 2.0, copper(0.3), plain).unwrap();
        let s = sp();
        let n = b.normal(&s).normalize();
        let (wo, wi) = (dir(30.0, 10.0), dir(50.0, 200.0));
        let with = bump(2.0, copper(0.3)).eval(&s, wo, wi);
        let without = Bsdf::BumpMap(b).eval(&s, wo, wi);
        let g = shadow_terminator(n, wi);
        assert!(g < 1.0 && (with - without * g).abs().max_element() < 1e-6, "{with} {without} {g}");
    }
}

#[cfg(test)]
mod alpha_texture_tests {
    //! Roughness textures of `roughconductor` and `roughdielectric` (kept here, with the other
    //! texture-driven BSDF tests, to leave those files' own tests untouched).

    use super::super::{MicrofacetDistribution, MicrofacetKind, RoughConductor, RoughDielectric};
    use super::tests::heights;
    use super::*;
    use crate::testkit::bsdf::*;

    #[test]
    fn roughness_is_read_at_the_shading_point() {
        // a roughness between 0.05 and 0.55 that varies over the surface
        let alpha =
            |uv: Vec2| 0.05 + 5.0 * heights().eval_1(crate::texture::TexturePoint::at_uv(uv));
        for uv in [Vec2::new(0.3, 0.6), Vec2::new(0.8, 0.1)] {
            let sp = ShadingPoint::at_uv(uv);
            let a = alpha(uv);
            let d = MicrofacetDistribution::new(MicrofacetKind::Ggx, a, a, true);
            let plain = RoughConductor::new(
                d,
                Spectrum::splat(0.2),
                Spectrum::splat(3.0),
                Spectrum::ONE.into(),
            );
            // a constant texture per test point stands in for the spatially varying one
            let textured = RoughConductor::new(
                MicrofacetDistribution::new(MicrofacetKind::Ggx, 0.1, 0.1, true),
                Spectrum::splat(0.2),
                Spectrum::splat(3.0),
                Spectrum::ONE.into(),
            )
            .with_alpha_textures(Spectrum::splat(a).into(), Spectrum::splat(a).into());
            let (wo, wi) = (dir(30.0, 10.0), dir(50.0, 200.0));
            assert_eq!(
                Bsdf::RoughConductor(plain.clone()).eval(&sp, wo, wi),
                Bsdf::RoughConductor(textured.clone()).eval(&sp, wo, wi)
            );
            assert_eq!(
                Bsdf::RoughConductor(plain).pdf(&sp, wo, wi),
                Bsdf::RoughConductor(textured).pdf(&sp, wo, wi)
            );
            let g = RoughDielectric::new(d, 1.5, Spectrum::ONE.into(), Spectrum::ONE.into());
            let gt = RoughDielectric::new(
                MicrofacetDistribution::new(MicrofacetKind::Ggx, 0.1, 0.1, true),
                1.5,
                Spectrum::ONE.into(),
                Spectrum::ONE.into(),
            )
            .with_alpha_textures(Spectrum::splat(a).into(), Spectrum::splat(a).into());
            let wt = -dir(40.0, 200.0);
            assert_eq!(
                Bsdf::RoughDielectric(g.clone()).eval(&sp, wo, wt),
                Bsdf::RoughDielectric(gt.clone()).eval(&sp, wo, wt)
            );
            assert_eq!(
                Bsdf::RoughDielectric(g).pdf(&sp, wo, wt),
                Bsdf::RoughDielectric(gt).pdf(&sp, wo, wt)
            );
        }
        // a bitmap roughness: sampling still matches the density at the test point
        let b = Bsdf::RoughConductor(
            RoughConductor::new(
                MicrofacetDistribution::new(MicrofacetKind::Beckmann, 0.1, 0.1, true),
                Spectrum::splat(0.2),
                Spectrum::splat(3.0),
                Spectrum::ONE.into(),
            )
            .with_alpha_textures(heights(), heights()),
        );
        let a = heights().eval_1(sp().tex());
        assert!(a > 0.02, "{a}");
        check_sample_consistency(&b, dir(40.0, 0.0), 3);
        let p = chi2_pvalue_sub(&b, dir(40.0, 0.0), 200_000, 77, 32);
        assert!(p > 0.01, "p-value {p}");
    }
}
