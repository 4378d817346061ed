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
//! `4·|to_world·x̂ × to_world·ŷ|` in m², and uniform area sampling (pdf 1/area).

use glam::{Vec2, Vec3};

use super::PositionSample;
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};

#[derive(Clone, Debug)]
pub struct Rectangle {
    to_world: Transform,
    n: Vec3,
    dpdu: Vec3,
    area: f32,
}

impl Rectangle {
    pub fn new(to_world: &Transform, flip_normals: bool) -> Rectangle {
        let n = to_world.normal(Vec3::Z).normalize();
        let n = if flip_normals { -n } else { n };
        let dpdu = to_world.vector(Vec3::X * 2.0);
        let dpdv = to_world.vector(Vec3::Y * 2.0);
        Rectangle { to_world: *to_world, n, dpdu, area: dpdu.cross(dpdv).length() }
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
            wo: -ray.d,
            shape: hit.shape,
            prim: hit.prim,
        }
    }

    pub fn sample_position(&self, u: Vec2) -> PositionSample {
        PositionSample { p: self.point(u), n: self.n, uv: u, pdf_area: 1.0 / self.area }
    }
}
