//! `perspective`: an ideal pinhole camera.
//!
//! | parameter        | type      | default   | meaning |
//! |------------------|-----------|-----------|---------|
//! | `to_world`       | transform | identity  | camera → world; rigid (a scale is an error). The camera looks along local +z with +y up; `lookat` is the usual way to set it |
//! | `fov`            | float     | —         | field of view in degrees along `fov_axis`, in (0, 180) |
//! | `fov_axis`       | string    | `x`       | `x`, `y`, `diagonal`, `smaller` or `larger` |
//! | `focal_length`   | string    | `50mm`    | alternative to `fov`: 35 mm-equivalent focal length, applied to the diagonal |
//! | `near_clip`      | float     | 0.01      | m; rays start on the near plane |
//! | `far_clip`       | float     | 10000     | m |
//! | `focus_distance` | float     | far_clip  | accepted for compatibility; a pinhole is always in focus |
//! | `principal_point_offset_x`, `principal_point_offset_y` | float | 0 | shift of the image window, as fractions of the film's width and height (the Mitsuba Blender add-on writes them for Blender's lens shift) |
//! | film, sampler    | children  | `hdrfilm`, `independent` | |
//!
//! Pixel (0,0) is the top-left of the image; image x grows towards the camera's right (local
//! −x, since Mitsuba's local +x points left) and image y downwards. For a film position
//! (sx, sy) ∈ [0,1]², the ray direction in camera space is proportional to
//! ((1 − 2sx)·tan(fov_x/2), (1 − 2sy)·tan(fov_x/2)/aspect, 1).
//!
//! **Principal point.** As in Mitsuba 3, the offset (ox, oy) is added to the film position
//! before it becomes a direction: pixel (sx, sy) looks where (sx + ox, sy + oy) looks without
//! it, so a positive ox turns the view towards the image's right and the scene moves left.
//! The window keeps its size, so the importance below is unchanged; particle tracing maps a
//! direction back to the film position less the offset. (Mitsuba's `importance` tests the
//! unshifted window, which drops light-traced points near the shifted edges; steradian tests
//! the window the camera actually sees.)
//!
//! ## Importance (for particle tracing)
//!
//! The camera's importance is normalised over the film: with A = 4·tan(fov_x/2)·tan(fov_y/2)
//! the area of the image rectangle at unit distance, a direction at angle θ from the optical
//! axis has W(θ) = 1/(A·cos⁴θ) per unit area of the pinhole and solid angle, so that
//! ∫ W cos θ dω = 1 over the image. Connecting a point at distance r to the pinhole gives the
//! factor W·cos θ/r² = 1/(A·cos³θ·r²) ([`Perspective::sample_direction`]); a light path's
//! splat of that weight, scaled by 1/spp, makes each pixel the mean radiance it sees.

use glam::{Vec2, Vec3};

use crate::geometry::is_positive;
use crate::geometry::{Ray, Transform};
use crate::param::ParamError;

#[derive(Clone, Debug)]
pub struct Perspective {
    pub to_world: Transform,
    /// tan of half the field of view along x and y.
    tan_half: Vec2,
    pub near_clip: f32,
    pub far_clip: f32,
    /// Principal point offset (fractions of the film's width and height, see the module docs).
    principal_point: Vec2,
}

/// Checks the camera transform is rigid and the clip planes are sane.
pub(super) fn validate(
    to_world: &Transform,
    near_clip: f32,
    far_clip: f32,
) -> Result<(), ParamError> {
    let s = to_world.axis_scales();
    if (s - Vec3::ONE).abs().max_element() > 1e-3 {
        return Err(ParamError::new("to_world", format!("scale factors in the camera's to_world are not allowed (axis scales {:.4}, {:.4}, {:.4})", s.x, s.y, s.z)));
    }
    if !(near_clip > 0.0 && near_clip.is_finite()) {
        return Err(ParamError::new(
            "near_clip",
            format!("near_clip must be positive, got {near_clip}"),
        ));
    }
    if !is_positive(far_clip - near_clip) {
        let reason = format!("far_clip ({far_clip}) must exceed near_clip ({near_clip})");
        return Err(ParamError::new("far_clip", reason).with_related("near_clip"));
    }
    Ok(())
}

impl Perspective {
    /// Default `near_clip` (m; Mitsuba's); `thinlens` shares it.
    pub const DEFAULT_NEAR_CLIP: f32 = 0.01;
    /// Default `far_clip` (m; Mitsuba's); `thinlens` shares it, and `focus_distance` defaults
    /// to the far clip.
    pub const DEFAULT_FAR_CLIP: f32 = 1e4;

