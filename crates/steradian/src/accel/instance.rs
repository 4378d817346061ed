//! Instancing: one copy of a group's geometry with its own BVH, placed any number of times.
//!
//! A [`ShapeGroup`] holds its shapes (in the group's own space) and the [`Accel`] built over
//! them; an [`Instance`] is a group and a transform. The scene's BVH holds each instance as one
//! primitive with the world bounds of its group's box; a ray reaching it is taken into the
//! group's space (direction renormalised, distances rescaled by its length so that `t` stays a
//! world distance outside) and traced through the group's BVH. Memory grows with the geometry
//! of the groups, not with the number of instances.
//!
//! Surface data is computed in the group's space and taken to the world as Mitsuba 3's
//! `instance` does: points and tangents by `to_world`, normals by its inverse transpose
//! (renormalised), so a mirroring transform does not turn faces inside out.

use std::sync::Arc;

use super::Accel;
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};
use crate::shape::Shape;

/// Shapes that are only rendered through instances, with their own hierarchy.
#[derive(Debug)]
pub struct ShapeGroup {
    /// The members, in the group's space.
    pub shapes: Vec<Shape>,
    pub(super) accel: Accel,
}

impl ShapeGroup {
    /// Builds the group's hierarchy over `shapes`.
    pub fn new(shapes: Vec<Shape>) -> ShapeGroup {
        let accel = Accel::build(&shapes);
        ShapeGroup { shapes, accel }
    }

    /// Bounds of the members in the group's space.
    pub fn bounds(&self) -> Aabb {
        self.accel.bounds()
    }
}

/// A placed copy of a [`ShapeGroup`].
#[derive(Clone, Debug)]
pub struct Instance {
    pub group: Arc<ShapeGroup>,
    pub to_world: Transform,
    to_local: Transform,
}

impl Instance {
    pub fn new(group: Arc<ShapeGroup>, to_world: Transform) -> Instance {
        let to_local = to_world.inverse();
        Instance { group, to_world, to_local }
    }

    /// World bounds (the group's box, transformed).
    pub fn bounds(&self) -> Aabb {
        let b = self.group.bounds();
        if b.is_empty() {
            b
        } else {
            self.to_world.aabb(&b)
        }
    }

    /// The ray in the group's space and the factor from world to local distances (`None`
    /// for a degenerate transform).
    #[inline]
    pub(super) fn local_ray(&self, ray: &Ray) -> Option<(Ray, f32)> {
        let d = self.to_local.vector(ray.d);
        let scale = d.length();
        (scale > 0.0 && scale.is_finite())
            .then(|| (Ray::new(self.to_local.point(ray.o), d / scale, ray.t_max * scale), scale))
    }

    /// The world surface interaction of `hit` (found by [`Accel::intersect`] on this instance).
    #[inline(never)]
    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        let (local, scale) = self.local_ray(ray).unwrap_or((*ray, 1.0));
        let local_hit = PreliminaryHit { t: hit.t * scale, ..*hit };
        let si = self.group.shapes[hit.shape as usize].interaction(&local, &local_hit);
        let world_normal = |n| self.to_world.normal(n).normalize_or_zero();
        let n = world_normal(si.n);
        let ns = world_normal(si.sh_frame.n);
        let dpdu = self.to_world.vector(si.dpdu);
        SurfaceInteraction {
            p: self.to_world.point(si.p),
            t: hit.t,
            n,
            sh_frame: Frame::from_normal_tangent(ns, dpdu),
            dpdu,
            dpdv: self.to_world.vector(si.dpdv),
            wo: -ray.d,
            instance: hit.instance,
            ..si
        }
    }
}
