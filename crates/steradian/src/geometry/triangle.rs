//! Watertight ray–triangle intersection (Woop, Benthin & Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1), 2013).
//!
//! The ray is turned into the +z axis of a sheared frame (the axis `kz` of the largest
//! |direction| component becomes z, and x, y are sheared so that the direction is (0, 0, 1)).
//! Vertices are translated by the ray origin and sheared the same way; the 2-D edge functions
//! U, V, W of the projected triangle then decide the hit. Two triangles sharing an edge compute
//! the same edge function for it (same operands, same order), so a ray through the edge hits at
//! least one of them: no cracks. Edge functions that come out exactly 0 are recomputed in f64,
//! as the paper prescribes, so that the sign on an edge is exact.
//!
//! [`intersect_triangle`] is the scalar reference; the SIMD kernels of the BVH (`accel/simd.rs`) evaluate the
//! same operations in the same order on 4 triangles at once (no FMA contraction), so both give
//! bit-identical distances and barycentrics.

use glam::{Vec2, Vec3};

use super::Ray;

/// Per-ray constants of the watertight test.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    /// Axis permutation: `k[2]` is the axis of the largest |d| component.
    pub k: [usize; 3],
    /// Shear constants `(d[kx]/d[kz], d[ky]/d[kz], 1/d[kz])` (the first two as products with
    /// `1/d[kz]`).
    pub s: [f32; 3],
}

impl WatertightRay {
    #[inline]
    pub fn new(d: Vec3) -> Self {
        // The dominant axis and the permutation are computed without branches: for incoherent
        // rays (diffuse bounces) each comparison is a coin toss, which a branch would mispredict
        // half the time on the chain from one hit to the next ray.
        let a = d.abs();
        let x_dominant = (a.x >= a.y) & (a.x >= a.z);
        let z_over_y = (a.y < a.z) as usize;
        let kz = (!x_dominant as usize) * (1 + z_over_y);
        // keep the winding (sign of the edge functions) independent of the direction's sign:
        // (kx, ky) = (kz + 1, kz + 2) mod 3, swapped where d[kz] < 0
        let negative = (d[kz] < 0.0) as usize;
        let kx = (kz + 1 + negative) % 3;
        let ky = (kz + 2 - negative) % 3;
        // one division per ray instead of three
        let sz = 1.0 / d[kz];
        WatertightRay { k: [kx, ky, kz], s: [d[kx] * sz, d[ky] * sz, sz] }
    }
}