    /// `x_fov` in radians (see [`super::FieldOfView::x_fov`]); `aspect` = width/height.
    pub fn new(
        to_world: Transform,
        x_fov: f32,
        aspect: f32,
        near_clip: f32,
        far_clip: f32,
    ) -> Result<Self, ParamError> {
        validate(&to_world, near_clip, far_clip)?;
        let tx = (x_fov / 2.0).tan();
        Ok(Perspective {
            to_world,
            tan_half: Vec2::new(tx, tx / aspect),
            near_clip,
            far_clip,
            principal_point: Vec2::ZERO,
        })
    }

    /// The camera with its principal point offset by `offset` (fractions of the film's width
    /// and height, Mitsuba's `principal_point_offset_x/y`; see the module docs).
    pub fn with_principal_point_offset(mut self, offset: Vec2) -> Result<Self, ParamError> {
        for (name, v) in
            [("principal_point_offset_x", offset.x), ("principal_point_offset_y", offset.y)]
        {
            if !v.is_finite() {
                return Err(ParamError::new(name, format!("{name} must be finite, got {v}")));
            }
        }
        self.principal_point = offset;
        Ok(self)
    }

    /// The principal point offset (fractions of the film's width and height).
    pub fn principal_point_offset(&self) -> Vec2 {
        self.principal_point
    }

    /// Unnormalised camera-space direction through film position `film_uv`.
    #[inline]
    pub(super) fn local_direction(tan_half: Vec2, film_uv: Vec2) -> Vec3 {
        Vec3::new((1.0 - 2.0 * film_uv.x) * tan_half.x, (1.0 - 2.0 * film_uv.y) * tan_half.y, 1.0)
    }

    #[inline]
    pub fn tan_half(&self) -> Vec2 {
        self.tan_half
    }

    #[inline]
    pub fn sample_ray(&self, film_uv: Vec2) -> Ray {
        let d = Self::local_direction(self.tan_half, film_uv + self.principal_point).normalize();
        // rays start on the near plane and end on the far plane (both are z = const planes)
        let inv_z = 1.0 / d.z;
        let (near_t, far_t) = (self.near_clip * inv_z, self.far_clip * inv_z);
        let d_world = self.to_world.vector(d).normalize();
        Ray::new(self.to_world.point(Vec3::ZERO) + d_world * near_t, d_world, far_t - near_t)
    }
}

/// The film position in [0, 1]² (before a principal point offset) of camera-space direction
/// `local` (z > 0, any length).
#[inline]
pub(super) fn film_position(tan_half: Vec2, local: Vec3) -> Vec2 {
    let (px, py) = (local.x / local.z, local.y / local.z);
    Vec2::new(0.5 * (1.0 - px / tan_half.x), 0.5 * (1.0 - py / tan_half.y))
}

/// Whether film position `film_uv` lies on the film.
#[inline]
pub(super) fn on_film(film_uv: Vec2) -> bool {
    film_uv.cmpge(Vec2::ZERO).all() && film_uv.cmple(Vec2::ONE).all()
}

/// W·cos θ = 1/(A·cos³θ) for camera-space direction `local` (z > 0, any length), with A the
/// image rectangle's area at unit distance (see the module docs), 1/sr.
#[inline]
pub(super) fn importance_factor(tan_half: Vec2, local: Vec3) -> f32 {
    let cos_theta = local.z / local.length();
    let area = 4.0 * tan_half.x * tan_half.y;
    1.0 / (area * cos_theta * cos_theta * cos_theta)
}

/// A point on a camera's lens that a light path connects to (particle tracing): the pinhole
/// of a `perspective` camera, a point of a `thinlens` camera's aperture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LensSample {
    /// World position, m.
    pub position: Vec3,
    /// Camera-space position, m (z = 0).
    pub local: Vec3,
}

/// A connection from a point to the camera (particle tracing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorConnection {
    /// The point of the camera's lens connected to (the pinhole, a point of the aperture), m.
    pub position: Vec3,
    /// Unit direction from the point towards the camera.
    pub wi: Vec3,
    /// Distance to the camera, m.
    pub dist: f32,
    /// Film position in [0, 1]² of the ray through the point.
    pub film_uv: Vec2,
    /// W·cos θ / r² (1/(m²·sr) per unit area, see the module documentation); for a point at
    /// infinity ([`Perspective::sample_direction_at_infinity`]) W·cos θ, without the 1/r².
    pub weight: f32,
}

