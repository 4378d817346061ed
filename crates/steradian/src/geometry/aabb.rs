use glam::Vec3;

use super::Ray;

/// An axis-aligned bounding box. The empty box has `min = +∞`, `max = −∞`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    pub const EMPTY: Aabb =
        Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };

    #[inline]
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Aabb { min, max }
    }

    #[inline]
    pub fn from_point(p: Vec3) -> Self {
        Aabb { min: p, max: p }
    }

    #[inline]
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    #[inline]
    pub fn grow(&mut self, p: Vec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    #[inline]
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    #[inline]
    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    #[inline]
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Surface area in m² (0 for an empty box).
    #[inline]
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Index of the longest axis.
    #[inline]
    pub fn max_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }

    /// Slab test: the parametric interval `[t0, t1]` of the ray inside the box, if any, clipped
    /// to `(0, ray.t_max)`. `inv_d` is `1 / ray.d`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, inv_d: Vec3) -> Option<(f32, f32)> {
        let t_a = (self.min - ray.o) * inv_d;
        let t_b = (self.max - ray.o) * inv_d;
        let t0 = t_a.min(t_b).max_element().max(0.0);
        let t1 = t_a.max(t_b).min_element().min(ray.t_max);
        (t0 <= t1).then_some((t0, t1))
    }

    /// A bounding sphere (centre, radius) of the box.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        let c = self.center();
        (c, if self.is_empty() { 0.0 } else { (self.max - c).length() })
    }
}