/// One triangle's watertight test for a prepared ray: `a`, `b`, `c` are the vertices minus the
/// ray origin, already permuted to (kx, ky, kz). Returns `(t, b1, b2)` with
/// `t_min < t < t_max`.
#[inline(always)]
pub(crate) fn watertight_core(
    a: [f32; 3],
    b: [f32; 3],
    c: [f32; 3],
    s: [f32; 3],
    t_min: f32,
    t_max: f32,
) -> Option<(f32, f32, f32)> {
    let (ax, ay) = (a[0] - s[0] * a[2], a[1] - s[1] * a[2]);
    let (bx, by) = (b[0] - s[0] * b[2], b[1] - s[1] * b[2]);
    let (cx, cy) = (c[0] - s[0] * c[2], c[1] - s[1] * c[2]);
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    if u == 0.0 || v == 0.0 || w == 0.0 {
        (u, v, w) = edge_functions_f64([ax, ay, bx, by, cx, cy]);
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let (az, bz, cz) = (s[2] * a[2], s[2] * b[2], s[2] * c[2]);
    let t_scaled = u * az + v * bz + w * cz;
    let rcp = 1.0 / det;
    let t = t_scaled * rcp;
    // NaN (degenerate or padding data) fails both comparisons
    (t > t_min && t < t_max).then_some((t, v * rcp, w * rcp))
}

/// The edge functions in double precision from the sheared f32 coordinates
/// `[ax, ay, bx, by, cx, cy]` (exact products: the sign is right even on an edge).
#[cold]
#[inline(never)]
pub(crate) fn edge_functions_f64(p: [f32; 6]) -> (f32, f32, f32) {
    let [ax, ay, bx, by, cx, cy] = p.map(f64::from);
    ((cx * by - cy * bx) as f32, (ax * cy - ay * cx) as f32, (bx * ay - by * ax) as f32)
}

/// Watertight test of `ray` against the triangle (p0, p1, p2) for `t ∈ (0, ray.t_max)`.
/// Returns the distance and the barycentrics (b1, b2) of the hit (the point is
/// `(1 − b1 − b2)·p0 + b1·p1 + b2·p2`). Both sides hit; degenerate triangles and rays in their
/// plane miss.
#[inline]
pub fn intersect_triangle(p0: Vec3, p1: Vec3, p2: Vec3, ray: &Ray) -> Option<(f32, Vec2)> {
    let wt = WatertightRay::new(ray.d);
    let rel = |p: Vec3| {
        let q = p - ray.o;
        [q[wt.k[0]], q[wt.k[1]], q[wt.k[2]]]
    };
    watertight_core(rel(p0), rel(p1), rel(p2), wt.s, 0.0, ray.t_max)
        .map(|(t, b1, b2)| (t, Vec2::new(b1, b2)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    #[test]
    fn hits_inside_and_misses_outside() {
        let (a, b, c) =
            (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
        let r = Ray::infinite(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z);
        let (t, uv) = intersect_triangle(a, b, c, &r).unwrap();
        assert!((t - 2.0).abs() < 1e-6 && (uv - Vec2::new(0.25, 0.5)).length() < 1e-6);
        // back side hits too (no culling)
        let r2 = Ray::infinite(Vec3::new(0.25, 0.5, -2.0), Vec3::Z);
        assert!(intersect_triangle(a, b, c, &r2).is_some());
        assert!(intersect_triangle(a, b, c, &Ray::infinite(Vec3::new(0.6, 0.6, 2.0), -Vec3::Z))
            .is_none());
        assert!(intersect_triangle(a, b, c, &Ray::new(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z, 1.9))
            .is_none());
        assert!(intersect_triangle(a, b, c, &Ray::infinite(Vec3::new(0.25, 0.5, 2.0), Vec3::Z))
            .is_none());
        // degenerate
        assert!(intersect_triangle(a, b, b, &r).is_none());
        // oblique ray: the barycentrics reproduce the hit point
        let o = Vec3::new(-1.0, 2.0, 3.0);
        let p = Vec3::new(0.2, 0.3, 0.0);
        let r3 = Ray::infinite(o, (p - o).normalize());
        let (t, uv) = intersect_triangle(a, b, c, &r3).unwrap();
        let q = a * (1.0 - uv.x - uv.y) + b * uv.x + c * uv.y;
        assert!((r3.at(t) - p).length() < 1e-5 && (q - p).length() < 1e-5, "{t} {uv}");
    }

    /// Rays through the shared edges and the shared vertex of a fan of triangles must hit at
    /// least one of them (Möller–Trumbore can let them through the crack).
    #[test]
    fn no_cracks_on_shared_edges_and_vertices() {
        let mut rng = Pcg32::new(7, 3);
        // a fan of 8 triangles around a centre vertex, slightly non-planar
        let centre = Vec3::new(0.1, 0.2, 0.05);
        let rim: Vec<Vec3> = (0..8)
            .map(|i| {
                let phi = i as f32 * std::f32::consts::TAU / 8.0;
                Vec3::new(phi.cos(), phi.sin(), 0.1 * (i % 3) as f32)
            })
            .collect();
        let tris: Vec<[Vec3; 3]> = (0..8).map(|i| [centre, rim[i], rim[(i + 1) % 8]]).collect();
        let mut tested = 0;
        for (i, &corner) in rim.iter().enumerate() {
            for _ in 0..500 {
                // a point on the shared edge centre–corner (or exactly the centre)
                let f = if tested % 50 == 0 { 0.0 } else { rng.next_f32() };
                let target = centre + (corner - centre) * f;
                let o = target
                    + Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 1.0 + rng.next_f32())
                        * 3.0;
                let ray = Ray::infinite(o, (target - o).normalize());
                let hit = tris.iter().any(|t| intersect_triangle(t[0], t[1], t[2], &ray).is_some());
                assert!(hit, "ray towards {target} (edge {i}, f {f}) slipped through");
                tested += 1;
            }
        }
    }
}