impl SensorConnection {
    /// The connection from world point `p` to lens point `lens`, with film position `film_uv`
    /// and importance factor `w` = W·cos θ (the weight is w/r²).
    #[inline]
    pub(super) fn to_point(lens: &LensSample, p: Vec3, film_uv: Vec2, w: f32) -> Self {
        let d = lens.position - p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        SensorConnection { position: lens.position, wi: d / dist, dist, film_uv, weight: w / dist2 }
    }

    /// The connection for light arriving at lens point `lens` from world direction `wi`
    /// (towards the light) at infinity: the weight is W·cos θ, without the 1/r².
    #[inline]
    pub(super) fn from_infinity(lens: &LensSample, wi: Vec3, film_uv: Vec2, weight: f32) -> Self {
        SensorConnection { position: lens.position, wi: -wi, dist: f32::INFINITY, film_uv, weight }
    }
}

impl Perspective {
    /// The film position and importance factor of the camera ray towards camera-space
    /// direction `local` (any length); `None` outside the field of view.
    #[inline]
    fn importance(&self, local: Vec3) -> Option<(Vec2, f32)> {
        if !is_positive(local.z) {
            return None;
        }
        let film_uv = film_position(self.tan_half, local) - self.principal_point;
        on_film(film_uv).then(|| (film_uv, importance_factor(self.tan_half, local)))
    }

    /// The pinhole, as the lens point particle tracing connects to.
    #[inline]
    pub fn lens(&self) -> LensSample {
        LensSample { position: self.to_world.point(Vec3::ZERO), local: Vec3::ZERO }
    }

    /// The connection from world point `p` to the pinhole `lens` ([`Perspective::lens`]);
    /// `None` when `p` is outside the field of view or the clip range (depth along the axis in
    /// [near_clip, far_clip]).
    #[inline]
    pub fn sample_direction(&self, lens: &LensSample, p: Vec3) -> Option<SensorConnection> {
        let local = self.to_world.inverse().point(p);
        if !(local.z >= self.near_clip && local.z <= self.far_clip) {
            return None;
        }
        let (film_uv, w) = self.importance(local)?;
        Some(SensorConnection::to_point(lens, p, film_uv, w))
    }

    /// The camera ray's film position and importance for light arriving from world
    /// direction `wi` (towards the light, from the pinhole `lens`), for lights at infinity.
    #[inline]
    pub fn sample_direction_at_infinity(
        &self,
        lens: &LensSample,
        wi: Vec3,
    ) -> Option<SensorConnection> {
        let (film_uv, weight) = self.importance(self.to_world.inverse().vector(wi))?;
        Some(SensorConnection::from_infinity(lens, wi, film_uv, weight))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Perspective {
        // the cornell camera: at (0,0,3.9) looking at the origin, y up, 256×256
        let tw = Transform::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y).unwrap();
        Perspective::new(tw, 39.3077f32.to_radians(), 1.0, 0.001, 100.0).unwrap()
    }

