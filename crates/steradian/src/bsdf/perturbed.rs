//! Evaluating a BSDF in a perturbed shading frame: the common part of `bumpmap` and
//! `normalmap` (Mitsuba 3.7.1+'s `PerturbedBSDF`, the version steradian follows).
//!
//! Each adapter supplies a perturbed normal n (unnormalised, in the original shading frame).
//! Then, as in Mitsuba 3.9.1:
//! - `flip_invalid_normals` (default on; Schüssler et al. 2017): when n faces away from the
//!   viewer (cos θo · (wo·n) ≤ 0) its tangential part is mirrored, n → (−nx, −ny, nz);
//! - n is normalised (falling back to +z), s' is the Gram–Schmidt projection of the original
//!   first axis (1, 0, 0) (falling back to (0, 1, 0)) and t' = n × s';
//! - the nested BSDF is evaluated on the directions rotated into (s', t', n); a light
//!   direction wi counts only if it lies on the same side of both frames (cos θi · cos θ'i > 0),
//!   otherwise the value is 0 and sampling fails;
//! - `use_shadowing_function` (default on; Conty Estevez, Lecocq & Stein 2019, "A
//!   Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem") multiplies the
//!   value and the sample weight by G(wi) = 2 / (1 + √(1 + α²·tan²θi)) with α² =
//!   min(tan²θn / 8, 1), θi and θn measured from the original shading normal. The density is
//!   unchanged.
//!
//! Mitsuba's `eval` includes the cosine, which is then cos θ'i of the perturbed frame; since
//! steradian's integrators multiply by |cos θi| of the original frame, the adapter returns
//! ρ'·|cos θ'i|·G / |cos θi|, so that the product is Mitsuba's value and `sample`'s weight
//! (the nested weight times G) stays eval·|cos θi|/pdf. Rotations preserve solid angle, so
//! densities carry over unchanged.
//!
//! The reflectance obeys only the adjoint form of reciprocity for shading normals (Veach 1997,
//! §5.3): ρ(wo, wi)·|cos θi| / (|cos θ'i|·G(wi)) is symmetric when neither direction flips n.

use glam::{Vec2, Vec3};

use super::{positive, Bsdf, BsdfSample, ShadingPoint};
use crate::geometry::Frame;
use crate::Spectrum;

/// A perturbed frame and the shading point as the nested BSDF sees it.
pub(crate) struct Perturbed {
    pub frame: Frame,
    pub sp: ShadingPoint,
    /// Whether the shadowing term G applies.
    shadowing: bool,
}

/// Options of the adapters, both on by default as in Mitsuba.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PerturbOptions {
    pub flip_invalid_normals: bool,
    pub use_shadowing_function: bool,
}

impl Default for PerturbOptions {
    fn default() -> Self {
        PerturbOptions { flip_invalid_normals: true, use_shadowing_function: true }
    }
}

/// tan²θ of a local direction (∞ on the horizon).
#[inline]
fn tan2_theta(w: Vec3) -> f32 {
    let c2 = w.z * w.z;
    (w.length_squared() - c2).max(0.0) / c2
}

/// The bump-terminator shadowing G(wi) of a perturbed normal `n` (both local, unit).
#[inline]
pub(crate) fn shadow_terminator(n: Vec3, wi: Vec3) -> f32 {
    let alpha2 = (0.125 * tan2_theta(n)).min(1.0);
    2.0 / (1.0 + (1.0 + alpha2 * tan2_theta(wi)).sqrt())
}

impl Perturbed {
    /// The frame of the perturbed normal `n` (unnormalised, original-frame coordinates) seen
    /// from the viewer direction `wo`.
    pub fn new(sp: &ShadingPoint, n: Vec3, wo: Vec3, options: PerturbOptions) -> Perturbed {
        let mut n = n;
        if options.flip_invalid_normals && wo.z * wo.dot(n) <= 0.0 {
            n = Vec3::new(-n.x, -n.y, n.z);
        }
        let inv_len = n.length_squared().sqrt().recip();
        let n = if inv_len > 0.0 && inv_len.is_finite() { n * inv_len } else { Vec3::Z };
        let s = Vec3::X - n * n.x;
        let inv_s = s.length_squared().sqrt().recip();
        let s = if inv_s.is_finite() { s * inv_s } else { Vec3::Y };
        let frame = Frame { s, t: n.cross(s), n };
        let nested = ShadingPoint {
            uv: sp.uv,
            dpdu: frame.to_local(sp.dpdu),
            dpdv: frame.to_local(sp.dpdv),
            ng: frame.to_local(sp.ng),
            prim: sp.prim,
            bary: sp.bary,
            p: sp.p,
        };
        Perturbed { frame, sp: nested, shadowing: options.use_shadowing_function }
    }

    /// G(wi), or 1 without the shadowing function.
    #[inline]
    fn g(&self, wi: Vec3) -> f32 {
        if self.shadowing {
            shadow_terminator(self.frame.n, wi)
        } else {
            1.0
        }
    }

    #[inline]
    pub fn eval(&self, nested: &Bsdf, wo: Vec3, wi: Vec3) -> Spectrum {
        let wi_p = self.frame.to_local(wi);
        if !positive(wi.z * wi_p.z) {
            return Spectrum::ZERO;
        }
        nested.eval(&self.sp, self.frame.to_local(wo), wi_p)
            * (wi_p.z.abs() / wi.z.abs() * self.g(wi))
    }

    #[inline]
    pub fn pdf(&self, nested: &Bsdf, wo: Vec3, wi: Vec3) -> f32 {
        let wi_p = self.frame.to_local(wi);
        if !positive(wi.z * wi_p.z) {
            return 0.0;
        }
        nested.pdf(&self.sp, self.frame.to_local(wo), wi_p)
    }

    #[inline]
    pub fn sample(&self, nested: &Bsdf, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let mut s = nested.sample(&self.sp, self.frame.to_local(wo), u1, u2)?;
        let wi = self.frame.to_world(s.wi);
        if !positive(wi.z * s.wi.z) {
            return None;
        }
        s.wi = wi;
        s.weight *= self.g(wi);
        Some(s)
    }
}
