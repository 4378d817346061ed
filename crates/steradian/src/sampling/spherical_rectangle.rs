//! Uniform sampling of the solid angle a rectangle subtends (Ureña, Fajardo & King 2013, "An
//! Area-Preserving Parametrization for Spherical Rectangles").
//!
//! Seen from a point o, a rectangle covers a spherical rectangle of solid angle S (sr). The
//! map from the unit square to it is area-preserving, so directions are drawn with the
//! constant density 1/S per steradian: the irradiance from a uniform rectangular emitter is
//! then estimated with only the cosine at o left to vary, where uniform *area* sampling also
//! carries the 1/r² and the emitter-side cosine. The computation runs in the rectangle's own
//! frame: x and y along its edges, z the normal pointing away from o.

use glam::{Vec2, Vec3};

use std::f32::consts::TAU;

use crate::geometry::trig::acos;

/// A rectangle's own frame, computed once per rectangle: the corner, unit vectors along its
/// two (perpendicular) edges, their normal, and the edge lengths (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectangleFrame {
    corner: Vec3,
    x: Vec3,
    y: Vec3,
    z: Vec3,
    x_len: f32,
    y_len: f32,
}

impl RectangleFrame {
    /// The rectangle `corner + [0, 1]·ex + [0, 1]·ey` (ex ⊥ ey).
    pub fn new(corner: Vec3, ex: Vec3, ey: Vec3) -> Self {
        let (x_len, y_len) = (ex.length(), ey.length());
        let (x, y) = (ex / x_len, ey / y_len);
        RectangleFrame { corner, x, y, z: x.cross(y), x_len, y_len }
    }

    /// Squared distance from `p` to the nearest point of the rectangle, m².
    pub fn distance_squared(&self, p: Vec3) -> f32 {
        let d = p - self.corner;
        let (u, v) = (d.dot(self.x), d.dot(self.y));
        let du = u - u.clamp(0.0, self.x_len);
        let dv = v - v.clamp(0.0, self.y_len);
        let h = d.dot(self.z);
        du * du + dv * dv + h * h
    }
}

/// A rectangle as seen from a reference point, ready to be sampled.
#[derive(Clone, Copy, Debug)]
pub struct SphericalRectangle {
    o: Vec3,
    x: Vec3,
    y: Vec3,
    z: Vec3,
    /// Coordinates of the rectangle's corners relative to `o` in the (x, y, z) frame:
    /// x ∈ [x0, x1], y ∈ [y0, y1], z = z0 ≤ 0.
    x0: f32,
    x1: f32,
    y0: f32,
    y1: f32,
    z0: f32,
    b0: f32,
    b1: f32,
    k: f32,
    /// Solid angle, sr.
    pub solid_angle: f32,
}

impl SphericalRectangle {
    /// The rectangle `corner + [0, 1]·ex + [0, 1]·ey` (ex ⊥ ey) seen from `o`.
    pub fn new(o: Vec3, corner: Vec3, ex: Vec3, ey: Vec3) -> Self {
        Self::from_frame(o, &RectangleFrame::new(corner, ex, ey))
    }

    /// The rectangle of `frame` seen from `o`.
    #[inline]
    pub fn from_frame(o: Vec3, frame: &RectangleFrame) -> Self {
        let (x, y) = (frame.x, frame.y);
        let mut z = frame.z;
        let d = frame.corner - o;
        let mut z0 = d.dot(z);
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let (x1, y1) = (x0 + frame.x_len, y0 + frame.y_len);
        // Normals of the four great-circle edges through the corners v00 → v10 → v11 → v01,
        // in closed form (each is the cross product of two adjacent corners, normalised):
        // n0 = (0, z0, −y0)/|·|, n1 = (−z0, 0, x1)/|·|, n2 = (0, −z0, y1)/|·|,
        // n3 = (z0, 0, −x0)/|·|.
        let z02 = z0 * z0;
        let r0 = (z02 + y0 * y0).sqrt().recip();
        let r1 = (z02 + x1 * x1).sqrt().recip();
        let r2 = (z02 + y1 * y1).sqrt().recip();
        let r3 = (z02 + x0 * x0).sqrt().recip();
        // interior angles g_i = acos(−n_i·n_{i+1})
        let g0 = acos(y0 * x1 * r0 * r1);
        let g1 = acos(-x1 * y1 * r1 * r2);
        let g2 = acos(y1 * x0 * r2 * r3);
        let g3 = acos(-x0 * y0 * r3 * r0);
        let k = TAU - g2 - g3;
        SphericalRectangle {
            o,
            x,
            y,
            z,
            x0,
            x1,
            y0,
            y1,
            z0,
            b0: -y0 * r0,
            b1: y1 * r2,
            k,
            solid_angle: g0 + g1 - k,
        }
    }

    /// The point of the rectangle in direction u ∈ [0, 1)² (density 1/S per steradian).
    pub fn sample(&self, u: Vec2) -> Vec3 {
        self.sample_with_uv(u).0
    }

