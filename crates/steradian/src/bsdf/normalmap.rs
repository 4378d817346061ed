//! `normalmap`: replaces the shading normal of a nested BSDF by one read from a texture.
//!
//! | parameter   | type    | default    | meaning |
//! |-------------|---------|------------|---------|
//! | `normalmap` | texture | (required) | RGB c ∈ [0, 1]³ encoding the normal n' = normalize(2c − 1) in the local shading frame (give the bitmap `raw`) |
//! | (nested)    | BSDF    | (required) | the material being perturbed |
//!
//! As in Mitsuba 3, n' is taken relative to the shading frame whose first axis follows ∂p/∂u
//! (so c = (½, ½, 1) leaves the surface unchanged), is not flipped towards the geometric
//! normal, and the new first axis s' is the projection of ∂p/∂u. Mitsuba projects the
//! world-space ∂p/∂u on the local n'; steradian projects the local ∂p/∂u, which gives the same
//! n' and differs only in the azimuth of s' (invisible to isotropic nested BSDFs). See
//! `perturbed.rs` for how the nested BSDF is evaluated in the new frame.

use glam::{Vec2, Vec3};

use super::perturbed::Perturbed;
use super::{Bsdf, BsdfSample, ShadingPoint};
use crate::texture::Texture;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    pub normals: Texture,
    pub nested: Box<Bsdf>,
}

impl NormalMap {
    pub fn new(normals: Texture, nested: Bsdf) -> Self {
        NormalMap { normals, nested: Box::new(nested) }
    }

    /// The mapped normal in the local shading frame (zero when the texel encodes none).
    pub fn normal(&self, sp: &ShadingPoint) -> Vec3 {
        (self.normals.eval(sp.uv) * 2.0 - Vec3::ONE).normalize_or_zero()
    }

    #[inline]
    fn frame(&self, sp: &ShadingPoint) -> Option<Perturbed> {
        Perturbed::new(sp, self.normal(sp))
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        match self.frame(sp) {
            Some(p) => p.eval(&self.nested, wo, wi),
            None => Spectrum::ZERO,
        }
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        match self.frame(sp) {
            Some(p) => p.pdf(&self.nested, wo, wi),
            None => 0.0,
        }
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        self.frame(sp)?.sample(&self.nested, wo, u1, u2)
    }

    pub fn has_smooth_lobe(&self) -> bool {
        self.nested.has_smooth_lobe()
    }
}

#[cfg(test)]
mod tests {
    use super::super::bumpmap::tests::rough;
    use super::super::testing::*;
    use super::super::Diffuse;
    use super::*;

    fn nmap(c: Vec3, nested: Bsdf) -> Bsdf {
        Bsdf::NormalMap(NormalMap::new(c.into(), nested))
    }

    #[test]
    fn flat_normal_changes_nothing_and_tilt_rotates() {
        let s = sp();
        let (wo, wi) = (dir(30.0, 10.0), dir(50.0, 200.0));
        let flat = nmap(Vec3::new(0.5, 0.5, 1.0), rough(0.3));
        assert!((flat.eval(&s, wo, wi) - rough(0.3).eval(&s, wo, wi)).abs().max_element() < 1e-5);
        let Bsdf::NormalMap(m) = nmap(Vec3::new(0.75, 0.5, 0.9), rough(0.3)) else { unreachable!() };
        let n = m.normal(&s);
        assert!((n - Vec3::new(0.5, 0.0, 0.8).normalize()).length() < 1e-6);
        // a mirror-like nested lobe peaks around the reflection about n'
        let tilted = Bsdf::NormalMap(m);
        let wo = dir(0.0, 0.0);
        let refl = (2.0 * n.dot(wo) * n - wo).normalize();
        assert!(refl.z > 0.0 && tilted.eval(&s, wo, refl).max_element() > 10.0 * tilted.eval(&s, wo, Vec3::Z).max_element());
    }

    #[test]
    fn sampling_matches_pdf_chi2_consistency_furnace() {
        let mut k = 0;
        for (c, nested) in [(Vec3::new(0.7, 0.4, 0.9), rough(0.3)), (Vec3::new(0.3, 0.8, 0.8), Bsdf::Diffuse(Diffuse::new(Spectrum::splat(0.9).into())))] {
            let b = nmap(c, nested);
            for theta in [0.0, 40.0, 80.0] {
                let p = chi2_pvalue_sub(&b, dir(theta, 20.0), 200_000, 60 + k, 32);
                k += 1;
                assert!(p > 0.01 / 6.0, "θ={theta}: p-value {p}");
                check_sample_consistency(&b, dir(theta, 20.0), 9);
                let (m, se) = albedo(&b, dir(theta, 20.0), 50_000, 10);
                assert!(m.iter().zip(se).all(|(m, se)| *m <= 1.0 + 5.0 * se), "θ={theta}: {m:?}");
            }
        }
    }
}
