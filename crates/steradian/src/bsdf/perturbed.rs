//! Evaluating a BSDF in a perturbed shading frame: the common part of `bumpmap` and
//! `normalmap`.
//!
//! The adapter computes a new frame (s', t', n') expressed in the original shading frame and
//! evaluates the nested BSDF on the directions rotated into it. As in Mitsuba 3, a direction
//! wi (towards the light) counts only if it lies on the same side of both frames (cos θi ·
//! cos θ'i > 0); otherwise the BSDF is 0 and sampling fails. Mitsuba's `eval` includes the
//! cosine, which is then cos θ'i of the perturbed frame; since steradian's integrators
//! multiply by |cos θi| of the original frame, the adapter returns ρ'·|cos θ'i| / |cos θi|, so
//! that the product is Mitsuba's value and `sample`'s weight (the nested weight) stays
//! eval·|cos θi|/pdf. Rotations preserve solid angle, so densities carry over unchanged.
//!
//! The reflectance therefore obeys the adjoint form of reciprocity for shading normals
//! (Veach 1997, §5.3): ρ(wo, wi)·|cos θi|/|cos θ'i| is symmetric, ρ itself is not.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample, ShadingPoint};
use crate::geometry::Frame;
use crate::Spectrum;

/// A perturbed frame and the shading point as the nested BSDF sees it.
pub(crate) struct Perturbed {
    pub frame: Frame,
    pub sp: ShadingPoint,
}

impl Perturbed {
    /// The frame with normal `n` (unit, original-frame coordinates) and first axis along
    /// the projection of `dpdu`; `None` when `n` is not a usable direction.
    pub fn new(sp: &ShadingPoint, n: Vec3) -> Option<Perturbed> {
        if !n.is_finite() || !(n.length_squared() > 0.5) {
            return None;
        }
        let frame = Frame::from_normal_tangent(n, sp.dpdu);
        let nested = ShadingPoint { uv: sp.uv, dpdu: frame.to_local(sp.dpdu), dpdv: frame.to_local(sp.dpdv), ng: frame.to_local(sp.ng) };
        Some(Perturbed { frame, sp: nested })
    }

    #[inline]
    pub fn eval(&self, nested: &Bsdf, wo: Vec3, wi: Vec3) -> Spectrum {
        let wi_p = self.frame.to_local(wi);
        if !(wi.z * wi_p.z > 0.0) {
            return Spectrum::ZERO;
        }
        nested.eval(&self.sp, self.frame.to_local(wo), wi_p) * (wi_p.z.abs() / wi.z.abs())
    }

    #[inline]
    pub fn pdf(&self, nested: &Bsdf, wo: Vec3, wi: Vec3) -> f32 {
        let wi_p = self.frame.to_local(wi);
        if !(wi.z * wi_p.z > 0.0) {
            return 0.0;
        }
        nested.pdf(&self.sp, self.frame.to_local(wo), wi_p)
    }

    #[inline]
    pub fn sample(&self, nested: &Bsdf, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let mut s = nested.sample(&self.sp, self.frame.to_local(wo), u1, u2)?;
        let wi = self.frame.to_world(s.wi);
        if !(wi.z * s.wi.z > 0.0) {
            return None;
        }
        s.wi = wi;
        Some(s)
    }
}
