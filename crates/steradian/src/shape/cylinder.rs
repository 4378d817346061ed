//! # `cylinder`: an open cylinder
//!
//! Mitsuba plugin `cylinder`: the lateral surface of a circular cylinder, without caps
//! (add `disk`s for those).
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `p0` | point | (0, 0, 0) | centre of the first end, m |
//! | `p1` | point | (0, 0, 1) | centre of the second end, m |
//! | `radius` | float | 1 | radius, m |
//! | `to_world` | transform | identity | applied after `p0`, `p1`, `radius` |
//! | `flip_normals` | bool | false | normals point inwards instead of outwards |
//!
//! The object-to-world map is `to_world · T(p0) · R · S(radius, radius, |p1 − p0|)` where `R`
//! maps +z to the axis direction (the frame of the axis, as Mitsuba's `to_frame`); the unit
//! cylinder x² + y² = 1, z ∈ [0, 1] is intersected in that local space (both roots, so rays
//! from inside hit the far wall). uv = (φ/2π, z). The normal is the outward radial direction
//! (inward with `flip_normals`).
//!
//! Area: 2π·r·ℓ with r the mean world length of the local x and y axes and ℓ that of the
//! local z axis. Like Mitsuba (which warns), steradian assumes the transform scales x and y
//! equally (no shear); area sampling is uniform in (φ, z) with pdf 1/area, exact in that case.

use std::f32::consts::PI;

use glam::{Mat4, Vec2, Vec3};

use super::{azimuth01, is_positive, is_positive_finite, PositionSample, ShapeError};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};

#[derive(Clone, Debug)]
pub struct Cylinder {
    object_to_world: Transform,
    flip: bool,
    area: f32,
}

impl Cylinder {
    /// Default `p0` (m; Mitsuba's).
    pub const DEFAULT_P0: Vec3 = Vec3::ZERO;
    /// Default `p1` (m; Mitsuba's).
    pub const DEFAULT_P1: Vec3 = Vec3::Z;
    /// Default `radius` (m; Mitsuba's).
    pub const DEFAULT_RADIUS: f32 = 1.0;

    pub fn new(
        p0: Vec3,
        p1: Vec3,
        radius: f32,
        to_world: &Transform,
        flip_normals: bool,
    ) -> Result<Cylinder, ShapeError> {
        let d = p1 - p0;
        let len = d.length();
        if !is_positive_finite(len) {
            return Err(ShapeError("cylinder: p0 and p1 must be distinct finite points".into()));
        }
        if !is_positive_finite(radius) {
            return Err(ShapeError(format!(
                "cylinder: the radius must be positive (got {radius})"
            )));
        }
        let f = Frame::from_normal(d / len);
        let m = Mat4::from_translation(p0)
            * Mat4::from_cols(f.s.extend(0.0), f.t.extend(0.0), f.n.extend(0.0), glam::Vec4::W)
            * Mat4::from_scale(Vec3::new(radius, radius, len));
        let local = Transform::from_matrix(m).map_err(|e| ShapeError(format!("cylinder: {e}")))?;
        let object_to_world = to_world.then_after(&local);
        let s = object_to_world.axis_scales();
        let area = 2.0 * PI * 0.5 * (s.x + s.y) * s.z;
        Ok(Cylinder { object_to_world, flip: flip_normals, area })
    }

    pub fn bounds(&self) -> Aabb {
        self.object_to_world.aabb(&Aabb::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 1.0)))
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<(f32, Vec2)> {
        let o = self.object_to_world.inv.transform_point3(ray.o).as_dvec3();
        let d = self.object_to_world.inv.transform_vector3(ray.d).as_dvec3();
        let a = d.x * d.x + d.y * d.y;
        if !is_positive(a) {
            return None;
        }
        let b = o.x * d.x + o.y * d.y; // half of the linear coefficient
        let c = o.x * o.x + o.y * o.y - 1.0;
        // discriminant / 4, written without cancellation: a − (o × d)_z²
        let cross = o.x * d.y - o.y * d.x;
        let disc = a - cross * cross;
        if disc < 0.0 {
            return None;
        }
        let q = -b - disc.sqrt().copysign(b);
        let (mut t0, mut t1) = if q == 0.0 { (-b / a, -b / a) } else { (q / a, c / q) };
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        for t in [t0, t1] {
            let tf = t as f32;
            if !(tf > 0.0 && tf < ray.t_max) {
                continue;
            }
            let z = o.z + t * d.z;
            if (0.0..=1.0).contains(&z) {
                let (x, y) = (o.x + t * d.x, o.y + t * d.y);
                return Some((tf, Vec2::new(azimuth01(x as f32, y as f32), z as f32)));
            }
        }
        None
    }

    fn local(uv: Vec2) -> (Vec3, f32, f32) {
        let (s, c) = (2.0 * PI * uv.x).sin_cos();
        (Vec3::new(c, s, uv.y), c, s)
    }

    fn surface(&self, uv: Vec2) -> (Vec3, Vec3, Vec3) {
        let (l, c, s) = Self::local(uv);
        let p = self.object_to_world.point(l);
        let n = self.object_to_world.normal(Vec3::new(c, s, 0.0)).normalize();
        let n = if self.flip { -n } else { n };
        let dpdu = self.object_to_world.vector(Vec3::new(-s, c, 0.0) * (2.0 * PI));
        (p, n, dpdu)
    }

    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        let (p, n, dpdu) = self.surface(hit.uv);
        SurfaceInteraction {
            p,
            t: hit.t,
            n,
            sh_frame: Frame::from_normal_tangent(n, dpdu),
            uv: hit.uv,
            dpdu,
            // v is the local height z ∈ [0, 1]
            dpdv: self.object_to_world.vector(Vec3::Z),
            wo: -ray.d,
            shape: hit.shape,
            prim: hit.prim,
            bary: hit.uv,
            instance: hit.instance,
        }
    }

    pub fn sample_position(&self, u: Vec2) -> PositionSample {
        let uv = Vec2::new(u.x, u.y);
        let (p, n, _) = self.surface(uv);
        PositionSample { p, n, uv, pdf_area: 1.0 / self.area }
    }
}
