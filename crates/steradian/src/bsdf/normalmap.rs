//! `normalmap`: replaces the shading normal of a nested BSDF by one read from a texture.
//!
//! | parameter   | type    | default    | meaning |
//! |-------------|---------|------------|---------|
//! | `normalmap` | texture | (required) | RGB c ∈ [0, 1]³ encoding the normal n' = normalize(2c − 1) in the local shading frame (give the bitmap `raw`) |
//! | (nested)    | BSDF    | (required) | the material being perturbed |
//! | `flip_invalid_normals`   | boolean | true | mirror mapped normals that face away from the viewer (see `perturbed.rs`) |
//! | `use_shadowing_function` | boolean | true | the bump-terminator shadowing term (see `perturbed.rs`) |
//!
//! As in Mitsuba 3, n' = 2c − 1 is taken relative to the shading frame, whose first axis
//! follows ∂p/∂u (so c = (½, ½, 1) leaves the surface unchanged). See `perturbed.rs` for the
//! frame built on n' and how the nested BSDF is evaluated in it.

use glam::{Vec2, Vec3};

use super::perturbed::{PerturbOptions, Perturbed};
use super::{Bsdf, BsdfSample, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    pub normals: Texture,
    pub nested: Box<Bsdf>,
    pub options: PerturbOptions,
}

impl NormalMap {
    pub fn new(normals: Texture, nested: Bsdf, options: PerturbOptions) -> Self {
        NormalMap { normals, nested: Box::new(nested), options }
    }

    /// The mapped normal 2c − 1 in the local shading frame (unnormalised).
    pub fn normal(&self, sp: &ShadingPoint) -> Vec3 {
        Vec3::from(self.normals.eval(sp.tex())) * 2.0 - Vec3::ONE
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
mod tests {
    use super::super::bumpmap::tests::{copper, copper_with};
    use super::super::{Diffuse, MicrofacetKind};
    use super::*;
    use crate::testkit::bsdf::*;

    fn nmap(c: Vec3, nested: Bsdf) -> Bsdf {
        Bsdf::NormalMap(NormalMap::new(
            crate::Spectrum::from(c).into(),
            nested,
            PerturbOptions::default(),
        ))
    }

    fn white() -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(Spectrum::ONE.into()))
    }

    #[test]
    fn matches_mitsuba_values() {
        // mi.load_dict({'type': 'normalmap', 'normalmap': rgb (0.8, 0.5, 0.8), 'bsdf': ...})
        // .eval (cosine included) on a flat frame, Mitsuba 3.9.1 scalar_rgb: the shadowing
        // term, and the flip of invalid normals (wo = (60°, 180°) sees n from behind).
        let s = sp();
        let c = Vec3::new(0.8, 0.5, 0.8);
        let cases = [
            (white(), (0.0, 0.0), (60.0, 0.0), 0.28303707),
            (white(), (20.0, 180.0), (70.0, 0.0), 0.24099573),
            (copper_with(MicrofacetKind::Beckmann, 0.15), (0.0, 0.0), (60.0, 0.0), 0.20704070),
            (copper_with(MicrofacetKind::Beckmann, 0.15), (20.0, 180.0), (70.0, 0.0), 0.023624061),
            (white(), (60.0, 180.0), (30.0, 0.0), 0.081543893),
            (white(), (60.0, 180.0), (40.0, 180.0), 0.31041268),
        ];
        for (nested, o, i, f) in cases {
            let b = nmap(c, nested);
            let (wo, wi) = (dir(o.0, o.1), dir(i.0, i.1));
            let v = b.eval(&s, wo, wi).x * wi.z;
            assert!((v - f).abs() < 2e-4 * f.max(1.0), "{o:?} {i:?}: {v} vs {f}");
        }
    }

    #[test]
    fn flat_normal_changes_nothing_and_tilt_rotates() {
        let s = sp();
        let (wo, wi) = (dir(30.0, 10.0), dir(50.0, 200.0));
        let flat = nmap(Vec3::new(0.5, 0.5, 1.0), copper(0.3));
        assert!((flat.eval(&s, wo, wi) - copper(0.3).eval(&s, wo, wi)).abs().max_element() < 1e-5);
        let Bsdf::NormalMap(m) = nmap(Vec3::new(0.75, 0.5, 0.9), copper(0.1)) else {
            unreachable!()
        };
        let n = m.normal(&s).normalize();
        assert!((n - Vec3::new(0.5, 0.0, 0.8).normalize()).length() < 1e-6);
        // a glossy nested lobe peaks around the reflection about n'
        let tilted = Bsdf::NormalMap(m);
        let wo = dir(0.0, 0.0);
        let refl = (2.0 * n.dot(wo) * n - wo).normalize();
        assert!(
            refl.z > 0.0
                && tilted.eval(&s, wo, refl).max_element()
                    > 10.0 * tilted.eval(&s, wo, Vec3::Z).max_element()
        );
    }

    #[test]
    fn sampling_matches_pdf_chi2_consistency_furnace() {
        let mut k = 0;
        for (c, nested) in [
            (Vec3::new(0.7, 0.4, 0.9), copper(0.3)),
            (Vec3::new(0.3, 0.8, 0.8), Bsdf::Diffuse(Diffuse::new(Spectrum::splat(0.9).into()))),
        ] {
            let b = nmap(c, nested);
            for theta in [0.0, 40.0, 80.0] {
                let p = chi2_pvalue_sub(&b, dir(theta, 20.0), 200_000, 60 + k, 32);
                k += 1;
                eprintln!("χ² p-value {p:.3}");
                assert!(p > 0.01 / 6.0, "θ={theta}: p-value {p}");
                check_sample_consistency(&b, dir(theta, 20.0), 9);
                let (m, se) = albedo(&b, dir(theta, 20.0), 50_000, 10);
                assert!(m.iter().zip(se).all(|(m, se)| *m <= 1.0 + 5.0 * se), "θ={theta}: {m:?}");
            }
        }
    }
}
