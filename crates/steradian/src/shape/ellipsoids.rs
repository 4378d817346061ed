//! # `ellipsoids`: a cloud of anisotropic ellipsoids, intersected in closed form
//!
//! Mitsuba plugin `ellipsoids` (its mesh twin is `ellipsoidsmesh`, in `ellipsoidsmesh.rs`).
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `filename` | string | (required) | PLY file of the ellipsoids (layout below) |
//! | `scale_factor` | float | 1 | factor on every ellipsoid's scales |
//! | `extent` | float | 3 | the shell's radii in units of the scales: radius = `extent` · scale |
//! | `extent_adaptive_clamping` | bool | false | scale each ellipsoid's `extent` by its opacity α: by √(2·ln(α/0.01))/3 |
//! | `to_world` | transform | identity | moves the centres; turns the ellipsoids by its rotation and scales them by its mean scale (below) |
//!
//! **File** (the layout of 3-D Gaussian-splatting files, as Mitsuba reads it). The first
//! element of the PLY file has one record per ellipsoid; its properties start with `x y z nx
//! ny nz` and end with `scale_0 scale_1 scale_2 rot_0 rot_1 rot_2 rot_3`, any others lying
//! between. (x, y, z) is the centre, m. The scales are stored as logarithms: scale =
//! max(exp(`scale_i`), 10⁻⁶) · `scale_factor`. `rot_0` is the real part of the rotation
//! quaternion and `rot_1..3` its i, j, k parts; it is normalised. The normals and the
//! properties between are read past: Mitsuba keeps the latter as attributes for its
//! volumetric-primitive integrators, and no steradian plugin reads them, except the opacity.
//! A file is a Gaussian-splatting file when its seventh property is `f_dc_0` and the one
//! before `scale_0` is `opacity`; its opacity is α = sigmoid(`opacity`), kept within
//! [10⁻⁸, 1 − 10⁻⁸]. In another file a single property named `opacities` (or `opacities_…`)
//! gives α as stored. `extent_adaptive_clamping` needs α; without it Mitsuba warns and uses
//! `extent` alone, and so does steradian. With it, an ellipsoid of α ≤ 0.01 has no shell
//! (Mitsuba's extent is then NaN or 0, and nothing hits it).
//!
//! **`to_world`.** Its linear part is split by the polar decomposition M = Q·S (Q orthogonal,
//! S symmetric), as Mitsuba splits it. Centres move by the whole transform; each ellipsoid is
//! turned by Q (by −Q where Q mirrors, the same set of points since an ellipsoid is symmetric
//! about its centre), and its scales are multiplied by the mean of S's diagonal, so a
//! non-uniform scale or a shear is averaged, not applied.
//!
//! **Geometry.** Each ellipsoid, with centre c, rotation R and radii r = `extent` · scale, is a
//! primitive of the scene's BVH, bounded by its exact box. Along a ray o + t·d the point q(t) =
//! r⁻¹·Rᵀ·(o + t·d − c) lies on the unit sphere at the roots of |q(t)|² = 1, solved in f64
//! from the distance between the line and the centre (accurate at grazing incidence). As in
//! Mitsuba, an ellipsoid is hit at its near root only when that root is ahead of the ray's
//! origin: a ray starting inside an ellipsoid does not see it (back faces are culled), so
//! a ray leaving a shell's surface never hits it again. The normal is the gradient
//! R·(q/r), normalised; there are no texture coordinates (uv = 0), and ∂p/∂u, ∂p/∂v are the
//! normal's default frame.
//!
//! Mitsuba made the shape for volumetric-primitive integrators (a separate package); under a
//! surface integrator, which is what steradian renders, each ellipsoid is an opaque shell
//! carrying the shape's BSDF.
//!
//! **Where steradian differs on purpose.**
//! - Mitsuba 3.9.1's hits on thin ellipsoids lie off the surface: on one of radii 0.6 × 0.4 ×
//!   0.06, by up to 0.5 % of the radius in the unit sphere's coordinates, about 3·10⁻⁴ m
//!   across the thin axis. A ray refracted into such an ellipsoid then hits the same surface
//!   again at once instead of being culled, so thin glass renders dark: over a glass ellipsoid
//!   of those radii under a white sky, Mitsuba's mean is 0.487, steradian's 0.573 (for a round
//!   one of radius 0.5 they agree: 0.5649 and 0.5651). Opaque surfaces are not affected (a
//!   ray leaving one outward is culled either way); `reference/ellipsoids.xml` renders them
//!   as Mitsuba does.
//! - Small ellipsoids far from the origin: Mitsuba's images depend on its variant. In a random
//!   test scene with a cloud of radii 8–75 mm about 7 m from the camera, its `llvm_ad_rgb`
//!   image passes its render-test rule against its own `scalar_rgb` reference at only 0.989
//!   and 0.990 of the pixels (two seeds); steradian's passes against `scalar_rgb` at
//!   0.9987–0.9990 (four seeds) and against `llvm_ad_rgb` at 0.9948.
//! - A mirroring `to_world`: Mitsuba's image differs from its image of the same ellipsoids
//!   written into the file (`reference/ellipsoids.xml` with the analytic cloud's scale x made
//!   −1.2: image mean 0.1657 against 0.1685 at 256 spp). steradian's two images agree (0.1683)
//!   and pass the render-test rule against Mitsuba's image of the written-out file.
//! - The file's properties may be of any PLY scalar type (Mitsuba reads each record's bytes
//!   as 32-bit floats).
//! - An anisotropic BSDF's tangent is the normal's default frame (Mitsuba leaves the
//!   tangent undefined).
//!
//! As in Mitsuba, an ellipsoid cloud cannot emit or carry a sensor (the loader refuses both)
//! and reports a surface area of 0; its `data`, `centers`, `scales` and `quaternions` tensors
//! cannot be written in a scene file.

