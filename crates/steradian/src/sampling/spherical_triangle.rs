//! Uniform sampling of the solid angle a triangle subtends (Arvo 1995, "Stratified Sampling of
//! Spherical Triangles").
//!
//! Seen from a point o, a triangle covers a spherical triangle ABC of solid angle Ω (sr). Arvo's
//! map from the unit square to it is area-preserving: u₁ picks the sub-triangle ABĈ whose area
//! is u₁·Ω (Ĉ on the arc AC), u₂ picks the point on the arc BĈ so that the density along it is
//! uniform in solid angle. Directions therefore have the constant density 1/Ω per steradian,
//! and the irradiance of a uniform triangular emitter is estimated with only the receiver's
//! cosine left to vary (area sampling also carries the 1/r² and the emitter's cosine).
//!
//! The computation runs in f64: the angle at A and the side AB enter through differences of
//! nearly equal cosines for small triangles. Callers fall back to area sampling when Ω is too
//! small (see [`SphericalTriangle::USEFUL`]) for the parametrisation to stay accurate in f32
//! outputs.

use glam::{DVec3, Vec2, Vec3};

/// A triangle as seen from a reference point, ready to be sampled.
#[derive(Clone, Copy, Debug)]
pub struct SphericalTriangle {
    /// Unit directions from the reference point to the three vertices.
    a: DVec3,
    b: DVec3,
    c: DVec3,
    /// Interior angle at A, rad.
    alpha: f64,
    /// cos of the side AB (the arc between A and B).
    cos_ab: f64,
    /// Solid angle Ω, sr.
    solid_angle: f64,
}

impl SphericalTriangle {
    /// Solid angles (sr) within which solid-angle sampling is used: below, the triangle is a
    /// near-point where area sampling is as good (and the parametrisation loses precision);
    /// above, it covers nearly a hemisphere.
    pub const USEFUL: std::ops::Range<f64> = 3e-4..6.22;

    /// The triangle (p0, p1, p2) seen from `o`; `None` when it is degenerate from there
    /// (zero solid angle, or `o` in its plane).
    pub fn new(o: Vec3, p0: Vec3, p1: Vec3, p2: Vec3) -> Option<Self> {
        let o = o.as_dvec3();
        let a = (p0.as_dvec3() - o).try_normalize()?;
        let b = (p1.as_dvec3() - o).try_normalize()?;
        let c = (p2.as_dvec3() - o).try_normalize()?;
        // Van Oosterom–Strackee: tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a), stable for
        // small triangles where the angle-sum formula α + β + γ − π cancels
        let triple = a.dot(b.cross(c)).abs();
        let solid_angle = 2.0 * triple.atan2(1.0 + a.dot(b) + b.dot(c) + c.dot(a));
        if solid_angle.is_nan() || solid_angle <= 0.0 {
            return None;
        }
        // the angle at A between the great circles AB and AC
        let n_ab = a.cross(b).try_normalize()?;
        let n_ac = a.cross(c).try_normalize()?;
        let alpha = n_ab.dot(n_ac).clamp(-1.0, 1.0).acos();
        Some(SphericalTriangle { a, b, c, alpha, cos_ab: a.dot(b), solid_angle })
    }

    /// Solid angle, sr.
    pub fn solid_angle(&self) -> f64 {
        self.solid_angle
    }

    /// The unit direction for u ∈ [0, 1)² (density 1/Ω per steradian).
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let (a, b, c) = (self.a, self.b, self.c);
        let (sin_alpha, cos_alpha) = self.alpha.sin_cos();
        // 1. Ĉ on the arc AC such that the spherical triangle ABĈ has area u₁·Ω
        let area_hat = u.x as f64 * self.solid_angle;
        let (s, t) = (area_hat - self.alpha).sin_cos();
        let uu = t - cos_alpha;
        let v = s + sin_alpha * self.cos_ab;
        let q =
            (((v * t - uu * s) * cos_alpha - v) / ((v * s + uu * t) * sin_alpha)).clamp(-1.0, 1.0);
        let c_perp = (c - c.dot(a) * a).normalize_or_zero();
        let c_hat = q * a + (1.0 - q * q).max(0.0).sqrt() * c_perp;
        // 2. the point on the arc from B to Ĉ, uniform in solid angle: cos θ (from B) linear in u₂
        let z = 1.0 - u.y as f64 * (1.0 - c_hat.dot(b));
        let d_perp = (c_hat - c_hat.dot(b) * b).normalize_or_zero();
        let w = z * b + (1.0 - z * z).max(0.0).sqrt() * d_perp;
        w.normalize().as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radiometry;
    use crate::sampling::Pcg32;

