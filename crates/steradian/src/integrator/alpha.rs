//! The coverage of a camera ray: the value each camera sample gives an `rgba` film's alpha
//! channel (the rules, checked against Mitsuba 3.9.1, are in `film/pixel_format.rs`).
//!
//! Mitsuba marks a path valid (alpha 1) once it scatters somewhere, null crossings aside, or
//! from the start where an environment is visible; steradian takes the expectation of that
//! 0-or-1 value along the camera ray: 1 − T, T the probability of passing every null surface
//! and medium to the end of the ray (no estimator of its own: the null transmission and the
//! media's transmittance estimates that shadow rays use). The radiance is computed first, so
//! an `rgba` image is the `rgb` image bit for bit.

use crate::bsdf::ShadingPoint;
use crate::geometry::{offset_ray_origin, Ray};
use crate::integrator::EmitterVisibility;
use crate::sampling::PixelSampler;
use crate::scene::{Scene, MAX_NULL_CROSSINGS};
use crate::Spectrum;

/// How an integrator's camera samples cover the film.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlphaRule {
    /// 1 where the camera ray hits any surface, `null` ones included (`direct`, `depth`,
    /// `aov`).
    AnySurface,
    /// The probability that the path meets something other than a null crossing; 1 where an
    /// environment is visible (`path`, `volpath`).
    Scattering { media: MediaInAlpha, emitters: EmitterVisibility },
}

/// Whether media along the camera ray take part (`volpath`) or are ignored (`path`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MediaInAlpha {
    Ignored,
    Attenuating,
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
        AlphaRule::AnySurface => return if scene.occluded(ray) { 1.0 } else { 0.0 },
        AlphaRule::Scattering { media, emitters } => (media, emitters),
    };
    let environment = scene.environment.is_some() || scene.sun.is_some();
    if emitters == EmitterVisibility::Visible && environment {
        return 1.0;
    }
    let mut medium = match media {
        MediaInAlpha::Ignored => None,
        MediaInAlpha::Attenuating => scene.camera_medium,
    };
    if medium.is_none() && !scene.has_null_surfaces() {
        // every surface scatters and no medium can: coverage is a hit
        return if scene.occluded(ray) { 1.0 } else { 0.0 };
    }
    let mut pass = Spectrum::ONE;
    let mut r = *ray;
    for _ in 0..MAX_NULL_CROSSINGS {
        let hit = scene.intersect(&r);
        if let Some(m) = medium {
            let t = hit.as_ref().map_or(r.t_max, |si| si.t);
            pass *= scene.media[m as usize].transmittance(&r, t, sampler);
        }
        let Some(si) = hit else { return 1.0 - pass.element_sum() / 3.0 };
        pass *= scene.bsdf(&si).null_transmission(&ShadingPoint::new(&si), si.to_local(si.wo));
        if pass == Spectrum::ZERO {
            return 1.0;
        }
        if media == MediaInAlpha::Attenuating {
            medium = scene.medium_after(&si, r.d, medium);
        }
        r = Ray::new(offset_ray_origin(si.p, si.n, r.d), r.d, r.t_max - si.t);
    }
    // caught between coincident surfaces: counted as covered, as shadow rays count it blocked
    1.0
}
