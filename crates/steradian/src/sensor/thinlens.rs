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
//!
//! ## Importance (for particle tracing)
//!
//! A film position maps to a point of the focal plane, at distance F along the axis; from an
//! aperture point a, the ray towards it leaves at angle θ from the axis. The film position is
//! uniform over the image rectangle of area A·F² on the focal plane (A as for
//! [`perspective`](super::Perspective)), and dω = cos θ dA_focal/(F/cos θ)², so a unit of film
//! area is A·cos³θ of solid angle at a; the aperture point is uniform over πR². The camera's
//! importance is therefore W(a, θ) = 1/(πR²·A·cos⁴θ) per unit area of the aperture and solid
//! angle. `ptracer` connects a point at distance r to an aperture point drawn uniformly
//! (density 1/(πR²)), which gives the factor W·cos θ/r² · πR² = 1/(A·cos³θ·r²): the pinhole's,
//! with θ and r taken from the aperture point, and the film position that of the focal-plane
//! point the ray from the aperture point through the lit point meets. Points out of focus
//! spread over a disc of the film: the blur of `path`'s image, reached from the light.

use glam::{Vec2, Vec3};

use super::perspective::{
    film_position, importance_factor, on_film, validate, LensSample, Perspective, SensorConnection,
};
use crate::geometry::{is_positive, Ray, Transform};
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

    /// A point of the aperture, uniform by area (the same warp as [`ThinLens::sample_ray`]'s).
    #[inline]
    pub fn sample_lens(&self, u: Vec2) -> LensSample {
        let a = self.aperture_radius * warp::square_to_uniform_disk_concentric(u);
        let local = Vec3::new(a.x, a.y, 0.0);
        LensSample { position: self.to_world.point(local), local }
    }

    /// The film position and importance factor W·cos θ (module docs) of the ray from aperture
    /// point `lens` along camera-space direction `local`; `None` outside the film.
    #[inline]
    fn importance(&self, lens: &LensSample, local: Vec3) -> Option<(Vec2, f32)> {
        if !is_positive(local.z) {
            return None;
        }
        // where the ray meets the focal plane, as a direction from the pinhole
        let focus_p = lens.local + local * (self.focus_distance / local.z);
        let film_uv = film_position(self.tan_half, focus_p);
        on_film(film_uv).then(|| (film_uv, importance_factor(self.tan_half, local)))
    }

    /// The connection from world point `p` to aperture point `lens`; `None` when `p` is
    /// outside the clip range (depth along the axis in [near_clip, far_clip]) or the ray from
    /// `lens` through `p` misses the film.
    #[inline]
    pub fn sample_direction(&self, lens: &LensSample, p: Vec3) -> Option<SensorConnection> {
        let local_p = self.to_world.inverse().point(p);
        if !(local_p.z >= self.near_clip && local_p.z <= self.far_clip) {
            return None;
        }
        let (film_uv, w) = self.importance(lens, local_p - lens.local)?;
        Some(SensorConnection::to_point(lens, p, film_uv, w))
    }

    /// [`ThinLens::sample_direction`] for light arriving from world direction `wi` (towards
    /// the light) at infinity: W·cos θ, without the 1/r².
    #[inline]
    pub fn sample_direction_at_infinity(
        &self,
        lens: &LensSample,
        wi: Vec3,
    ) -> Option<SensorConnection> {
        let local = self.to_world.inverse().vector(wi);
        let (film_uv, weight) = self.importance(lens, local)?;
        Some(SensorConnection::from_infinity(lens, wi, film_uv, weight))
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

    /// The connection from a point to an aperture point names the film position whose camera
    /// ray, started at that aperture point, passes through the point.
    #[test]
    fn a_connection_names_the_film_position_whose_ray_meets_the_point() {
        let tw = Transform::look_at(Vec3::new(0.5, 1.0, 4.0), Vec3::ZERO, Vec3::Y).unwrap();
        let c = ThinLens::new(tw, 0.9, 1.5, 0.01, 1e4, 0.3, 2.5).unwrap();
        for (u, p) in [
            (Vec2::new(0.2, 0.7), Vec3::new(0.3, -0.2, 0.1)),
            (Vec2::new(0.9, 0.1), Vec3::new(-0.6, 0.4, -1.5)),
            (Vec2::new(0.5, 0.5), Vec3::new(0.1, 0.2, 1.0)),
        ] {
            let lens = c.sample_lens(u);
            let conn = c.sample_direction(&lens, p).expect("in view");
            let ray = c.sample_ray(conn.film_uv, u);
            let to_p = (p - ray.o).normalize();
            assert!(to_p.dot(ray.d) > 1.0 - 1e-6, "{u:?}: ray {:?} misses {p:?}", ray.d);
            assert!((conn.position - lens.position).length() < 1e-6);
            assert!((conn.wi + to_p).length() < 1e-4);
        }
    }
}
