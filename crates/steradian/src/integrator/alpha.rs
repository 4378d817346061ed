//! The coverage of a camera ray: the value each camera sample gives an `rgba` film's alpha
//! channel (the rules, checked against Mitsuba 3.9.1, are in `film/pixel_format.rs`).
//!
//! Mitsuba marks a path valid (alpha 1) once it scatters somewhere, null crossings aside, or
//! from the start where an environment is visible; steradian takes the expectation of that
//! 0-or-1 value along the camera ray: 1 − T, T the probability of passing every null surface
//! and medium to the end of the ray (no estimator of its own: [`Scene::transmittance`], which
//! shadow rays use). The radiance is computed first, so an `rgba` image is the `rgb` image
//! bit for bit.

use glam::Vec3;

use crate::geometry::Ray;
use crate::integrator::EmitterVisibility;
use crate::sampling::PixelSampler;
use crate::scene::{MediaAlong, Scene};

/// How an integrator's camera samples cover the film.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlphaRule {
    /// 1 where the camera ray hits any surface, `null` ones included (`direct`, `depth`,
    /// `aov`), past the lights `direct` hides.
    AnySurface { emitters: EmitterVisibility },
    /// The probability that the path meets something other than a null crossing; 1 where an
    /// environment is visible (`path`, whose camera rays ignore media; `volpath`, whose
    /// follow them).
    Scattering { media: MediaAlong, emitters: EmitterVisibility },
}

/// The alpha of a camera sample along `ray` (see the module docs), in [0, 1] for surfaces;
/// an unbiased estimate through heterogeneous media (whose transmittance is estimated).
pub fn camera_ray_alpha(
    scene: &Scene,
    ray: &Ray,
    rule: AlphaRule,
    sampler: &mut PixelSampler,
) -> f32 {
    let (media, emitters) = match rule {
        AlphaRule::AnySurface { emitters } => {
            return if scene.occluded(&emitters.camera_ray(scene, ray)) { 1.0 } else { 0.0 }
        }
        AlphaRule::Scattering { media, emitters } => (media, emitters),
    };
    let environment = scene.environment.is_some() || scene.sun.is_some();
    if emitters == EmitterVisibility::Visible && environment {
        return 1.0;
    }
    let ray = &emitters.camera_ray(scene, ray);
    // a point in free space (no normal to offset along), in the camera's medium
    let pass = scene.transmittance(
        ray.o,
        Vec3::ZERO,
        ray.d,
        ray.t_max,
        scene.camera_medium,
        media,
        sampler,
    );
    1.0 - pass.element_sum() / 3.0
}