use glam::{DMat3, DVec3, Mat3, Quat, Vec2, Vec3};

use super::{PositionSample, ShapeError};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};

/// One ellipsoid as the file describes it: `extent` is not yet applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipsoid {
    /// Centre, m.
    pub center: Vec3,
    /// Semi-axes along the rotated x, y and z axes before `extent`, m.
    pub scale: Vec3,
    /// Object (axis-aligned) → world rotation.
    pub rotation: Mat3,
}

/// The ellipsoids of a file, with their opacities where the file gives them.
#[derive(Clone, Debug, PartialEq)]
pub struct EllipsoidCloud {
    pub ellipsoids: Vec<Ellipsoid>,
    /// Opacity α of each ellipsoid, in (0, 1] (see the module documentation).
    pub opacities: Option<Vec<f32>>,
}

/// Whether each ellipsoid's extent follows its opacity (`extent_adaptive_clamping`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExtentClamping {
    /// Every ellipsoid's extent is `extent`.
    Fixed,
    /// `extent` · √(2·ln(α/0.01))/3: the radius at which a Gaussian of peak α falls to 0.01.
    Adaptive,
}

impl ExtentClamping {
    /// Default `extent_adaptive_clamping` (Mitsuba's: off).
    pub const DEFAULT: ExtentClamping = ExtentClamping::Fixed;
}

/// Smallest response of a Gaussian inside its adaptive shell (Mitsuba's α threshold).
const MIN_RESPONSE: f32 = 0.01;

