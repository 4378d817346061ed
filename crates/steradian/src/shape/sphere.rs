//! # `sphere`: an analytic sphere
//!
//! Mitsuba plugin `sphere`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `center` | point | (0, 0, 0) | centre, m (before `to_world`) |
//! | `radius` | float | 1 | radius, m (before `to_world`) |
//! | `to_world` | transform | identity | applied **after** centre and radius: the final transform is `to_world · T(center) · S(radius)` |
//! | `flip_normals` | bool | false | normals point inwards instead of outwards |
//!
//! steradian computes: the world centre `M·0` and the world radius, the mean of the lengths of
//! the three transformed unit axes (a sphere stays a sphere: for a non-uniform scale Mitsuba
//! only warns, and steradian likewise uses one radius). A transform with a negative
//! determinant (or a negative `radius`) flips the normals, as in Mitsuba. Intersections are
//! solved in single precision with the numerically stable quadratic (discriminant as
//! r² − |oc − b·d|², near root as c/q; both roots, so rays from inside hit the far side); the
//! offset of rays leaving a surface, 10⁻⁴ × (1 + |p|), is far above its rounding.
//! uv = (φ/2π, θ/π) of the hit in the local frame of `to_world · T(center) · S(radius)`.
//! Direction sampling from outside samples the cone of directions subtending the sphere
//! uniformly (pdf 1/(2π(1 − cos θmax)), 1/sr); from inside it samples the area uniformly and
//! converts to solid angle.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{area_to_solid_angle, azimuth01, is_positive_finite, DirectionSample, PositionSample};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};
use crate::sampling::warp;

#[derive(Clone, Debug)]
pub struct Sphere {
    /// to_world · T(center) · S(radius): unit sphere → world.
    object_to_world: Transform,
    center: Vec3,
    radius: f32,
    flip: bool,
}

impl Sphere {
    /// Default `center` (m; Mitsuba's).
    pub const DEFAULT_CENTER: Vec3 = Vec3::ZERO;
    /// Default `radius` (m; Mitsuba's).
    pub const DEFAULT_RADIUS: f32 = 1.0;

    pub fn new(center: Vec3, radius: f32, to_world: &Transform, flip_normals: bool) -> Sphere {
        let r = radius.abs();
        let local = Transform::translate(center).then_after(&Transform {
            m: glam::Mat4::from_scale(Vec3::splat(r)),
            inv: glam::Mat4::from_scale(Vec3::splat(1.0 / r)),
        });
        let object_to_world = to_world.then_after(&local);
        let s = to_world.axis_scales();
        let flip = flip_normals ^ (radius < 0.0) ^ to_world.flips_handedness();
        Sphere {
            object_to_world,
            center: to_world.point(center),
            radius: r * (s.x + s.y + s.z) / 3.0,
            flip,
        }
    }

    pub fn center(&self) -> Vec3 {
        self.center
    }

