//! The operations inside `<transform>`: `translate`, `rotate`, `scale`, `matrix`, `lookat`.
//!
//! Each operation becomes a core [`Transform`]; the parser composes them in document
//! order, each one left-multiplied (`<scale/><rotate/><translate/>` gives T·R·S). Unlike
//! Mitsuba, which lets NaN matrices and zero scales through, a degenerate operation is an
//! error at its element.
//!
//! `<rotate>` uses its axis as written, as Mitsuba 3 does: Mitsuba builds the Rodrigues matrix
//! cos θ·I + (1 − cos θ)·a aᵀ + sin θ·[a]ₓ from the unnormalised axis `a`, which is a rotation
//! only when |a| = 1 (axis (1, 1, 0) at 30° also stretches and shears). steradian builds the
//! same matrix, so such objects sit where Mitsuba puts them, and warns. Its inverse is the true
//! inverse (Mitsuba stores the transpose, which is the inverse only for a rotation), so normals
//! stay perpendicular to the stretched surfaces.

use glam::{Mat3, Mat4, Vec3};
use steradian::geometry::{Transform, TransformError};

use super::attrs::{tokenize, Attrs};
use crate::error::{LoadError, LoadWarning};

/// Parses one transform operation element (`op` is its tag name, after upgrade); what looks
/// unintended goes to `warnings`.
pub(super) fn parse_op(
    op: &str,
    attrs: &Attrs,
    warnings: &mut Vec<LoadWarning>,
) -> Result<Transform, LoadError> {
    match op {
        "translate" => {
            attrs.allow(&["x", "y", "z", "value"])?;
            let v = xyz(attrs, 0.0)?;
            Ok(Transform::translate(v))
        }
        "scale" => {
            attrs.allow(&["x", "y", "z", "value"])?;
            let v = xyz(attrs, 1.0)?;
            Transform::scale(v).map_err(|_| {
                attrs.error(format!(
                    "<scale> by ({}, {}, {}) makes the transform singular (a scale factor is zero)",
                    v.x, v.y, v.z
                ))
            })
        }
        "rotate" => {
            attrs.allow(&["x", "y", "z", "value", "angle"])?;
            let angle_attr = attrs.require("angle")?;
            let angle = attrs.number(angle_attr, angle_attr.value.trim())?;
            let axis = xyz(attrs, 0.0)?;
            if axis == Vec3::ZERO {
                return Err(attrs.error("<rotate> needs a non-zero axis (set x, y or z)"));
            }
            // within rounding of a unit axis: the rotation itself (and images of scenes with
            // axes such as (0.6, 0, 0.8) stay what they were)
            if (axis.length() - 1.0).abs() < 1e-5 {
                return Transform::rotate(axis, angle as f32)
                    .map_err(|_| attrs.error("invalid <rotate>"));
            }
            warnings.push(LoadWarning::at(
                &attrs.pos,
                format!(
                    "<rotate> axis ({}, {}, {}) has length {:.4}, not 1: Mitsuba 3 does not \
                     normalise it, so this stretches and shears as well as rotates (steradian \
                     does the same); normalise the axis for a pure rotation",
                    axis.x,
                    axis.y,
                    axis.z,
                    axis.length()
                ),
            ));
            Transform::from_matrix(rodrigues(axis, angle as f32))
                .map_err(|_| attrs.error("<rotate> about this axis is singular (not invertible)"))
        }
        "matrix" => {
            attrs.allow(&["value"])?;
            let a = attrs.require("value")?;
            let tokens = tokenize(&a.value);
            let mut v = Vec::with_capacity(16);
            for t in &tokens {
                v.push(attrs.number(a, t)? as f32);
            }
            let m: [f32; 16] = match v.len() {
                16 => v.try_into().unwrap_or([0.0; 16]),
                9 => [
                    v[0], v[1], v[2], 0.0, v[3], v[4], v[5], 0.0, v[6], v[7], v[8], 0.0, 0.0, 0.0,
                    0.0, 1.0,
                ],
                n => {
                    return Err(
                        attrs.error(format!("<matrix> needs 16 (4×4) or 9 (3×3) numbers, got {n}"))
                    )
                }
            };
            Transform::from_row_major(&m).map_err(|e| match e {
                TransformError::NotFinite => attrs.error("<matrix> has a NaN or infinite entry"),
                TransformError::Singular => attrs.error("<matrix> is singular (not invertible)"),
            })
        }
        "lookat" => {
            attrs.allow(&["origin", "target", "up"])?;
            let origin = vec3_attr(attrs, "origin")?;
            let target = vec3_attr(attrs, "target")?;
            let dir = target - origin;
            if dir.length_squared() == 0.0 {
                return Err(attrs.error("<lookat> origin and target are the same point"));
            }
            let up = match attrs.get("up") {
                Some(_) => vec3_attr(attrs, "up")?,
                // Mitsuba: a missing (or zero) up is the first vector of coordinate_system(dir).
                None => coordinate_system_first(dir.normalize()),
            };
            let up = if up == Vec3::ZERO { coordinate_system_first(dir.normalize()) } else { up };
            Transform::look_at(origin, target, up).map_err(|_| {
                attrs.error("<lookat> is degenerate: 'up' is parallel to the viewing direction")
            })
        }
        _ => Err(attrs.error(format!("unexpected transform operation <{op}>"))),
    }
}

