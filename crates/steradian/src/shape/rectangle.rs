//! # `rectangle`: a planar quadrilateral
//!
//! Mitsuba plugin `rectangle`. In its local frame the rectangle is [−1, 1]² in the plane
//! z = 0 with normal +z (area 4 before scaling).
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `to_world` | transform | identity | places the rectangle; any affine map (it becomes a parallelogram) |
//! | `flip_normals` | bool | false | the front side faces −z (local) instead of +z |
//!
//! steradian computes: the world normal `normalize(to_world⁻ᵀ · (0,0,1))` (negated by
//! `flip_normals`), uv = ((x+1)/2, (y+1)/2) of the local hit point, the area
//! `4·|to_world·x̂ × to_world·ŷ|` in m², and uniform area sampling (pdf 1/area). Seen
//! from a point, a true rectangle (perpendicular edges) is sampled uniformly in the solid
//! angle it subtends ([`SphericalRectangle`]) unless that solid angle is tiny (< 3·10⁻⁴ sr,
//! where area sampling is as good and better conditioned) or nearly a hemisphere.

use glam::{Vec2, Vec3};

use super::{direction_from_position, is_positive_finite, DirectionSample, PositionSample};
use crate::sampling::spherical_rectangle::{RectangleFrame, SphericalRectangle};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};

#[derive(Clone, Debug)]
pub struct Rectangle {
    to_world: Transform,
    n: Vec3,
    dpdu: Vec3,
    dpdv: Vec3,
    area: f32,
    /// The rectangle's own frame, when its edges are perpendicular (a true rectangle).
    frame: Option<RectangleFrame>,
}

/// Solid angles (sr) within which spherical-rectangle sampling is used (pbrt-v4's bounds).
const SOLID_ANGLE_SAMPLING: std::ops::Range<f32> = 3e-4..6.22;

impl Rectangle {
    pub fn new(to_world: &Transform, flip_normals: bool) -> Rectangle {
        let n = to_world.normal(Vec3::Z).normalize();
        let n = if flip_normals { -n } else { n };
        let dpdu = to_world.vector(Vec3::X * 2.0);
        let dpdv = to_world.vector(Vec3::Y * 2.0);
        let corner = to_world.point(Vec3::new(-1.0, -1.0, 0.0));
        let perpendicular = dpdu.dot(dpdv).abs() <= 1e-5 * dpdu.length() * dpdv.length();
        let frame = perpendicular.then(|| RectangleFrame::new(corner, dpdu, dpdv));
        Rectangle { to_world: *to_world, n, dpdu, dpdv, area: dpdu.cross(dpdv).length(), frame }
    }

    /// World normal of the front side.
    pub fn normal(&self) -> Vec3 {
        self.n
    }

    pub fn bounds(&self) -> Aabb {
        self.to_world.aabb(&Aabb::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0)))
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<(f32, Vec2)> {
        let o = self.to_world.inv.transform_point3(ray.o);
        let d = self.to_world.inv.transform_vector3(ray.d);
        let t = -o.z / d.z;
        if !(t > 0.0 && t < ray.t_max) {
            return None;
        }
        let x = o.x + t * d.x;
        let y = o.y + t * d.y;
        if x.abs() <= 1.0 && y.abs() <= 1.0 {
            Some((t, Vec2::new(0.5 * (x + 1.0), 0.5 * (y + 1.0))))
        } else {
            None
        }
    }

    fn point(&self, uv: Vec2) -> Vec3 {
        self.to_world.point(Vec3::new(2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0, 0.0))
    }

    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        SurfaceInteraction {
            p: self.point(hit.uv),
            t: hit.t,
            n: self.n,
            sh_frame: Frame::from_normal_tangent(self.n, self.dpdu),
            uv: hit.uv,
            dpdu: self.dpdu,
            dpdv: self.dpdv,
            wo: -ray.d,
            shape: hit.shape,
            prim: hit.prim,
        }
    }

    /// The rectangle as seen from `reference`, when solid-angle sampling applies there.
    fn spherical(&self, reference: Vec3) -> Option<SphericalRectangle> {
        let sr = SphericalRectangle::from_frame(reference, self.frame.as_ref()?);
        SOLID_ANGLE_SAMPLING.contains(&sr.solid_angle).then_some(sr)
    }

    /// A point seen from `reference`, uniformly in solid angle where possible.
    pub fn sample_direction(&self, reference: Vec3, u: Vec2) -> Option<DirectionSample> {
        let Some(sr) = self.spherical(reference) else {
            return direction_from_position(reference, &self.sample_position(u), 0);
        };
        let (p, uv) = sr.sample_with_uv(u);
        let d = p - reference;
        let dist = d.length();
        let pdf = 1.0 / sr.solid_angle;
        if !is_positive_finite(dist) || !is_positive_finite(pdf) {
            return None;
        }
        Some(DirectionSample { p, n: self.n, uv, wi: d / dist, dist, pdf, prim: 0 })
    }

    /// Density per solid angle of [`Rectangle::sample_direction`] for the point `p`.
    pub fn pdf_direction(&self, reference: Vec3, p: Vec3, n: Vec3) -> f32 {
        match self.spherical(reference) {
            Some(sr) => 1.0 / sr.solid_angle,
            None => super::area_to_solid_angle(1.0 / self.area, reference, p, n),
        }
    }

    pub fn sample_position(&self, u: Vec2) -> PositionSample {
        PositionSample { p: self.point(u), n: self.n, uv: u, pdf_area: 1.0 / self.area }
    }
}
