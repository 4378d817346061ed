use std::fmt;

use glam::{Mat3, Mat4, Vec3, Vec4};

use super::is_positive;
use super::{Aabb, Ray};

/// An affine (or projective) transform with its inverse. Points, vectors and normals
/// transform differently: normals use the inverse transpose so they stay perpendicular to
/// transformed tangents.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub m: Mat4,
    pub inv: Mat4,
}

/// Why a matrix cannot be a transform.
#[derive(Clone, Debug, PartialEq)]
pub enum TransformError {
    NotFinite,
    Singular,
}

impl fmt::Display for TransformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TransformError::NotFinite => write!(f, "the matrix has a NaN or infinite entry"),
            TransformError::Singular => write!(f, "the matrix is singular (not invertible)"),
        }
    }
}

impl std::error::Error for TransformError {}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform { m: Mat4::IDENTITY, inv: Mat4::IDENTITY };

    /// A transform from a matrix, checked to be finite and invertible.
    pub fn from_matrix(m: Mat4) -> Result<Self, TransformError> {
        if !m.is_finite() {
            return Err(TransformError::NotFinite);
        }
        let det = m.determinant();
        if det == 0.0 || !det.is_finite() {
            return Err(TransformError::Singular);
        }
        let inv = m.inverse();
        if !inv.is_finite() {
            return Err(TransformError::Singular);
        }
        Ok(Transform { m, inv })
    }

    /// From 16 numbers in row-major order (Mitsuba's `<matrix value="..."/>`).
    pub fn from_row_major(v: &[f32; 16]) -> Result<Self, TransformError> {
        Self::from_matrix(Mat4::from_cols_array(v).transpose())
    }

    pub fn translate(t: Vec3) -> Self {
        Transform { m: Mat4::from_translation(t), inv: Mat4::from_translation(-t) }
    }

    /// Scale; fails for a zero factor.
    pub fn scale(s: Vec3) -> Result<Self, TransformError> {
        Self::from_matrix(Mat4::from_scale(s))
    }

    /// Right-handed rotation by `angle_deg` degrees about `axis` (Mitsuba's `<rotate>`).
    pub fn rotate(axis: Vec3, angle_deg: f32) -> Result<Self, TransformError> {
        let len = axis.length();
        if !is_positive(len) || !angle_deg.is_finite() {
            return Err(TransformError::Singular);
        }
        let r = Mat4::from_axis_angle(axis / len, angle_deg.to_radians());
        Ok(Transform { m: r, inv: r.transpose() })
    }

    /// Mitsuba's `lookat`: maps +z to the viewing direction, +y to (orthogonalised) `up`
    /// and +x to `left = up × dir`, with the origin at `origin`.
    pub fn look_at(origin: Vec3, target: Vec3, up: Vec3) -> Result<Self, TransformError> {
        let dir = target - origin;
        if !is_positive(dir.length_squared()) {
            return Err(TransformError::Singular);
        }
        let dir = dir.normalize();
        let left = up.cross(dir);
        if !is_positive(left.length_squared()) {
            return Err(TransformError::Singular);
        }
        let left = left.normalize();
        let new_up = dir.cross(left);
        let m = Mat4::from_cols(
            left.extend(0.0),
            new_up.extend(0.0),
            dir.extend(0.0),
            origin.extend(1.0),
        );
        Self::from_matrix(m)
    }

    /// `self · other`: apply `other` first, then `self`.
    #[inline]
    pub fn then_after(&self, other: &Transform) -> Transform {
        Transform { m: self.m * other.m, inv: other.inv * self.inv }
    }

    /// `other · self`: apply `self` first, then `other` (document order of Mitsuba's
    /// `<transform>` children: each new operation is left-multiplied).
    #[inline]
    pub fn then(&self, other: &Transform) -> Transform {
        other.then_after(self)
    }

    #[inline]
    pub fn inverse(&self) -> Transform {
        Transform { m: self.inv, inv: self.m }
    }

    #[inline]
    pub fn is_identity(&self) -> bool {
        self.m == Mat4::IDENTITY
    }

    /// Transforms a point (with the projective divide when the last row is not (0,0,0,1)).
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        let r = self.m * Vec4::new(p.x, p.y, p.z, 1.0);
        if r.w == 1.0 {
            r.truncate()
        } else {
            r.truncate() / r.w
        }
    }

    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.m.transform_vector3(v)
    }

    /// Transforms a normal with the inverse transpose (not normalised).
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        Mat3::from_mat4(self.inv).transpose() * n
    }

    /// The translation part.
    #[inline]
    pub fn translation(&self) -> Vec3 {
        self.m.w_axis.truncate()
    }

    /// The linear (3×3) part.
    #[inline]
    pub fn linear(&self) -> Mat3 {
        Mat3::from_mat4(self.m)
    }

    /// True when the linear part flips orientation (negative determinant).
    #[inline]
    pub fn flips_handedness(&self) -> bool {
        self.linear().determinant() < 0.0
    }

    /// Lengths of the images of the unit axes (the scale factors when there is no shear).
    pub fn axis_scales(&self) -> Vec3 {
        let l = self.linear();
        Vec3::new(l.x_axis.length(), l.y_axis.length(), l.z_axis.length())
    }

    /// Transforms a ray; the direction is renormalised and `t_max` rescaled to keep `t` a
    /// distance.
    pub fn ray(&self, r: &Ray) -> Ray {
        let d = self.vector(r.d);
        let len = d.length();
        Ray::new(self.point(r.o), d / len, r.t_max * len)
    }

    /// Bounds of the transformed box (transforms its 8 corners).
    pub fn aabb(&self, b: &Aabb) -> Aabb {
        let mut out = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            out.grow(self.point(c));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn document_order_is_left_multiplication() {
        // <scale/><rotate/><translate/> means M = T·R·S.
        let s = Transform::scale(Vec3::new(2.0, 1.0, 1.0)).unwrap();
        let r = Transform::rotate(Vec3::Z, 90.0).unwrap();
        let t = Transform::translate(Vec3::new(0.0, 0.0, 5.0));
        let m = Transform::IDENTITY.then(&s).then(&r).then(&t);
        // x = (1,0,0) → scaled (2,0,0) → rotated (0,2,0) → translated (0,2,5)
        assert!(close(m.point(Vec3::X), Vec3::new(0.0, 2.0, 5.0)));
        assert!(close(m.inverse().point(Vec3::new(0.0, 2.0, 5.0)), Vec3::X));
    }

    #[test]
    fn rotation_is_right_handed_in_degrees() {
        let r = Transform::rotate(Vec3::X, 90.0).unwrap();
        // right-handed about +x: +y → +z, +z → −y
        assert!(close(r.vector(Vec3::Y), Vec3::Z));
        assert!(close(r.vector(Vec3::Z), -Vec3::Y));
    }

    #[test]
    fn normals_use_the_inverse_transpose() {
        // A plane tilted 45° and stretched along x: the normal must stay perpendicular.
        let m = Transform::scale(Vec3::new(3.0, 1.0, 1.0)).unwrap();
        let tangent = Vec3::new(1.0, 0.0, -1.0);
        let n = Vec3::new(1.0, 0.0, 1.0);
        assert!(m.vector(tangent).dot(m.normal(n)).abs() < 1e-6);
    }

    #[test]
    fn lookat_matches_mitsuba_frame() {
        // Camera at +z looking at the origin with +y up: local +z → −z world, local +x
        // (= left) → up × dir = (0,1,0) × (0,0,−1) = (−1,0,0).
        let m = Transform::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y).unwrap();
        assert!(close(m.vector(Vec3::Z), -Vec3::Z));
        assert!(close(m.vector(Vec3::X), -Vec3::X));
        assert!(close(m.vector(Vec3::Y), Vec3::Y));
        assert!(close(m.point(Vec3::ZERO), Vec3::new(0.0, 0.0, 3.9)));
    }

    #[test]
    fn degenerate_matrices_are_refused() {
        assert_eq!(Transform::scale(Vec3::new(1.0, 0.0, 1.0)), Err(TransformError::Singular));
        let mut v = [0.0f32; 16];
        v[0] = f32::NAN;
        assert_eq!(Transform::from_row_major(&v), Err(TransformError::NotFinite));
        assert!(Transform::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y).is_err());
    }

    #[test]
    fn row_major_matrix_reads_translation_from_last_column() {
        let v = [1.0, 0.0, 0.0, 7.0, 0.0, 1.0, 0.0, 8.0, 0.0, 0.0, 1.0, 9.0, 0.0, 0.0, 0.0, 1.0];
        let m = Transform::from_row_major(&v).unwrap();
        assert!(close(m.point(Vec3::ZERO), Vec3::new(7.0, 8.0, 9.0)));
    }
}