impl EllipsoidCloud {
    /// Each ellipsoid's extent; 0 for an ellipsoid without a shell. [`ExtentClamping::Adaptive`]
    /// without opacities is [`ExtentClamping::Fixed`] (the loader warns).
    pub fn extents(&self, extent: f32, clamping: ExtentClamping) -> Vec<f32> {
        match (clamping, &self.opacities) {
            (ExtentClamping::Adaptive, Some(alpha)) => alpha
                .iter()
                .map(|&a| {
                    let k = (2.0 * (a / MIN_RESPONSE).ln()).sqrt() / 3.0;
                    if k > 0.0 {
                        extent * k
                    } else {
                        0.0
                    }
                })
                .collect(),
            _ => vec![extent; self.ellipsoids.len()],
        }
    }
}

/// Default `extent` (Mitsuba's): the shell's radii in units of the scales.
pub const DEFAULT_EXTENT: f32 = 3.0;
/// Default `scale_factor` (Mitsuba's).
pub const DEFAULT_SCALE_FACTOR: f32 = 1.0;
/// Smallest scale after the exponential (Mitsuba's clamp).
const MIN_SCALE: f32 = 1e-6;
/// Iterations of the polar decomposition at most (it converges quadratically).
const POLAR_ITERATIONS: usize = 25;

/// Reads the ellipsoids of a PLY file (layout in the module documentation), scaled by
/// `scale_factor` and placed by `to_world`.
pub fn read_ellipsoids(
    path: &std::path::Path,
    scale_factor: f32,
    to_world: &Transform,
) -> Result<EllipsoidCloud, ShapeError> {
    let table = super::ply::read_ply_table(path)?;
    let fail = |msg: String| ShapeError(format!("PLY file \"{}\": {msg}", path.display()));
    let names = &table.names;
    let head = ["x", "y", "z", "nx", "ny", "nz"];
    let tail = ["scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"];
    let n = names.len();
    if n < head.len() + tail.len() || names[..head.len()] != head || names[n - tail.len()..] != tail
    {
        return Err(fail(format!(
            "element \"{}\" has properties {}; ellipsoids need x y z nx ny nz first and \
             scale_0 scale_1 scale_2 rot_0 rot_1 rot_2 rot_3 last",
            table.element,
            names.join(" ")
        )));
    }
    // where α is: a Gaussian-splatting file's `opacity` (through a sigmoid), or a lone
    // `opacities` property
    let splats = names[6] == "f_dc_0" && names[n - 8] == "opacity";
    let prefix = |name: &str| name.rfind('_').map_or(name, |i| &name[..i]).to_string();
    let opacity_at: Option<(usize, bool)> = if splats {
        Some((n - 8, true))
    } else {
        let group: Vec<usize> =
            (6..n - tail.len()).filter(|&i| prefix(&names[i]) == "opacities").collect();
        (group.len() == 1).then(|| (group[0], false))
    };
    let (linear, mean_scale) =
        polar_rotation(to_world.linear()).ok_or_else(|| fail("to_world has no inverse".into()))?;
    let mut out = Vec::with_capacity(table.values.len() / n);
    let mut opacities = Vec::new();
    for (i, row) in table.values.chunks_exact(n).enumerate() {
        let bad = |what: &str| fail(format!("ellipsoid {i}: {what}"));
        if let Some(v) = row.iter().find(|v| !v.is_finite()) {
            return Err(bad(&format!("a value is not finite ({v})")));
        }
        let s = &row[n - 7..];
        let center = to_world.point(Vec3::new(row[0] as f32, row[1] as f32, row[2] as f32));
        let scale =
            Vec3::new(s[0] as f32, s[1] as f32, s[2] as f32).exp().max(Vec3::splat(MIN_SCALE))
                * (scale_factor * mean_scale);
        let q = Quat::from_xyzw(s[4] as f32, s[5] as f32, s[6] as f32, s[3] as f32);
        if q.length_squared() == 0.0 {
            return Err(bad("the rotation quaternion is zero"));
        }
        let rotation = linear * Mat3::from_quat(q.normalize());
        if !scale.is_finite() || !center.is_finite() {
            return Err(bad("its placed centre or scale is not finite"));
        }
        out.push(Ellipsoid { center, scale, rotation });
        if let Some((k, sigmoid)) = opacity_at {
            let a = row[k] as f32;
            opacities.push(if sigmoid {
                (1.0 / (1.0 + (-a).exp())).clamp(1e-8, 1.0 - 1e-8)
            } else {
                a
            });
        }
    }
    if out.is_empty() {
        return Err(fail(format!("element \"{}\" holds no ellipsoid", table.element)));
    }
    let opacities = opacity_at.map(|_| opacities);
    Ok(EllipsoidCloud { ellipsoids: out, opacities })
}