    pub fn radius(&self) -> f32 {
        self.radius
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.center - Vec3::splat(self.radius), self.center + Vec3::splat(self.radius))
    }

    pub fn surface_area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    #[inline]
    fn normal_at(&self, p: Vec3) -> Vec3 {
        let n = (p - self.center).normalize();
        if self.flip {
            -n
        } else {
            n
        }
    }

    fn uv_at(&self, p: Vec3) -> Vec2 {
        Self::uv_of_local(self.object_to_world.inv.transform_point3(p))
    }

    /// Mitsuba's (φ/2π, θ/π) of a point in the sphere's local frame.
    #[inline]
    fn uv_of_local(l: Vec3) -> Vec2 {
        let l = l.normalize_or_zero();
        Vec2::new(
            azimuth01(l.x, l.y),
            crate::geometry::trig::acos(l.z) * std::f32::consts::FRAC_1_PI,
        )
    }

    /// Both roots of |o + t·d − c|² = r² for the unit direction d, in increasing order.
    #[inline]
    fn roots(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)> {
        let oc = o - self.center;
        let r = self.radius;
        let b = oc.dot(d);
        let c = oc.dot(oc) - r * r;
        // discriminant written as r² − |oc − b·d|² (exact-ish for far rays)
        let f = oc - b * d;
        let disc = r * r - f.dot(f);
        if disc < 0.0 {
            return None;
        }
        let q = -b - disc.sqrt().copysign(b);
        if q == 0.0 {
            return Some((0.0, 0.0));
        }
        let (t0, t1) = (c / q, q);
        Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<(f32, Vec2)> {
        let (t0, t1) = self.roots(ray.o, ray.d)?;
        let t = if t0 > 0.0 && t0 < ray.t_max {
            t0
        } else if t1 > 0.0 && t1 < ray.t_max {
            t1
        } else {
            return None;
        };
        // uv waits for `interaction`: most candidate hits (and every shadow ray) never need it
        Some((t, Vec2::ZERO))
    }

    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        // Project the hit onto the surface to remove the error of o + t·d.
        let p = self.center + (ray.at(hit.t) - self.center).normalize() * self.radius;
        let n = self.normal_at(p);
        // Mitsuba's parametrisation: u = φ/2π, v = θ/π on the unit sphere of the local frame,
        // so ∂p/∂u = 2π·(−y, x, 0) and ∂p/∂v = π·(z cos φ, z sin φ, −sin θ).
        let l = self.object_to_world.inv.transform_point3(p);
        let dpdu = self.object_to_world.vector(Vec3::new(-l.y, l.x, 0.0) * (2.0 * PI));
        let rd = (l.x * l.x + l.y * l.y).sqrt();
        let (cos_phi, sin_phi) = if rd > 0.0 { (l.x / rd, l.y / rd) } else { (1.0, 0.0) };
        let dpdv = self.object_to_world.vector(Vec3::new(l.z * cos_phi, l.z * sin_phi, -rd) * PI);
        SurfaceInteraction {
            p,
            t: hit.t,
            n,
            sh_frame: Frame::from_normal_tangent(n, dpdu),
            uv: Self::uv_of_local(l),
            dpdu,
            dpdv,
            wo: -ray.d,
            shape: hit.shape,
            prim: hit.prim,
            bary: hit.uv,
            instance: hit.instance,
        }
    }

    pub fn sample_position(&self, u: Vec2) -> PositionSample {
        let w = warp::square_to_uniform_sphere(u);
        let p = self.center + w * self.radius;
        PositionSample {
            p,
            n: if self.flip { -w } else { w },
            uv: self.uv_at(p),
            pdf_area: 1.0 / self.surface_area(),
        }
    }

    /// (cos θmax, 1 − cos θmax) of the cone subtended from `reference`, or `None` when the
    /// reference is inside (or on) the sphere.
    #[inline]
    fn cone(&self, reference: Vec3) -> Option<(f32, f32, f32)> {
        let dc2 = (self.center - reference).length_squared();
        let r2 = self.radius * self.radius;
        if dc2 <= r2 * (1.0 + 1e-5) {
            return None;
        }
        let sin2 = r2 / dc2;
        let cos_max = (1.0 - sin2).max(0.0).sqrt();
        // 1 − cos θmax = sin² / (1 + cos), without cancellation for tiny cones
        let one_minus = sin2 / (1.0 + cos_max);
        Some((cos_max, one_minus, dc2.sqrt()))
    }

    /// Whether every direction sample from `reference` has a bounded weight for a Lambertian
    /// receiver there (see [`super::Shape::light_sampling_bounded`]): from outside, the cone is sampled
    /// uniformly, and a sample weighs at most its solid angle 2π(1 − cos θmax); from inside,
    /// area sampling's 1/d² is not bounded.
    pub fn light_sampling_bounded(&self, reference: Vec3) -> bool {
        self.cone(reference).is_some()
    }

    pub fn sample_direction(
        &self,
        reference: Vec3,
        u: Vec2,
        uv: super::UvRequest,
    ) -> Option<DirectionSample> {
        let Some((cos_max, one_minus, dc)) = self.cone(reference) else {
            return super::direction_from_position(reference, &self.sample_position(u), 0);
        };
        let axis = (self.center - reference) / dc;
        // cos θ uniform in [cos θmax, 1], with the cone's 1 − cos θmax free of cancellation
        let local = warp::square_to_uniform_cone(u, one_minus);
        let cos_t = local.z;
        // |axis| = 1 and the frame is orthonormal, so wi is a unit vector up to rounding
        let wi = Frame::from_normal(axis).to_world(local);
        // Nearest intersection: dist = dc·cos θ − √(r² − dc²·sin² θ). The radicand is a
        // difference of near-equal terms at the silhouette; with r² = dc²·sin² θmax it is
        // dc²·(cos θ − cos θmax)(cos θ + cos θmax), and cos θ − cos θmax = (1 − cos θmax)(1 − u.y)
        // without cancellation, so single precision keeps the point on the sphere.
        let dist = dc * (cos_t - (one_minus * (1.0 - u.y) * (cos_t + cos_max)).max(0.0).sqrt());
        if !is_positive_finite(dist) {
            return None;
        }
        // Put p exactly on the surface (it only moves by rounding error); the same unit vector
        // is the normal.
        let radial = (reference + wi * dist - self.center).normalize();
        let p = self.center + radial * self.radius;
        let pdf = 1.0 / (2.0 * PI * one_minus);
        if !(pdf.is_finite() && pdf > 0.0) {
            return None;
        }
        let n = if self.flip { -radial } else { radial };
        let uv = match uv {
            super::UvRequest::Compute => self.uv_at(p),
            super::UvRequest::Skip => Vec2::ZERO,
        };
        Some(DirectionSample { p, n, uv, wi, dist, pdf, prim: 0 })
    }

    pub fn pdf_direction(&self, reference: Vec3, p: Vec3, n: Vec3) -> f32 {
        match self.cone(reference) {
            Some((_, one_minus, _)) => {
                let pdf = 1.0 / (2.0 * PI * one_minus);
                if pdf.is_finite() {
                    pdf
                } else {
                    0.0
                }
            }
            None => area_to_solid_angle(1.0 / self.surface_area(), reference, p, n),
        }
    }
}
