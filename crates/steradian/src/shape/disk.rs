//! # `disk`: a flat circular disk
//!
//! Mitsuba plugin `disk`. In its local frame the disk has radius 1, lies in the plane z = 0
//! and faces +z. Use `to_world` to scale, rotate and place it.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `to_world` | transform | identity | places the disk (a non-uniform scale makes an ellipse) |
//! | `flip_normals` | bool | false | the front side faces −z (local) instead of +z |
//!
//! steradian computes: the world normal `normalize(to_world⁻ᵀ · (0,0,1))` (negated by
//! `flip_normals`), uv = (r, φ/2π) of the local hit point (as Mitsuba), the area
//! `π·|to_world·x̂ × to_world·ŷ|` in m² (exact for any affine map), and uniform area
//! sampling with the concentric disk map (pdf 1/area).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{azimuth01, PositionSample};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};
use crate::sampling::warp;

#[derive(Clone, Debug)]
pub struct Disk {
    to_world: Transform,
    n: Vec3,
    area: f32,
}

impl Disk {
    pub fn new(to_world: &Transform, flip_normals: bool) -> Disk {
        let n = to_world.normal(Vec3::Z).normalize();
        let n = if flip_normals { -n } else { n };
        let area = PI * to_world.vector(Vec3::X).cross(to_world.vector(Vec3::Y)).length();
        Disk { to_world: *to_world, n, area }
    }

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
        let r2 = x * x + y * y;
        if r2 <= 1.0 {
            Some((t, Vec2::new(r2.sqrt(), azimuth01(x, y))))
        } else {
            None
        }
    }

    fn local(uv: Vec2) -> Vec3 {
        let (s, c) = (2.0 * PI * uv.y).sin_cos();
        Vec3::new(uv.x * c, uv.x * s, 0.0)
    }

    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        let (s, c) = (2.0 * PI * hit.uv.y).sin_cos();
        // dp/du points radially outwards (as Mitsuba); at the centre use the local x axis.
        let dpdu =
            self.to_world.vector(if hit.uv.x > 0.0 { Vec3::new(c, s, 0.0) } else { Vec3::X });
        // v = φ/2π: ∂p/∂v = 2π·r·(−sin φ, cos φ, 0)
        let dpdv = self.to_world.vector(Vec3::new(-s, c, 0.0) * (2.0 * PI * hit.uv.x));
        SurfaceInteraction {
            p: self.to_world.point(Self::local(hit.uv)),
            t: hit.t,
            n: self.n,
            sh_frame: Frame::from_normal_tangent(self.n, dpdu),
            uv: hit.uv,
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
        let q = warp::square_to_uniform_disk_concentric(u);
        let uv = Vec2::new(q.length(), azimuth01(q.x, q.y));
        PositionSample {
            p: self.to_world.point(q.extend(0.0)),
            n: self.n,
            uv,
            pdf_area: 1.0 / self.area,
        }
    }
}
