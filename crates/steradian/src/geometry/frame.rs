use super::is_positive;
use glam::Vec3;

/// An orthonormal frame (s, t, n). Converts between world space and a local space in which
/// `n` is +z, so that `to_local(w).z = cos θ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit normal `n` (Duff et al. 2017, "Building an orthonormal basis,
    /// revisited": branchless and continuous except across n.z = 0 sign flips).
    #[inline]
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// A frame around `n` whose first axis follows the tangent `dpdu` as closely as possible
    /// (Gram–Schmidt); falls back to [`Frame::from_normal`] when `dpdu` is degenerate.
    pub fn from_normal_tangent(n: Vec3, dpdu: Vec3) -> Self {
        let s = dpdu - n * n.dot(dpdu);
        let len2 = s.length_squared();
        if !is_positive(len2 - 1e-20) || !len2.is_finite() {
            return Self::from_normal(n);
        }
        let s = s / len2.sqrt();
        Frame { s, t: n.cross(s), n }
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_and_invert() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.4, 0.866).normalize(),
            Vec3::new(1e-8, 0.0, -1.0).normalize(),
        ] {
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-5);
            assert!((f.t.length() - 1.0).abs() < 1e-5);
            assert!(
                f.s.dot(f.t).abs() < 1e-5 && f.s.dot(n).abs() < 1e-5 && f.t.dot(n).abs() < 1e-5
            );
            // right-handed: s × t = n
            assert!((f.s.cross(f.t) - n).length() < 1e-5);
            let v = Vec3::new(0.2, -0.7, 0.5);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-5);
            assert!((f.to_local(n) - Vec3::Z).length() < 1e-5);
        }
    }
}
