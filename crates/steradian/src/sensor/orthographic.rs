//! `orthographic`: a camera without perspective, measuring radiance along its view axis.
//!
//! | parameter   | type      | default  | meaning |
//! |-------------|-----------|----------|---------|
//! | `to_world`  | transform | identity | camera → world; unlike the perspective cameras it may scale: the scale sets the size of the sensor plane |
//! | `near_clip` | float     | 0.01 ([`DEFAULT_NEAR_CLIP`]) | camera-space distance of the plane rays start on |
//! | `far_clip`  | float     | 10000 ([`DEFAULT_FAR_CLIP`]) | rays end `far_clip − near_clip` (world units) after their start |
//! | film, sampler | children | `hdrfilm`, `independent` | |
//!
//! There is no field of view. In camera space the sensor is the rectangle x ∈ [−1, 1],
//! y ∈ [−1/aspect, 1/aspect] (aspect = film width/height, so the film's x always spans
//! [−1, 1], as Mitsuba's fov defaults to the x axis), on the plane z = `near_clip`, and every
//! ray points along +z. For a film position (sx, sy) ∈ \[0, 1\]² (pixel (0,0) top-left, as for
//! [`perspective`](super::Perspective)) the ray starts at
//! `to_world · (1 − 2sx, (1 − 2sy)/aspect, near_clip)` and runs along
//! `normalize(to_world · (0, 0, 1))` for `far_clip − near_clip`. So a 10×10 sensor is
//! `<scale x="5" y="5"/>` before the `lookat`.
//!
//! This is Mitsuba 3.9.1's behaviour, checked by sampling rays of its plugin: a scale along
//! the camera's z moves the start plane (it multiplies `near_clip`) but not the ray length.
//! Mitsuba's `srf` (sensor response function, spectral variants) and `shutter_open`/
//! `shutter_close` (motion blur) are not supported and are refused as unknown parameters.

use glam::{Vec2, Vec3};

use crate::geometry::{Ray, Transform};
use crate::param::ParamError;

/// Mitsuba's default near clip distance (camera space).
pub const DEFAULT_NEAR_CLIP: f32 = 0.01;
/// Mitsuba's default far clip distance.
pub const DEFAULT_FAR_CLIP: f32 = 1e4;

#[derive(Clone, Debug)]
pub struct Orthographic {
    pub to_world: Transform,
    /// Half the sensor's camera-space height: 1/aspect.
    half_height: f32,
    pub near_clip: f32,
    pub far_clip: f32,
    /// World-space unit view direction.
    dir: Vec3,
}

impl Orthographic {
    /// `aspect` = film width/height.
    pub fn new(
        to_world: Transform,
        aspect: f32,
        near_clip: f32,
        far_clip: f32,
    ) -> Result<Self, ParamError> {
        if !(near_clip > 0.0 && near_clip.is_finite()) {
            let reason = format!("near_clip must be positive, got {near_clip}");
            return Err(ParamError::new("near_clip", reason));
        }
        if !(far_clip > near_clip && far_clip.is_finite()) {
            let reason = format!("far_clip ({far_clip}) must exceed near_clip ({near_clip})");
            return Err(ParamError::new("far_clip", reason).with_related("near_clip"));
        }
        if !(aspect > 0.0 && aspect.is_finite()) {
            let reason = format!("the film's aspect ratio must be positive, got {aspect}");
            return Err(ParamError::new("to_world", reason));
        }
        let dir = to_world.vector(Vec3::Z).normalize_or_zero();
        if dir == Vec3::ZERO || !dir.is_finite() {
            let reason = "to_world maps the view axis (0, 0, 1) to a zero vector";
            return Err(ParamError::new("to_world", reason));
        }
        let o = to_world.point(Vec3::ZERO);
        let corner = to_world.point(Vec3::new(1.0, 1.0 / aspect, near_clip));
        if !(o.is_finite() && corner.is_finite()) {
            return Err(ParamError::new("to_world", "to_world is not finite"));
        }
        Ok(Orthographic { to_world, half_height: 1.0 / aspect, near_clip, far_clip, dir })
    }

    /// The world-space view direction (unit).
    #[inline]
    pub fn direction(&self) -> Vec3 {
        self.dir
    }

    #[inline]
    pub fn sample_ray(&self, film_uv: Vec2) -> Ray {
        let local = Vec3::new(
            1.0 - 2.0 * film_uv.x,
            (1.0 - 2.0 * film_uv.y) * self.half_height,
            self.near_clip,
        );
        Ray::new(self.to_world.point(local), self.dir, self.far_clip - self.near_clip)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rays Mitsuba 3.9.1's `orthographic` samples for to_world = T(0,0,1)·S(2,3,1),
    /// near 0.5, far 20 (printed with `sensor.sample_ray`).
    #[test]
    fn rays_match_mitsuba() {
        let tw = Transform::scale(Vec3::new(2.0, 3.0, 1.0))
            .unwrap()
            .then(&Transform::translate(Vec3::Z));
        for (w, h, corner_y) in [(96.0, 72.0, 2.25), (72.0, 96.0, 4.0)] {
            let c = Orthographic::new(tw, w / h, 0.5, 20.0).unwrap();
            for (uv, o) in [
                (Vec2::new(0.0, 0.0), Vec3::new(2.0, corner_y, 1.5)),
                (Vec2::new(1.0, 1.0), Vec3::new(-2.0, -corner_y, 1.5)),
                (Vec2::new(0.5, 0.5), Vec3::new(0.0, 0.0, 1.5)),
                (Vec2::new(1.0, 0.5), Vec3::new(-2.0, 0.0, 1.5)),
            ] {
                let r = c.sample_ray(uv);
                assert!((r.o - o).length() < 1e-5, "{w}x{h} {uv}: {} vs {o}", r.o);
                assert_eq!(r.d, Vec3::Z);
                assert!((r.t_max - 19.5).abs() < 1e-5);
            }
        }
        // a z scale moves the start plane but not the far end: o.z = 5·0.01, t_max = 1e4 − 0.01
        let tw = Transform::scale(Vec3::new(2.0, 2.0, 5.0)).unwrap();
        let r = Orthographic::new(tw, 1.0, DEFAULT_NEAR_CLIP, DEFAULT_FAR_CLIP)
            .unwrap()
            .sample_ray(Vec2::splat(0.5));
        assert!((r.o - Vec3::new(0.0, 0.0, 0.05)).length() < 1e-6 && r.d == Vec3::Z);
        assert!((r.t_max - 9999.99).abs() < 1e-3);
    }

    #[test]
    fn bad_parameters_are_refused() {
        let id = Transform::IDENTITY;
        assert!(Orthographic::new(id, 1.0, 0.0, 1.0).is_err());
        assert!(Orthographic::new(id, 1.0, 1.0, 1.0).is_err());
        assert!(Orthographic::new(id, 1.0, 0.1, f32::INFINITY).is_err());
        // a singular to_world is refused by Transform itself; a 0 aspect by the camera
        assert!(Orthographic::new(id, 0.0, 0.1, 1.0).is_err());
    }
}
