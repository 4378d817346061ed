//! `thinlens`: a perspective camera with a circular thin-lens aperture (depth of field).
//!
//! Parameters as [`perspective`](super::Perspective), plus:
//!
//! | parameter         | type  | default   | meaning |
//! |-------------------|-------|-----------|---------|
//! | `aperture_radius` | float | required  | lens radius, m (0 is replaced by a tiny radius, as in Mitsuba) |
//! | `focus_distance`  | float | far_clip  | distance of the plane in focus along the view axis, m |
//!
//! A ray starts at a uniformly sampled point of the aperture disk and passes through the point
//! of the focal plane that the pinhole ray of the same film position meets.

use glam::{Vec2, Vec3};

use super::perspective::{validate, Perspective};
use crate::geometry::{Ray, Transform};
use crate::param::ParamError;
use crate::sampling::warp;

#[derive(Clone, Debug)]
pub struct ThinLens {
    pub to_world: Transform,
    tan_half: Vec2,
    pub near_clip: f32,
    pub far_clip: f32,
    pub aperture_radius: f32,
    pub focus_distance: f32,
}

impl ThinLens {
    pub fn new(
        to_world: Transform,
        x_fov: f32,
        aspect: f32,
        near_clip: f32,
        far_clip: f32,
        aperture_radius: f32,
        focus_distance: f32,
    ) -> Result<Self, ParamError> {
        validate(&to_world, near_clip, far_clip)?;
        if !(aperture_radius >= 0.0 && aperture_radius.is_finite()) {
            return Err(ParamError::new(
                "aperture_radius",
                format!("aperture_radius must be non-negative, got {aperture_radius}"),
            ));
        }
        if !(focus_distance > 0.0 && focus_distance.is_finite()) {
            return Err(ParamError::new(
                "focus_distance",
                format!("focus_distance must be positive, got {focus_distance}"),
            ));
        }
        let tx = (x_fov / 2.0).tan();
        Ok(ThinLens {
            to_world,
            tan_half: Vec2::new(tx, tx / aspect),
            near_clip,
            far_clip,
            aperture_radius: aperture_radius.max(f32::EPSILON),
            focus_distance,
        })
    }

    #[inline]
    pub fn sample_ray(&self, film_uv: Vec2, aperture_u: Vec2) -> Ray {
        let dir = Perspective::local_direction(self.tan_half, film_uv);
        let focus_p = dir * self.focus_distance; // dir.z = 1
        let a = self.aperture_radius * warp::square_to_uniform_disk_concentric(aperture_u);
        let aperture_p = Vec3::new(a.x, a.y, 0.0);
        let d = (focus_p - aperture_p).normalize();
        let inv_z = 1.0 / d.z;
        let (near_t, far_t) = (self.near_clip * inv_z, self.far_clip * inv_z);
        let d_world = self.to_world.vector(d).normalize();
        Ray::new(self.to_world.point(aperture_p) + d_world * near_t, d_world, far_t - near_t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_aperture_rays_meet_on_the_focal_plane() {
        let c = ThinLens::new(Transform::IDENTITY, 0.8, 1.5, 0.01, 1e4, 0.2, 3.0).unwrap();
        let film = Vec2::new(0.3, 0.8);
        let mut meet: Option<Vec3> = None;
        for (i, j) in [(0.1, 0.2), (0.9, 0.5), (0.5, 0.5), (0.3, 0.95)] {
            let r = c.sample_ray(film, Vec2::new(i, j));
            let t = (3.0 - r.o.z) / r.d.z;
            let p = r.at(t);
            if let Some(m) = meet {
                assert!((p - m).length() < 1e-4, "{p:?} vs {m:?}");
            }
            meet = Some(p);
        }
    }
}
