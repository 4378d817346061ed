//! # `depth` — distance to the first surface
//!
//! Mitsuba plugin `depth` (no parameters). Each camera ray's value is the distance t (m) from
//! its origin to the first surface it hits, the same in the three channels, and 0 where it
//! hits nothing. Camera rays start on the near-clip plane (Mitsuba's convention), so t is
//! measured from there; pixels average t over the samples of their filter as any image does
//! (a pixel on a silhouette holds a mix of both depths, as in Mitsuba).
//!
//! The image is a distance, not light: steradian refuses it for meters and irradiance maps,
//! whose readings are radiometric quantities.

use crate::geometry::Ray;
use crate::scene::Scene;
use crate::Spectrum;

/// The `depth` integrator.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DepthIntegrator;

impl DepthIntegrator {
    /// The distance (m) along `ray` to its first hit, 0 on a miss.
    #[inline]
    pub fn li(&self, scene: &Scene, ray: &Ray) -> Spectrum {
        scene.intersect(ray).map_or(Spectrum::ZERO, |si| Spectrum::splat(si.t))
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::integrator::PathTracer;
    use crate::testkit::scenes::lit_plane;

    /// A plane at z = 0 seen from height h: t = h / cos θ along a ray tilted by θ, 0 past it.
    #[test]
    fn distance_to_a_plane() {
        let job = lit_plane(
            Spectrum::splat(0.5),
            Spectrum::splat(1.0),
            Vec3::Z,
            4.0,
            PathTracer::default(),
        );
        let o = Vec3::new(0.1, -0.2, 2.5);
        for theta in [0.0f32, 0.3, 0.7] {
            let d = Vec3::new(theta.sin(), 0.0, -theta.cos());
            let t = DepthIntegrator.li(&job.scene, &Ray::new(o, d, f32::INFINITY));
            let want = 2.5 / theta.cos();
            assert!((t.x - want).abs() < 1e-4 * want && t.x == t.y && t.y == t.z, "{t} vs {want}");
        }
        let up = DepthIntegrator.li(&job.scene, &Ray::new(o, Vec3::Z, f32::INFINITY));
        assert_eq!(up, Spectrum::ZERO);
    }
}