    #[test]
    fn centre_pixel_looks_at_the_target_from_the_near_plane() {
        let r = camera().sample_ray(Vec2::splat(0.5));
        assert!((r.d - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6);
        assert!((r.o - Vec3::new(0.0, 0.0, 3.9 - 0.001)).length() < 1e-6);
        assert!((r.t_max - (100.0 - 0.001)).abs() < 1e-3);
    }

    #[test]
    fn image_axes_follow_mitsuba() {
        let c = camera();
        // top-left film corner: up (+y) and to the image's left; the camera faces −z with +y
        // up, so its right is +x and the image's left is −x in world space.
        let r = c.sample_ray(Vec2::new(0.0, 0.0));
        assert!(r.d.y > 0.0 && r.d.x < 0.0, "{:?}", r.d);
        let r = c.sample_ray(Vec2::new(1.0, 1.0));
        assert!(r.d.y < 0.0 && r.d.x > 0.0);
        // the right edge of the image is at half the horizontal fov
        let r = c.sample_ray(Vec2::new(1.0, 0.5));
        let angle = r.d.dot(Vec3::new(0.0, 0.0, -1.0)).acos().to_degrees();
        assert!((angle - 39.3077 / 2.0).abs() < 1e-3, "{angle}");
    }

    #[test]
    fn projects_a_known_point_to_its_pixel() {
        // A world point projects back onto the film position whose ray passes through it.
        let c = camera();
        let p = Vec3::new(0.3, -0.2, 0.5);
        let local = c.to_world.inverse().point(p);
        let t = c.tan_half();
        let sx = 0.5 * (1.0 - local.x / local.z / t.x);
        let sy = 0.5 * (1.0 - local.y / local.z / t.y);
        let r = c.sample_ray(Vec2::new(sx, sy));
        let to_p = (p - r.o).normalize();
        assert!((to_p - r.d).length() < 1e-5);
    }

    /// The importance integrates to 1 over the image: ∫ W cos θ dω = 1, by Monte Carlo over
    /// directions uniform on the sphere (4π·mean of W·cos θ where the camera sees them), within
    /// 4 standard errors; and a point connects to the film position whose ray reaches it.
    #[test]
    fn importance_is_normalised_over_the_film() {
        let c = camera();
        let mut rng = crate::sampling::Pcg32::new(3, 7);
        let n = 400_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let d = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                rng.next_f32(),
                rng.next_f32(),
            ));
            let v = c.sample_direction_at_infinity(&c.lens(), d).map_or(0.0, |s| s.weight as f64)
                * 4.0
                * std::f64::consts::PI;
            // W·cos θ at infinity is the factor without 1/r²: ∫ over the sphere of directions
            sum += v;
            sum2 += v * v;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!((mean - 1.0).abs() < 4.0 * se, "{mean} ± {se}");
        let p = Vec3::new(0.3, -0.2, 0.5);
        let s = c.sample_direction(&c.lens(), p).unwrap();
        let r = c.sample_ray(s.film_uv);
        assert!((r.d + s.wi).length() < 1e-5, "{:?} vs {:?}", r.d, s.wi);
        assert!((s.dist - (p - s.position).length()).abs() < 1e-5);
        // behind the camera: no connection
        assert!(c.sample_direction(&c.lens(), Vec3::new(0.0, 0.0, 5.0)).is_none());
    }

    /// A principal point offset shifts the window: the shifted camera's pixel looks where the
    /// plain camera's pixel at the offset position looks, a point connects back to the shifted
    /// film position, and the importance stays normalised (it is the same window, moved).
    #[test]
    fn principal_point_offset_shifts_the_window() {
        let offset = Vec2::new(0.13, -0.07);
        let c = camera().with_principal_point_offset(offset).unwrap();
        let plain = camera();
        for uv in [Vec2::new(0.5, 0.5), Vec2::new(0.1, 0.9), Vec2::new(0.8, 0.3)] {
            let (a, b) = (c.sample_ray(uv), plain.sample_ray(uv + offset));
            assert!((a.d - b.d).length() < 1e-6 && (a.o - b.o).length() < 1e-6, "{uv}");
        }
        // a positive x offset turns the view towards the image's right (+x here)
        assert!(c.sample_ray(Vec2::splat(0.5)).d.x > 0.0);
        let p = Vec3::new(0.3, -0.2, 0.5);
        let s = c.sample_direction(&c.lens(), p).unwrap();
        let r = c.sample_ray(s.film_uv);
        assert!((r.d + s.wi).length() < 1e-5, "{:?} vs {:?}", r.d, s.wi);
        let sp = plain.sample_direction(&plain.lens(), p).unwrap();
        assert!((s.film_uv + offset - sp.film_uv).length() < 1e-5);
        assert!((s.weight - sp.weight).abs() <= 1e-6 * sp.weight);
        // a direction the plain camera sees at its left edge falls outside the shifted window
        let edge = plain.sample_ray(Vec2::new(0.05, 0.5)).d;
        assert!(plain.sample_direction_at_infinity(&plain.lens(), edge).is_some());
        assert!(c.sample_direction_at_infinity(&c.lens(), edge).is_none());
        assert!(camera().with_principal_point_offset(Vec2::new(f32::NAN, 0.0)).is_err());
    }

    #[test]
    fn scaled_camera_is_refused() {
        let tw = Transform::scale(Vec3::splat(2.0)).unwrap();
        assert!(Perspective::new(tw, 1.0, 1.0, 0.01, 100.0).is_err());
        assert!(Perspective::new(Transform::IDENTITY, 1.0, 1.0, 0.0, 100.0).is_err());
        assert!(Perspective::new(Transform::IDENTITY, 1.0, 1.0, 1.0, 0.5).is_err());
    }
}
