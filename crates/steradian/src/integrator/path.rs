//! `path`: unidirectional path tracing with next-event estimation.
//!
//! | parameter       | type    | default | meaning |
//! |-----------------|---------|---------|---------|
//! | `max_depth`     | integer | −1 (∞)  | longest path in segments: 1 = emitters seen directly, 2 = direct lighting, 0 = black |
//! | `rr_depth`      | integer | 5       | depth from which Russian roulette may end paths |
//! | `hide_emitters` | boolean | false   | emitters seen directly by camera rays contribute nothing |
//! | `light_selection` | string | `uniform` | steradian's own: `uniform` or `power` (see `light_selection.rs`) |
//!
//! At every vertex with a non-delta BSDF one light is chosen uniformly and sampled (next-event
//! estimation), and the BSDF is sampled to continue the path; both estimators of emitted light
//! are combined by multiple importance sampling with the power heuristic, as in Mitsuba 3.
//! Russian roulette continues with probability q = min(max(β)·η², 0.95) and divides the
//! throughput β by q, so the estimator stays unbiased.

use glam::Vec3;

use super::mis::power_heuristic;
use super::LightSelection;
use crate::bsdf::{Lobe, ShadingPoint};
use crate::emitter::Support;
use crate::geometry::Ray;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::shape::SurfacePoint;
use crate::Spectrum;
use crate::shape::is_positive;

/// Whether directly visible emitters are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmitterVisibility {
    Visible,
    Hidden,
}

#[derive(Clone, Debug, PartialEq)]
pub struct PathTracer {
    /// Maximum number of path segments; `None` = unbounded.
    pub max_depth: Option<u32>,
    pub rr_depth: u32,
    pub emitters: EmitterVisibility,
    pub light_selection: LightSelection,
}

impl Default for PathTracer {
    fn default() -> Self {
        PathTracer { max_depth: None, rr_depth: 5, emitters: EmitterVisibility::Visible, light_selection: LightSelection::Uniform }
    }
}

/// Mitsuba's `max_depth` convention: −1 means unbounded; other negatives are errors.
pub fn parse_max_depth(v: i64) -> Result<Option<u32>, String> {
    match v {
        -1 => Ok(None),
        v if v >= 0 && v <= u32::MAX as i64 => Ok(Some(v as u32)),
        v => Err(format!("max_depth must be -1 (unbounded) or >= 0, got {v}")),
    }
}

impl PathTracer {
    pub fn li(&self, scene: &Scene, camera_ray: &Ray, sampler: &mut PixelSampler) -> Spectrum {
        if self.max_depth == Some(0) {
            return Spectrum::ZERO;
        }
        let mut result = Spectrum::ZERO;
        let mut beta = Spectrum::ONE;
        let mut eta = 1.0f32;
        let mut depth = 0u32;
        let mut ray = *camera_ray;
        // the previous vertex, for MIS of emitters hit by BSDF sampling
        let mut prev_p = ray.o;
        let mut prev_pdf = 1.0f32;
        let mut prev_lobe = Lobe::Delta;

        loop {
            let show_emitters = depth > 0 || self.emitters == EmitterVisibility::Visible;
            let Some(si) = scene.intersect(&ray) else {
                if let (Some(env), true) = (scene.environment, show_emitters) {
                    let le = scene.emitters[env as usize].radiance(-ray.d, Vec3::ZERO, glam::Vec2::ZERO);
                    let w = match prev_lobe {
                        Lobe::Delta => 1.0,
                        Lobe::Smooth => power_heuristic(prev_pdf, scene.pdf_emitter_direction(env, prev_p, ray.d, &SurfacePoint::AT_INFINITY)),
                    };
                    result += beta * le * w;
                }
                break;
            };

            if let (Some((e, emitter)), true) = (scene.area_emitter(&si), show_emitters) {
                let le = emitter.radiance(si.wo, si.n, si.uv);
                if le != Spectrum::ZERO {
                    let w = match prev_lobe {
                        Lobe::Delta => 1.0,
                        Lobe::Smooth => power_heuristic(prev_pdf, scene.pdf_emitter_direction(e, prev_p, ray.d, &si.surface_point())),
                    };
                    result += beta * le * w;
                }
            }

            if let Some(max) = self.max_depth {
                if depth + 1 >= max {
                    break;
                }
            }

            let bsdf = scene.bsdf(&si);
            let sp = ShadingPoint::new(&si);
            let wo = si.to_local(si.wo);

            // Six numbers per vertex, drawn in a fixed order so that with Sobol points each pair
            // is a well-stratified 2-D projection: light (2-D), BSDF direction (2-D), lobe
            // choice, Russian roulette (drawn even when unused, to keep the layout fixed).
            let u_light = sampler.next_2d();
            let u2 = sampler.next_2d();
            let u1 = sampler.next_1d();
            let u_rr = sampler.next_1d();

            // next-event estimation
            if bsdf.has_smooth_lobe() {
                if let Some(es) = scene.sample_emitter_direction(si.p, u_light) {
                    let wi = si.to_local(es.wi);
                    let f = bsdf.eval(&sp, wo, wi) * wi.z.abs();
                    if f != Spectrum::ZERO && scene.unoccluded(si.p, si.n, &es) {
                        let w = match es.support {
                            Support::Delta => 1.0,
                            Support::Extended => power_heuristic(es.pdf, bsdf.pdf(&sp, wo, wi)),
                        };
                        result += beta * f * es.weight * w;
                    }
                }
            }

            // continue the path by sampling the BSDF
            let Some(bs) = bsdf.sample(&sp, wo, u1, u2) else { break };
            beta *= bs.weight;
            eta *= bs.eta;
            prev_p = si.p;
            prev_pdf = bs.pdf;
            prev_lobe = bs.lobe;
            ray = si.spawn_ray(si.to_world(bs.wi).normalize());
            depth += 1;

            let beta_max = beta.max_element();
            if !is_positive(beta_max) {
                break;
            }
            if depth >= self.rr_depth {
                let q = (beta_max * eta * eta).min(0.95);
                if u_rr >= q {
                    break;
                }
                beta /= q;
            }
        }
        result
    }
}