/// `x`/`y`/`z` attributes (missing ones take `default`) or `value` (1 number, broadcast,
/// or 3 numbers). At least one attribute is required.
fn xyz(attrs: &Attrs, default: f64) -> Result<Vec3, LoadError> {
    if let Some(a) = attrs.get("value") {
        if attrs.get("x").is_some() || attrs.get("y").is_some() || attrs.get("z").is_some() {
            return Err(attrs
                .error(format!("<{}> can't mix 'value' with 'x'/'y'/'z' attributes", attrs.elem)));
        }
        let tokens = tokenize(&a.value);
        let nums = tokens.iter().map(|t| attrs.number(a, t)).collect::<Result<Vec<_>, _>>()?;
        return match nums.len() {
            1 => Ok(Vec3::splat(nums[0] as f32)),
            3 => Ok(Vec3::new(nums[0] as f32, nums[1] as f32, nums[2] as f32)),
            n => Err(LoadError::at(
                &a.pos,
                format!("'value' of <{}> must have 1 or 3 numbers, got {n}", attrs.elem),
            )),
        };
    }
    let mut out = [default; 3];
    let mut found = false;
    for (i, n) in ["x", "y", "z"].iter().enumerate() {
        if let Some(a) = attrs.get(n) {
            out[i] = attrs.number(a, a.value.trim())?;
            found = true;
        }
    }
    if !found {
        return Err(
            attrs.error(format!("<{}> needs 'value' or at least one of 'x', 'y', 'z'", attrs.elem))
        );
    }
    Ok(Vec3::new(out[0] as f32, out[1] as f32, out[2] as f32))
}

/// Mitsuba 3's rotation matrix about `axis` as given (unnormalised) by `angle_deg` degrees:
/// cos θ·I + (1 − cos θ)·a aᵀ + sin θ·[a]ₓ.
fn rodrigues(a: Vec3, angle_deg: f32) -> Mat4 {
    let (sin, cos) = angle_deg.to_radians().sin_cos();
    let c1 = 1.0 - cos;
    let m = Mat3::from_cols(
        Vec3::new(a.x * a.x * c1 + cos, a.x * a.y * c1 + a.z * sin, a.x * a.z * c1 - a.y * sin),
        Vec3::new(a.x * a.y * c1 - a.z * sin, a.y * a.y * c1 + cos, a.y * a.z * c1 + a.x * sin),
        Vec3::new(a.x * a.z * c1 + a.y * sin, a.y * a.z * c1 - a.x * sin, a.z * a.z * c1 + cos),
    );
    Mat4::from_mat3(m)
}

/// A required attribute of exactly 3 numbers (`origin="0, 0, 4"`).
fn vec3_attr(attrs: &Attrs, name: &str) -> Result<Vec3, LoadError> {
    let a = attrs.require(name)?;
    let tokens = tokenize(&a.value);
    if tokens.len() != 3 {
        return Err(LoadError::at(
            &a.pos,
            format!(
                "'{name}' of <{}> must have exactly 3 numbers, got {}",
                attrs.elem,
                tokens.len()
            ),
        ));
    }
    let mut v = [0.0f32; 3];
    for (i, t) in tokens.iter().enumerate() {
        v[i] = attrs.number(a, t)? as f32;
    }
    Ok(Vec3::from(v))
}

/// First tangent of Mitsuba's `coordinate_system(n)` (Duff et al. 2017).
fn coordinate_system_first(n: Vec3) -> Vec3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba 3.9.1's `ScalarTransform4f().rotate([1, 1, 0], 30).matrix`, row by row.
    #[test]
    fn unnormalised_axis_gives_mitsubas_matrix() {
        let m = rodrigues(Vec3::new(1.0, 1.0, 0.0), 30.0);
        let mitsuba = [[1.0, 0.133975, 0.5], [0.133975, 1.0, -0.5], [-0.5, 0.5, 0.866025]];
        for (r, row) in mitsuba.iter().enumerate() {
            for (c, want) in row.iter().enumerate() {
                let got = m.col(c)[r];
                assert!((got - want).abs() < 1e-6, "m[{r}][{c}] = {got}, Mitsuba {want}");
            }
        }
        // a unit axis gives the rotation the normalised path builds
        let axis = Vec3::new(0.6, 0.0, 0.8);
        let r = Mat4::from_axis_angle(axis, 40f32.to_radians());
        assert!(rodrigues(axis, 40.0).abs_diff_eq(r, 1e-6));
    }

    #[test]
    fn coordinate_system_is_orthonormal() {
        for n in [Vec3::Z, -Vec3::Z, Vec3::X, Vec3::new(1.0, 2.0, -3.0).normalize()] {
            let s = coordinate_system_first(n);
            assert!((s.length() - 1.0).abs() < 1e-5);
            assert!(s.dot(n).abs() < 1e-5);
        }
    }
}