/// One extent per ellipsoid, each finite and ≥ 0, and at least one ellipsoid.
pub(crate) fn check_extents(ellipsoids: &[Ellipsoid], extents: &[f32]) -> Result<(), ShapeError> {
    if ellipsoids.is_empty() {
        return Err(ShapeError("ellipsoids: the file holds no ellipsoid".into()));
    }
    if ellipsoids.len() != extents.len() {
        return Err(ShapeError(format!(
            "ellipsoids: {} extents for {} ellipsoids",
            extents.len(),
            ellipsoids.len()
        )));
    }
    if let Some(k) = extents.iter().find(|k| !(k.is_finite() && **k >= 0.0)) {
        return Err(ShapeError(format!("ellipsoids: an extent is {k}; it must be finite and ≥ 0")));
    }
    // a finite scale times a finite extent can still overflow
    for (i, (e, &k)) in ellipsoids.iter().zip(extents).enumerate() {
        let radii = e.scale * k;
        if !(radii.is_finite() && e.center.is_finite() && (e.center.abs() + radii).is_finite()) {
            return Err(ShapeError(format!(
                "ellipsoids: ellipsoid {i}'s shell (centre {}, radii {radii}) is not finite",
                e.center
            )));
        }
    }
    Ok(())
}

/// The rotation Q of the polar decomposition M = Q·S, turned into a proper rotation (−Q where
/// Q mirrors), and the mean of |S|'s diagonal; `None` when M is singular.
fn polar_rotation(m: Mat3) -> Option<(Mat3, f32)> {
    let m = m.as_dmat3();
    let det = m.determinant();
    if det.is_nan() || det.abs() <= 1e-30 {
        return None;
    }
    // Newton's iteration Q ← (Q + Q⁻ᵀ)/2 converges to the orthogonal factor
    let mut q = m;
    for _ in 0..POLAR_ITERATIONS {
        let next = (q + q.inverse().transpose()) * 0.5;
        let change = (next - q).to_cols_array().iter().fold(0.0f64, |a, v| a.max(v.abs()));
        q = next;
        if change < 1e-14 {
            break;
        }
    }
    let s: DMat3 = q.transpose() * m;
    let sign = q.determinant().signum();
    let mean = (s.x_axis.x + s.y_axis.y + s.z_axis.z).abs() / 3.0;
    Some(((q * sign).as_mat3(), mean as f32))
}

/// An ellipsoid ready for intersection.
#[derive(Clone, Copy, Debug)]
struct Prim {
    center: Vec3,
    /// Object → world rotation.
    rotation: Mat3,
    /// Radii (scale · extent), m.
    radii: Vec3,
}

#[derive(Clone, Debug)]
pub struct Ellipsoids {
    prims: Vec<Prim>,
}

impl Ellipsoids {
    /// The cloud of `ellipsoids`, the i-th scaled by `extents[i]`; those of extent 0 have no
    /// shell and are left out.
    pub fn new(ellipsoids: &[Ellipsoid], extents: &[f32]) -> Result<Ellipsoids, ShapeError> {
        check_extents(ellipsoids, extents)?;
        let prims: Vec<Prim> = ellipsoids
            .iter()
            .zip(extents)
            .filter(|(_, &k)| k > 0.0)
            .map(|(e, &k)| Prim { center: e.center, rotation: e.rotation, radii: e.scale * k })
            .collect();
        if prims.is_empty() {
            return Err(ShapeError("ellipsoids: no ellipsoid has a shell".into()));
        }
        Ok(Ellipsoids { prims })
    }

