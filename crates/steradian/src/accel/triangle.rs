//! Ray–triangle intersection (Möller–Trumbore).

use glam::{Vec2, Vec3};

use crate::geometry::Ray;

/// Möller–Trumbore test of `ray` against the triangle (p0, p1, p2). Returns the distance
/// `t ∈ (0, ray.t_max)` and the barycentrics (b1, b2) of the hit (the point is
/// `(1 − b1 − b2)·p0 + b1·p1 + b2·p2`). Degenerate triangles and rays in their plane miss.
#[inline]
pub fn intersect_triangle(p0: Vec3, p1: Vec3, p2: Vec3, ray: &Ray) -> Option<(f32, Vec2)> {
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let pv = ray.d.cross(e2);
    let det = e1.dot(pv);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let tv = ray.o - p0;
    let b1 = tv.dot(pv) * inv_det;
    if !(0.0..=1.0).contains(&b1) {
        return None;
    }
    let qv = tv.cross(e1);
    let b2 = ray.d.dot(qv) * inv_det;
    if !(b2 >= 0.0 && b1 + b2 <= 1.0) {
        return None;
    }
    let t = e2.dot(qv) * inv_det;
    (t > 0.0 && t < ray.t_max).then_some((t, Vec2::new(b1, b2)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_and_misses_outside() {
        let (a, b, c) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
        let r = Ray::infinite(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z);
        let (t, uv) = intersect_triangle(a, b, c, &r).unwrap();
        assert!((t - 2.0).abs() < 1e-6 && (uv - Vec2::new(0.25, 0.5)).length() < 1e-6);
        // back side hits too (no culling)
        let r2 = Ray::infinite(Vec3::new(0.25, 0.5, -2.0), Vec3::Z);
        assert!(intersect_triangle(a, b, c, &r2).is_some());
        assert!(intersect_triangle(a, b, c, &Ray::infinite(Vec3::new(0.6, 0.6, 2.0), -Vec3::Z)).is_none());
        assert!(intersect_triangle(a, b, c, &Ray::new(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z, 1.9)).is_none());
        assert!(intersect_triangle(a, b, c, &Ray::infinite(Vec3::new(0.25, 0.5, 2.0), Vec3::Z)).is_none());
        // degenerate
        assert!(intersect_triangle(a, b, b, &r).is_none());
    }
}
