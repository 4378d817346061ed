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
        let (exl, eyl) = (ex.length(), ey.length());
        let x = ex / exl;
        let y = ey / eyl;
        let mut z = x.cross(y);
        let d = corner - o;
        let mut z0 = d.dot(z);
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let (x1, y1) = (x0 + exl, y0 + eyl);
        let v00 = Vec3::new(x0, y0, z0);
        let v01 = Vec3::new(x0, y1, z0);
        let v10 = Vec3::new(x1, y0, z0);
        let v11 = Vec3::new(x1, y1, z0);
        // normals of the four great-circle edges, and the interior angles between them
        let n0 = v00.cross(v10).normalize();
        let n1 = v10.cross(v11).normalize();
        let n2 = v11.cross(v01).normalize();
        let n3 = v01.cross(v00).normalize();
        let angle = |a: Vec3, b: Vec3| (-a.dot(b)).clamp(-1.0, 1.0).acos();
        let (g0, g1, g2, g3) = (angle(n0, n1), angle(n1, n2), angle(n2, n3), angle(n3, n0));
        let k = TAU - g2 - g3;
        SphericalRectangle { o, x, y, z, x0, x1, y0, y1, z0, b0: n0.z, b1: n2.z, k, solid_angle: g0 + g1 - k }
    }

    /// The point of the rectangle in direction u ∈ [0, 1)² (density 1/S per steradian).
    pub fn sample(&self, u: Vec2) -> Vec3 {
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
        self.o + xu * self.x + yv * self.y + self.z0 * self.z
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
        for o in [Vec3::ZERO, Vec3::new(0.3, -2.0, 0.4), Vec3::new(5.0, 3.0, -1.0), Vec3::new(0.1, 1.25, -0.2)] {
            let sr = SphericalRectangle::new(o, c, ex, ey);
            let v = |p: Vec3| DVec3::new(p.x as f64, p.y as f64, p.z as f64);
            let expect = radiometry::quad_solid_angle(v(o), v(c), v(c + ex), v(c + ex + ey), v(c + ey));
            assert!((sr.solid_angle as f64 - expect).abs() <= 1e-4 * expect + 1e-6, "o = {o}: {} vs {expect}", sr.solid_angle);
        }
    }

    /// The samples lie on the rectangle, and estimate the rectangle's irradiance at a point
    /// (∫cos θ dω by 1/S-density samples) to within 4 standard errors of the closed form
    /// for a corner-aligned parallel rectangle.
    #[test]
    fn samples_are_uniform_in_solid_angle() {
        let (a, b, h) = (0.8f32, 1.3f32, 0.6f32);
        // rectangle [0, a] × [0, b] at height h above the origin, facing down
        let sr = SphericalRectangle::new(Vec3::ZERO, Vec3::new(0.0, 0.0, h), Vec3::new(a, 0.0, 0.0), Vec3::new(0.0, b, 0.0));
        let mut rng = Pcg32::new(3, 1);
        let n = 200_000;
        let (mut s1, mut s2) = (0f64, 0f64);
        for _ in 0..n {
            let p = sr.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            assert!((p.z - h).abs() < 1e-5 && (-1e-5..=a + 1e-5).contains(&p.x) && (-1e-5..=b + 1e-5).contains(&p.y), "{p}");
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
        let (c, ex, ey) = (Vec3::new(-0.5, -0.5, 1.0), Vec3::new(1.5, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
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
}