    /// [`SphericalRectangle::sample`], with the point's fractions (s, t) ∈ [0, 1]² along the
    /// two edges (`corner + s·ex + t·ey`): the rectangle's uv, with no inverse transform.
    #[inline]
    pub fn sample_with_uv(&self, u: Vec2) -> (Vec3, Vec2) {
        // the x coordinate: invert the solid angle of the sub-rectangle [x0, xu]
        let au = u.x * self.solid_angle + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = ((fu * fu + self.b0 * self.b0).sqrt().recip().copysign(fu)).clamp(-1.0, 1.0);
        let xu = (-(cu * self.z0) / (1.0 - cu * cu).max(0.0).sqrt()).clamp(self.x0, self.x1);
        let xu = if xu.is_finite() { xu } else { self.x0 };
        // then y, uniformly in the sine of the elevation along that column
        let d = (xu * xu + self.z0 * self.z0).sqrt();
        let h0 = self.y0 / (d * d + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (d * d + self.y1 * self.y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-6 { (hv * d) / (1.0 - hv2).sqrt() } else { self.y1 };
        let yv = yv.clamp(self.y0, self.y1);
        let p = self.o + xu * self.x + yv * self.y + self.z0 * self.z;
        let uv =
            Vec2::new((xu - self.x0) / (self.x1 - self.x0), (yv - self.y0) / (self.y1 - self.y0));
        (p, uv.clamp(Vec2::ZERO, Vec2::ONE))
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::radiometry;
    use crate::sampling::Pcg32;

    fn rect() -> (Vec3, Vec3, Vec3) {
        (Vec3::new(-0.3, 1.2, -0.5), Vec3::new(1.0, 0.0, 0.2), Vec3::new(-0.1, 0.0, 0.5))
    }

    #[test]
    fn solid_angle_matches_the_closed_form() {
        let (c, ex, ey) = rect();
        for o in [
            Vec3::ZERO,
            Vec3::new(0.3, -2.0, 0.4),
            Vec3::new(5.0, 3.0, -1.0),
            Vec3::new(0.1, 1.25, -0.2),
        ] {
            let sr = SphericalRectangle::new(o, c, ex, ey);
            let v = |p: Vec3| DVec3::new(p.x as f64, p.y as f64, p.z as f64);
            let expect =
                radiometry::quad_solid_angle(v(o), v(c), v(c + ex), v(c + ex + ey), v(c + ey));
            assert!(
                (sr.solid_angle as f64 - expect).abs() <= 1e-4 * expect + 1e-6,
                "o = {o}: {} vs {expect}",
                sr.solid_angle
            );
        }
    }

    /// The samples lie on the rectangle, and estimate the rectangle's irradiance at a point
    /// (∫cos θ dω by 1/S-density samples) to within 4 standard errors of the closed form
    /// for a corner-aligned parallel rectangle.
    #[test]
    fn samples_are_uniform_in_solid_angle() {
        let (a, b, h) = (0.8f32, 1.3f32, 0.6f32);
        // rectangle [0, a] × [0, b] at height h above the origin, facing down
        let sr = SphericalRectangle::new(
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, h),
            Vec3::new(a, 0.0, 0.0),
            Vec3::new(0.0, b, 0.0),
        );
        let mut rng = Pcg32::new(3, 1);
        let n = 200_000;
        let (mut s1, mut s2) = (0f64, 0f64);
        for _ in 0..n {
            let p = sr.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            assert!(
                (p.z - h).abs() < 1e-5
                    && (-1e-5..=a + 1e-5).contains(&p.x)
                    && (-1e-5..=b + 1e-5).contains(&p.y),
                "{p}"
            );
            let v = (p.normalize().z * sr.solid_angle) as f64;
            s1 += v;
            s2 += v * v;
        }
        let mean = s1 / n as f64;
        let se = ((s2 / n as f64 - mean * mean) / (n as f64 - 1.0)).sqrt();
        // E for L = 1 is the closed-form corner irradiance
        let expect = radiometry::rect_parallel_corner_irradiance(1.0, a as f64, b as f64, h as f64);
        assert!((mean - expect).abs() <= 4.0 * se + 1e-6, "{mean} ± {se} vs {expect}");
    }

    /// Uniformity: the fraction of samples landing in the sub-rectangle [0, a/2] × [0, b/2]
    /// equals its share of the solid angle (a binomial test at 4σ).
    #[test]
    fn sub_rectangle_gets_its_share() {
        let o = Vec3::new(0.2, -0.4, 0.0);
        let (c, ex, ey) =
            (Vec3::new(-0.5, -0.5, 1.0), Vec3::new(1.5, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
        let sr = SphericalRectangle::new(o, c, ex, ey);
        let sub = SphericalRectangle::new(o, c, ex * 0.5, ey * 0.5);
        let p = (sub.solid_angle / sr.solid_angle) as f64;
        let mut rng = Pcg32::new(9, 2);
        let n = 100_000;
        let mut hits = 0;
        for _ in 0..n {
            let q = sr.sample(Vec2::new(rng.next_f32(), rng.next_f32())) - c;
            if q.x < 0.75 && q.y < 0.5 {
                hits += 1;
            }
        }
        let se = (p * (1.0 - p) / n as f64).sqrt();
        let f = hits as f64 / n as f64;
        assert!((f - p).abs() <= 4.0 * se, "{f} vs {p} ± {se}");
    }
    #[test]
    fn sampled_uv_locates_the_point() {
        let (c, ex, ey) = rect();
        let sr = SphericalRectangle::new(Vec3::new(0.3, -2.0, 0.4), c, ex, ey);
        let mut rng = Pcg32::new(5, 3);
        for _ in 0..1000 {
            let (p, uv) = sr.sample_with_uv(Vec2::new(rng.next_f32(), rng.next_f32()));
            let q = c + uv.x * ex + uv.y * ey;
            assert!((p - q).length() < 1e-5, "{p} vs {q} at uv {uv}");
        }
    }
}