    pub fn count(&self) -> u32 {
        self.prims.len() as u32
    }

    pub fn bounds(&self) -> Aabb {
        (0..self.count()).fold(self.prim_bounds(0), |b, i| b.union(&self.prim_bounds(i)))
    }

    /// The exact box of ellipsoid `prim`: along world axis k its half-width is
    /// |row k of R·diag(r)|, padded by a millionth against rounding.
    pub fn prim_bounds(&self, prim: u32) -> Aabb {
        let e = &self.prims[prim as usize];
        let m = e.rotation * Mat3::from_diagonal(e.radii);
        let half = Vec3::new(m.row(0).length(), m.row(1).length(), m.row(2).length());
        let pad = half * 1e-6 + Vec3::splat(1e-7 * e.center.abs().max_element());
        Aabb::new(e.center - half - pad, e.center + half + pad)
    }

    /// Ray–ellipsoid test: the near root `(t, 0)` when `0 < t < ray.t_max`.
    pub fn intersect_prim(&self, prim: u32, ray: &Ray) -> Option<(f32, Vec2)> {
        let e = &self.prims[prim as usize];
        let rt = e.rotation.transpose().as_dmat3();
        let inv_r = e.radii.as_dvec3().recip();
        let o = rt * (ray.o.as_dvec3() - e.center.as_dvec3()) * inv_r;
        let d = rt * ray.d.as_dvec3() * inv_r;
        let a = d.length_squared();
        if a.is_nan() || a <= 0.0 {
            return None;
        }
        // t0: the parameter of the line's point closest to the centre; h² its squared distance
        let t0 = -o.dot(d) / a;
        let h2 = (o + d * t0).length_squared();
        if h2.is_nan() || h2 > 1.0 {
            return None;
        }
        let near = t0 - ((1.0 - h2) / a).sqrt();
        let t = near as f32;
        (near >= 0.0 && t > 0.0 && t < ray.t_max).then_some((t, Vec2::ZERO))
    }