    /// Where the ray o + t·w crosses the plane of (p0, p1, p2): barycentrics (b1, b2).
    fn barycentrics(o: Vec3, w: Vec3, p0: Vec3, p1: Vec3, p2: Vec3) -> Option<(f64, f64)> {
        let (o, w) = (o.as_dvec3(), w.as_dvec3());
        let (p0, e1, e2) = (p0.as_dvec3(), (p1 - p0).as_dvec3(), (p2 - p0).as_dvec3());
        let n = e1.cross(e2);
        let t = n.dot(p0 - o) / n.dot(w);
        if t.is_nan() || t <= 0.0 {
            return None;
        }
        let q = o + t * w - p0;
        // solve q = b1·e1 + b2·e2 by the normal equations
        let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (q1, q2) = (q.dot(e1), q.dot(e2));
        let det = d11 * d22 - d12 * d12;
        Some(((q1 * d22 - q2 * d12) / det, (q2 * d11 - q1 * d12) / det))
    }

    fn tri() -> (Vec3, Vec3, Vec3) {
        (Vec3::new(-0.4, 1.0, -0.3), Vec3::new(0.9, 1.3, 0.1), Vec3::new(0.2, 0.8, 0.9))
    }

    #[test]
    fn solid_angle_matches_the_closed_form() {
        let (p0, p1, p2) = tri();
        for o in [Vec3::ZERO, Vec3::new(0.3, -2.0, 0.4), Vec3::new(5.0, 3.0, -1.0)] {
            let st = SphericalTriangle::new(o, p0, p1, p2).unwrap();
            let expect = radiometry::triangle_solid_angle(
                o.as_dvec3(),
                p0.as_dvec3(),
                p1.as_dvec3(),
                p2.as_dvec3(),
            );
            assert!(
                (st.solid_angle() - expect).abs() <= 1e-9 * expect,
                "{} vs {expect}",
                st.solid_angle()
            );
        }
        // seen from a vertex: degenerate
        assert!(SphericalTriangle::new(p0, p0, p1, p2).is_none());
    }

    /// Every sample points into the triangle, and each of the four sub-triangles cut by the edge
    /// midpoints gets its share of the solid angle (binomial tests at 4σ): the density is
    /// uniform in solid angle.
    #[test]
    fn samples_are_uniform_in_solid_angle() {
        let (p0, p1, p2) = tri();
        for (k, o) in [Vec3::ZERO, Vec3::new(0.1, 0.2, 0.1), Vec3::new(-3.0, 0.5, 2.0)]
            .into_iter()
            .enumerate()
        {
            let st = SphericalTriangle::new(o, p0, p1, p2).unwrap();
            let (m01, m12, m20) = ((p0 + p1) / 2.0, (p1 + p2) / 2.0, (p2 + p0) / 2.0);
            let subs = [(p0, m01, m20), (m01, p1, m12), (m20, m12, p2), (m01, m12, m20)];
            let mut counts = [0usize; 4];
            let mut rng = Pcg32::new(17 + k as u64, 5);
            let n = 100_000;
            for _ in 0..n {
                let w = st.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
                assert!((w.length() - 1.0).abs() < 1e-5);
                let (b1, b2) =
                    barycentrics(o, w, p0, p1, p2).expect("sample misses the triangle's plane");
                assert!(
                    b1 >= -1e-4 && b2 >= -1e-4 && b1 + b2 <= 1.0 + 1e-4,
                    "({b1}, {b2}) outside the triangle"
                );
                // which sub-triangle: corners by barycentric thresholds, else the middle one
                let b0 = 1.0 - b1 - b2;
                let i = if b0 > 0.5 {
                    0
                } else if b1 > 0.5 {
                    1
                } else if b2 > 0.5 {
                    2
                } else {
                    3
                };
                counts[i] += 1;
            }
            for (i, (a, b, c)) in subs.into_iter().enumerate() {
                let share = radiometry::triangle_solid_angle(
                    o.as_dvec3(),
                    a.as_dvec3(),
                    b.as_dvec3(),
                    c.as_dvec3(),
                ) / st.solid_angle();
                let f = counts[i] as f64 / n as f64;
                let se = (share * (1.0 - share) / n as f64).sqrt();
                assert!(
                    (f - share).abs() <= 4.0 * se,
                    "o = {o}, sub-triangle {i}: {f} vs {share} ± {se}"
                );
            }
        }
    }

    /// The corners of the unit square map to the triangle's vertices and edges.
    #[test]
    fn square_corners_map_to_the_vertices() {
        let (p0, p1, p2) = tri();
        let o = Vec3::new(0.2, -0.5, 0.3);
        let st = SphericalTriangle::new(o, p0, p1, p2).unwrap();
        let dir = |p: Vec3| (p - o).normalize();
        assert!((st.sample(Vec2::new(0.3, 0.0)) - dir(p1)).length() < 1e-5, "u₂ = 0 gives B");
        assert!(
            (st.sample(Vec2::new(0.0, 1.0)) - dir(p0)).length() < 1e-4,
            "u₁ = 0, u₂ = 1 gives A"
        );
        assert!(
            (st.sample(Vec2::new(1.0, 1.0)) - dir(p2)).length() < 1e-4,
            "u₁ = 1, u₂ = 1 gives C"
        );
    }
}
