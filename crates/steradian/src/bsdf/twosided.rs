//! `twosided`: makes one-sided BSDFs reflect on both faces.
//!
//! | child  | meaning |
//! |--------|---------|
//! | 1 BSDF | used on both sides |
//! | 2 BSDFs| the first on the front (normal side), the second on the back |
//!
//! When wo lies below the surface, both directions are mirrored through the surface
//! (z → −z) and the back BSDF is evaluated, as Mitsuba 3 does. Transmissive BSDFs are not
//! allowed inside `twosided` (Mitsuba refuses them too).

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample, ShadingPoint};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct TwoSided {
    pub front: Box<Bsdf>,
    pub back: Box<Bsdf>,
}

#[inline]
fn flip(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.y, -w.z)
}

impl TwoSided {
    pub fn new(front: Bsdf, back: Bsdf) -> Self {
        TwoSided { front: Box::new(front), back: Box::new(back) }
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if wo.z >= 0.0 {
            self.front.eval(sp, wo, wi)
        } else {
            self.back.eval(sp, flip(wo), flip(wi))
        }
    }

    /// The straight-through fraction of the side `wo` lies on.
    #[inline]
    pub fn null_transmission(&self, sp: &ShadingPoint, wo: Vec3) -> Spectrum {
        if wo.z >= 0.0 {
            self.front.null_transmission(sp, wo)
        } else {
            self.back.null_transmission(sp, flip(wo))
        }
    }

    /// The chance that `sample` takes a null lobe: the facing side's.
    pub fn null_chance(&self, sp: &ShadingPoint, wo: Vec3) -> f32 {
        if wo.z >= 0.0 {
            self.front.null_chance(sp, wo)
        } else {
            self.back.null_chance(sp, flip(wo))
        }
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z >= 0.0 {
            self.front.pdf(sp, wo, wi)
        } else {
            self.back.pdf(sp, flip(wo), flip(wi))
        }
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z >= 0.0 {
            self.front.sample(sp, wo, u1, u2)
        } else {
            let mut s = self.back.sample(sp, flip(wo), u1, u2)?;
            s.wi = flip(s.wi);
            Some(s)
        }
    }

    pub fn has_smooth_lobe(&self) -> bool {
        self.front.has_smooth_lobe() || self.back.has_smooth_lobe()
    }
}

#[cfg(test)]
mod tests {
    use super::super::Diffuse;
    use super::*;
    use crate::testkit::bsdf::*;

    #[test]
    fn back_face_reflects_with_the_back_bsdf() {
        let b = Bsdf::TwoSided(TwoSided::new(
            Bsdf::Diffuse(Diffuse::new(Spectrum::splat(0.8).into())),
            Bsdf::Diffuse(Diffuse::new(Spectrum::splat(0.2).into())),
        ));
        let s = sp();
        let (wo, wi) = (dir(30.0, 0.0), dir(50.0, 90.0));
        assert!(
            (b.eval(&s, wo, wi) - Spectrum::splat(0.8 / std::f32::consts::PI)).abs().max_element()
                < 1e-6
        );
        assert!(
            (b.eval(&s, flip(wo), flip(wi)) - Spectrum::splat(0.2 / std::f32::consts::PI))
                .abs()
                .max_element()
                < 1e-6
        );
        // light and viewer on opposite sides: nothing
        assert_eq!(b.eval(&s, wo, flip(wi)), Spectrum::ZERO);
        let smp = b.sample(&s, flip(wo), 0.3, Vec2::new(0.2, 0.7)).unwrap();
        assert!(smp.wi.z < 0.0);
        check_sample_consistency(&b, flip(dir(60.0, 45.0)), 4);
        let p = chi2_pvalue(&b, flip(dir(60.0, 45.0)), 100_000, 9);
        assert!(p > 0.01, "p-value {p}");
    }
}
