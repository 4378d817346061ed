//! The irradiance estimator shared by the `irradiancemeter` and irradiance maps.
//!
//! H(p, n) = ∫ L(ωi) cos θi dωi over the hemisphere around n (W/m²). L splits into light
//! arriving straight from emitters and light reflected by other surfaces:
//!
//! - Emitted light is estimated by two strategies combined with the power heuristic: every
//!   emitter is sampled once (delta lights contribute I·cos θ/r² or H·cos θ exactly, with
//!   weight 1), and a cosine-weighted direction that happens to hit an emitter (or escapes to
//!   an `envmap` sky). The uniform sky (`constant`) is the exception: for a radiance that is
//!   the same in every direction the cosine-weighted strategy alone has zero variance wherever
//!   the sky is unoccluded, so it is used alone (with weight 1) rather than diluted by
//!   uniform-sphere samples.
//! - Reflected light along the cosine-weighted direction comes from the scene's integrator
//!   with the first hit's own emission hidden, so `max_depth` keeps Mitsuba's meaning (1 =
//!   emitters seen directly from the meter, 2 = one bounce, ...).
//! - Under `volpath` the meter may sit in a medium (the sensors') and light reach it through
//!   media and null surfaces: one light sample weighted by its transmittance, and π·L along the
//!   cosine-weighted direction traced by `volpath`, combined by MIS.

use std::f32::consts::PI;

use glam::Vec3;

use super::mis::power_heuristic;
use super::{EmitterVisibility, Integrator, PathTracer, VolPathTracer};
use crate::emitter::{Emitter, Support};
use crate::geometry::{offset_ray_origin, Frame, Ray};
use crate::sampling::{warp, PixelSampler};
use crate::scene::{MediaAlong, Scene};
use crate::Spectrum;

/// The integrator with emission at the first hit hidden, and how many segments remain.
fn reflected_only(integrator: &Integrator) -> Option<Integrator> {
    match integrator {
        Integrator::Path(p) => {
            if p.max_depth.is_some_and(|d| d <= 1) {
                return None;
            }
            let mut p = p.clone();
            p.emitters = EmitterVisibility::Hidden;
            // the meter's light is physical: no path is zeroed for crossing only null
            // surfaces (`path.rs`, "Null surfaces": Mitsuba's camera-image rule)
            p.null_paths = super::NullPaths::Kept;
            Some(Integrator::Path(p))
        }
        Integrator::Direct(d) => {
            let mut d = d.clone();
            d.emitters = EmitterVisibility::Hidden;
            Some(Integrator::Direct(d))
        }
        // estimated whole by `estimate_irradiance` (light sampled only along the path)
        Integrator::VolPath(_) => None,
        // refused by the render plan (Integrator::estimates_light, particle tracing)
        Integrator::Depth(_) | Integrator::ParticleTracer(_) => None,
        Integrator::Moment(super::MomentIntegrator { nested })
        | Integrator::Aov(super::AovIntegrator { nested, .. }) => {
            nested.first().and_then(|(_, i)| reflected_only(i))
        }
    }
}

/// The irradiance under `volpath`: the meter may sit in a medium (the sensors'), and light
/// reach it through media and null surfaces. One light sample (the scene's light choice),
/// weighted by the transmittance to it, and one cosine-weighted direction traced by `volpath`,
/// combined by MIS with the power heuristic.
fn volpath_irradiance(
    scene: &Scene,
    v: &VolPathTracer,
    p: Vec3,
    n: Vec3,
    sampler: &mut PixelSampler,
) -> Spectrum {
    let cos_pdf = |wi: Vec3| n.dot(wi).max(0.0) / PI;
    let medium = scene.camera_medium;
    let mut h = Spectrum::ZERO;
    if let Some(es) = scene.sample_emitter_direction(p, sampler.next_2d()) {
        let cos = n.dot(es.wi);
        if cos > 0.0 {
            let tr =
                scene.transmittance(p, n, es.wi, es.dist, medium, MediaAlong::Followed, sampler);
            let w = match es.support {
                Support::Delta => 1.0,
                Support::Extended => power_heuristic(es.pdf, cos_pdf(es.wi)),
            };
            h += es.weight * tr * (cos * w);
        }
    }
    let Some((ray, pdf)) = cosine_ray(p, n, sampler) else { return h };
    let last = super::volpath::LastScatter::Sampled { p, pdf };
    let visible = VolPathTracer { emitters: EmitterVisibility::Visible, ..v.clone() };
    h + visible.li_from(scene, &ray, medium, last, sampler) * PI
}