    /// Surface data at a hit found by [`Ellipsoids::intersect_prim`].
    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        let p = ray.o + ray.d * hit.t;
        let e = &self.prims[hit.prim as usize];
        let local: DVec3 = e.rotation.transpose().as_dmat3() * (p - e.center).as_dvec3();
        let r = e.radii.as_dvec3();
        let n = (e.rotation.as_dmat3() * (local / (r * r))).normalize().as_vec3();
        let n = if n.is_finite() { n } else { Vec3::Z };
        let frame = Frame::from_normal(n);
        SurfaceInteraction {
            p,
            t: hit.t,
            n,
            sh_frame: frame,
            uv: Vec2::ZERO,
            dpdu: frame.s,
            dpdv: frame.t,
            wo: -ray.d,
            shape: hit.shape,
            prim: hit.prim,
            bary: Vec2::ZERO,
            instance: hit.instance,
        }
    }

    /// Mitsuba reports 0 (no points can be sampled on the surface).
    pub fn surface_area(&self) -> f32 {
        0.0
    }

    /// No points can be sampled (the loader refuses emitters and sensors on the shape): a
    /// sample of density 0, which every caller drops.
    pub fn sample_position(&self, _u: Vec2) -> PositionSample {
        PositionSample { p: self.prims[0].center, n: Vec3::Z, uv: Vec2::ZERO, pdf_area: 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::NO_INSTANCE;

    fn cloud(e: &[Ellipsoid], extent: f32) -> Ellipsoids {
        Ellipsoids::new(e, &vec![extent; e.len()]).unwrap()
    }

    fn hit(c: &Ellipsoids, ray: &Ray) -> Option<(f32, SurfaceInteraction)> {
        let (t, uv) = c.intersect_prim(0, ray)?;
        let h = PreliminaryHit { t, uv, shape: 0, prim: 0, instance: NO_INSTANCE };
        Some((t, c.interaction(ray, &h)))
    }

    fn turned() -> Ellipsoid {
        Ellipsoid {
            center: Vec3::new(0.3, -0.2, 0.1),
            scale: Vec3::new(0.5, 0.2, 0.1),
            rotation: Mat3::from_quat(Quat::from_axis_angle(
                Vec3::new(1.0, 2.0, 0.5).normalize(),
                0.7,
            )),
        }
    }

    /// The implicit function of the shell (zero on it, negative inside).
    fn implicit(e: &Ellipsoid, extent: f32, p: Vec3) -> f32 {
        let q = e.rotation.transpose() * (p - e.center) / (e.scale * extent);
        q.length_squared() - 1.0
    }

    #[test]
    fn hits_lie_on_the_shell_with_the_gradient_as_normal() {
        let e = turned();
        let c = cloud(&[e], 2.0);
        let mut hits = 0;
        for i in 0..400 {
            let (a, b) = ((i % 20) as f32 / 19.0 - 0.5, (i / 20) as f32 / 19.0 - 0.5);
            let o = Vec3::new(a * 2.5, b * 2.5, 5.0);
            let ray = Ray::new(o, (e.center - o + Vec3::new(a, b, 0.0)).normalize(), f32::INFINITY);
            let Some((t, si)) = hit(&c, &ray) else { continue };
            hits += 1;
            assert!(implicit(&e, 2.0, si.p).abs() < 1e-4, "ray {i}: off the shell");
            // the normal is the implicit function's gradient, pointing away from the centre
            let h = 1e-3;
            let grad = Vec3::new(
                implicit(&e, 2.0, si.p + Vec3::X * h) - implicit(&e, 2.0, si.p - Vec3::X * h),
                implicit(&e, 2.0, si.p + Vec3::Y * h) - implicit(&e, 2.0, si.p - Vec3::Y * h),
                implicit(&e, 2.0, si.p + Vec3::Z * h) - implicit(&e, 2.0, si.p - Vec3::Z * h),
            )
            .normalize();
            assert!(si.n.dot(grad) > 0.999, "ray {i}: normal {} against {grad}", si.n);
            assert!(si.n.dot(-ray.d) > 0.0, "ray {i}: the near side faces the ray");
            assert!((t - (si.p - o).length()).abs() < 1e-4);
        }
        assert!(hits > 50 && hits < 400, "{hits} of 400 rays hit");
    }

    #[test]
    fn rays_from_inside_or_leaving_the_shell_do_not_see_it() {
        let e = turned();
        let c = cloud(&[e], 1.0);
        // from the centre, in any direction: culled
        for d in [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::ONE.normalize()] {
            assert!(c.intersect_prim(0, &Ray::new(e.center, d, f32::INFINITY)).is_none());
        }
        // from outside: hit; from the hit point onward (slightly inside): nothing
        let ray = Ray::new(e.center + Vec3::new(0.0, 0.0, 3.0), -Vec3::Z, f32::INFINITY);
        let (_, si) = hit(&c, &ray).expect("the ray is aimed at the centre");
        assert!(c
            .intersect_prim(0, &Ray::new(si.p - si.n * 1e-4, -Vec3::Z, f32::INFINITY))
            .is_none());
        // a ray behind which the ellipsoid lies, and one stopped short of it
        assert!(c
            .intersect_prim(0, &Ray::new(e.center + Vec3::Z * 3.0, Vec3::Z, f32::INFINITY))
            .is_none());
        let mut short = ray;
        short.t_max = 2.0;
        assert!(c.intersect_prim(0, &short).is_none());
    }

    #[test]
    fn boxes_hold_the_whole_shell() {
        let e = turned();
        let c = cloud(&[e], 3.0);
        let b = c.prim_bounds(0);
        let mut touches = [false; 6];
        for i in 0..20_000 {
            // points of the unit sphere (Fibonacci lattice) mapped onto the shell
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / 20_000.0;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            let q = Vec3::new(r * phi.cos(), r * phi.sin(), z);
            let p = e.center + e.rotation * (q * e.scale * 3.0);
            assert!(p.cmpge(b.min).all() && p.cmple(b.max).all(), "{p} outside {b:?}");
            for k in 0..3 {
                touches[2 * k] |= p[k] - b.min[k] < 1e-3;
                touches[2 * k + 1] |= b.max[k] - p[k] < 1e-3;
            }
        }
        assert_eq!(touches, [true; 6], "the box is tight on every side");
    }

    #[test]
    fn to_world_moves_centres_and_turns_and_scales_by_its_polar_factors() {
        let turn = Transform::rotate(Vec3::new(0.0, 0.0, 1.0), 90.0).unwrap();
        let m = Transform::translate(Vec3::new(1.0, 2.0, 3.0))
            .then_after(&turn)
            .then_after(&Transform::scale(Vec3::splat(2.0)).unwrap());
        let (q, mean) = polar_rotation(m.linear()).unwrap();
        assert!((mean - 2.0).abs() < 1e-5, "mean scale {mean}");
        assert!((q * Vec3::X - Vec3::Y).length() < 1e-5, "rotation {q}");
        // a mirror becomes the opposite rotation, of determinant +1
        let mirror = Transform::scale(Vec3::new(-1.0, 1.0, 1.0)).unwrap();
        let (q, mean) = polar_rotation(mirror.linear()).unwrap();
        assert!((q.determinant() - 1.0).abs() < 1e-5 && (mean - 1.0).abs() < 1e-5);
        // non-uniform scales are averaged
        let (_, mean) =
            polar_rotation(Transform::scale(Vec3::new(1.0, 2.0, 6.0)).unwrap().linear()).unwrap();
        assert!((mean - 3.0).abs() < 1e-5);
        assert!(polar_rotation(Mat3::ZERO).is_none());
    }

    #[test]
    fn a_bad_extent_or_an_empty_cloud_is_refused() {
        for extent in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(Ellipsoids::new(&[turned()], &[extent]).is_err(), "extent {extent}");
        }
        assert!(Ellipsoids::new(&[], &[]).is_err());
        assert!(Ellipsoids::new(&[turned(); 2], &[1.0]).is_err());
        let huge = Ellipsoid { scale: Vec3::splat(2e38), ..turned() };
        assert!(Ellipsoids::new(&[huge], &[3.0]).is_err(), "radii overflow to infinity");
        // an ellipsoid of extent 0 has no shell; the others stay
        assert_eq!(Ellipsoids::new(&[turned(); 2], &[0.0, 1.0]).unwrap().count(), 1);
    }

    #[test]
    fn adaptive_extents_follow_the_opacity() {
        let cloud = EllipsoidCloud {
            ellipsoids: vec![turned(); 3],
            opacities: Some(vec![1.0, 0.5, 0.005]),
        };
        let k = cloud.extents(3.0, ExtentClamping::Adaptive);
        // a Gaussian of peak α is 0.01 at √(2 ln(α/0.01)) standard deviations
        assert!((k[0] - (2.0 * 100f32.ln()).sqrt()).abs() < 1e-5);
        assert!((k[1] - (2.0 * 50f32.ln()).sqrt()).abs() < 1e-5);
        assert_eq!(k[2], 0.0);
        assert_eq!(cloud.extents(3.0, ExtentClamping::Fixed), vec![3.0; 3]);
        let without = EllipsoidCloud { opacities: None, ..cloud };
        assert_eq!(without.extents(2.0, ExtentClamping::Adaptive), vec![2.0; 3]);
    }
}