/// One-sample estimate of the irradiance (W/m², per channel) at `p` on the side of the unit
/// normal `n` (geometric normal of the surface, used to offset rays).
pub fn estimate_irradiance(
    scene: &Scene,
    integrator: &Integrator,
    p: Vec3,
    n: Vec3,
    sampler: &mut PixelSampler,
) -> Spectrum {
    match integrator {
        Integrator::Path(PathTracer { max_depth: Some(0), .. })
        | Integrator::VolPath(VolPathTracer { max_depth: Some(0), .. }) => return Spectrum::ZERO,
        Integrator::VolPath(v) => return volpath_irradiance(scene, v, p, n, sampler),
        _ => {}
    }
    let mut h = Spectrum::ZERO;
    let cos_pdf = |wi: Vec3| n.dot(wi).max(0.0) / PI;

    // 1. every emitter, sampled once
    for emitter in scene.emitters.iter() {
        let u = sampler.next_2d();
        if matches!(emitter, Emitter::Constant(_)) {
            continue;
        }
        let Some(es) = emitter.sample_direction(&scene.shapes, p, u) else { continue };
        let cos = n.dot(es.wi);
        if cos <= 0.0 {
            continue;
        }
        if !scene.unoccluded(p, n, &es) {
            continue;
        }
        let w = match es.support {
            Support::Delta => 1.0,
            Support::Extended => power_heuristic(es.pdf, cos_pdf(es.wi)),
        };
        h += es.weight * cos * w;
    }

    // 2. a cosine-weighted direction: weight L·cos/pdf = π·L
    let Some((ray, pdf)) = cosine_ray(p, n, sampler) else { return h };
    let wi = ray.d;
    match scene.intersect(&ray) {
        Some(hit) => {
            if let Some((_, emitter)) = scene.area_emitter(&hit) {
                let le = emitter.radiance(hit.wo, hit.sh_frame.n, hit.uv);
                if le != Spectrum::ZERO {
                    let pdf_e = emitter.pdf_direction(&scene.shapes, p, wi, &hit.surface_point());
                    h += le * (PI * power_heuristic(pdf, pdf_e));
                }
            }
        }
        None => {
            if let Some(env) = scene.environment {
                let emitter = &scene.emitters[env as usize];
                // one lookup for the radiance and the light-sampling density
                let (le, pdf_e) = emitter.radiance_and_pdf_from(wi);
                // a `constant` sky is not light-sampled here (see the module docs): weight 1
                let w = match emitter {
                    Emitter::Constant(_) => 1.0,
                    _ => power_heuristic(pdf, pdf_e),
                };
                h += le * (PI * w);
            }
            if let Some(sun) = scene.sun {
                let (le, pdf_e) = scene.emitters[sun as usize].radiance_and_pdf_from(wi);
                if le != Spectrum::ZERO {
                    h += le * (PI * power_heuristic(pdf, pdf_e));
                }
            }
        }
    }
    if let Some(reflected) = reflected_only(integrator) {
        h += reflected.li(scene, &ray, sampler) * PI;
    }
    h
}

/// A cosine-weighted direction about `n` leaving `p` (offset off the surface) and its density
/// cos θ/π (1/sr); `None` for a direction in the plane.
#[inline]
fn cosine_ray(p: Vec3, n: Vec3, sampler: &mut PixelSampler) -> Option<(Ray, f32)> {
    let local = warp::square_to_cosine_hemisphere(sampler.next_2d());
    if local.z <= 0.0 {
        return None;
    }
    let wi = Frame::from_normal(n).to_world(local).normalize();
    Some((Ray::infinite(offset_ray_origin(p, n, wi), wi), n.dot(wi).max(0.0) / PI))
}
