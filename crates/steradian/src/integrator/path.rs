//! `path`: unidirectional path tracing with next-event estimation.
//!
//! | parameter       | type    | default | meaning |
//! |-----------------|---------|---------|---------|
//! | `max_depth`     | integer | −1 (∞)  | longest path in segments: 1 = emitters seen directly, 2 = direct lighting, 0 = black |
//! | `rr_depth`      | integer | 5       | depth from which Russian roulette may end paths |
//! | `hide_emitters` | boolean | false   | emitters seen directly by camera rays contribute nothing |
//! | `light_selection` | string | `uniform` | steradian's own: `uniform` or `power` (see `light_selection.rs`) |
//! | `branches`      | integer | 4       | steradian's own: paths continued from each camera ray's first hit (1 to 64; 1 = Mitsuba's estimator) |
//!
//! At every vertex with a non-delta BSDF one light is chosen uniformly and sampled (next-event
//! estimation), and the BSDF is sampled to continue the path; both estimators of emitted light
//! are combined by multiple importance sampling with the power heuristic, as in Mitsuba 3.
//! Russian roulette continues with probability q = min(max(β)·η², 0.95) and divides the
//! throughput β by q, so the estimator stays unbiased.
//!
//! **Splitting at the first hit.** A camera sample traces its ray to the first surface once,
//! counts the light emitted there once, then continues from that point into `branches`
//! independent paths (each with its own next-event estimate, BSDF sample and roulette) and
//! averages them. Each branch is an unbiased estimate of the light leaving the first hit, so
//! the average is too, and the image's expectation is Mitsuba's; only the noise changes. The
//! camera ray, the first intersection and the film splat are paid once per `branches` paths,
//! and the branches of a pixel draw their numbers from one stratified set of
//! `branches × spp` Sobol points. Most of an image's noise comes after the first hit (in the
//! Cornell box, 98 % of relMSE at 64 spp is indirect light), so this buys more than the same
//! time spent on more camera samples: at equal time, relMSE against Mitsuba's references
//! falls by 1.4× (cornell), 1.6× (materials) and 1.9× (veach) with 4 branches, which are
//! close to the best counts for all three (measured, benches/README.md). A sample costs more,
//! so `spp` (camera samples, Mitsuba's meaning) buys less noise per second with `branches` = 1
//! than with 4 only in scenes whose noise comes from the pixel footprint itself, such as
//! direct light from point sources with `max_depth` = 2.

use glam::Vec3;

use super::mis::power_heuristic;
use super::LightSelection;
use crate::bsdf::{Lobe, ShadingPoint};
use crate::emitter::Support;
use crate::geometry::{Ray, SurfaceInteraction};
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
    /// Independent paths continued from each camera ray's first surface hit (≥ 1).
    pub branches: u32,
}

impl Default for PathTracer {
    fn default() -> Self {
        PathTracer { max_depth: None, rr_depth: 5, emitters: EmitterVisibility::Visible, light_selection: LightSelection::Uniform, branches: DEFAULT_BRANCHES }
    }
}

/// Paths continued from each first hit by default (see the module docs).
pub const DEFAULT_BRANCHES: u32 = 4;

/// The most branches a camera sample may split into.
pub const MAX_BRANCHES: u32 = 64;

/// Checks a `branches` value: 1 to [`MAX_BRANCHES`].
pub fn parse_branches(v: i64) -> Result<u32, String> {
    match v {
        v if (1..=MAX_BRANCHES as i64).contains(&v) => Ok(v as u32),
        v => Err(format!("branches must be between 1 and {MAX_BRANCHES}, got {v}")),
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

/// The state of a path between two vertices.
#[derive(Clone, Copy, Debug)]
struct PathState {
    /// Throughput: the product of f·cos/pdf (and 1/q for Russian roulette) so far.
    beta: Spectrum,
    /// Product of the relative indices of refraction crossed (for Russian roulette).
    eta: f32,
    /// Segments traced so far.
    depth: u32,
    ray: Ray,
    /// The previous vertex, for MIS of emitters hit by BSDF sampling.
    prev_p: Vec3,
    prev_pdf: f32,
    prev_lobe: Lobe,
}

impl PathTracer {
    /// Radiance arriving along `camera_ray` (W/(m²·sr)): one camera sample, split into
    /// [`PathTracer::branches`] paths at its first hit.
    pub fn li(&self, scene: &Scene, camera_ray: &Ray, sampler: &mut PixelSampler) -> Spectrum {
        if self.max_depth == Some(0) {
            return Spectrum::ZERO;
        }
        let st = PathState { beta: Spectrum::ONE, eta: 1.0, depth: 0, ray: *camera_ray, prev_p: camera_ray.o, prev_pdf: 1.0, prev_lobe: Lobe::Delta };
        self.walk(scene, st, sampler, self.branches)
    }

    /// Follows a path from `st` and returns the light it gathers; the first surface vertex it
    /// meets at depth 0 is left by `branches` paths.
    fn walk(&self, scene: &Scene, mut st: PathState, sampler: &mut PixelSampler, branches: u32) -> Spectrum {
        let mut result = Spectrum::ZERO;
        loop {
            let show_emitters = st.depth > 0 || self.emitters == EmitterVisibility::Visible;
            let Some(si) = scene.intersect(&st.ray) else {
                if let (Some(env), true) = (scene.environment, show_emitters) {
                    let le = scene.emitters[env as usize].radiance(-st.ray.d, Vec3::ZERO, glam::Vec2::ZERO);
                    let w = match st.prev_lobe {
                        Lobe::Delta => 1.0,
                        Lobe::Smooth => power_heuristic(st.prev_pdf, scene.pdf_emitter_direction(env, st.prev_p, st.ray.d, &SurfacePoint::AT_INFINITY)),
                    };
                    result += st.beta * le * w;
                }
                break;
            };

            if let (Some((e, emitter)), true) = (scene.area_emitter(&si), show_emitters) {
                let le = emitter.radiance(si.wo, si.n, si.uv);
                if le != Spectrum::ZERO {
                    let w = match st.prev_lobe {
                        Lobe::Delta => 1.0,
                        Lobe::Smooth => power_heuristic(st.prev_pdf, scene.pdf_emitter_direction(e, st.prev_p, st.ray.d, &si.surface_point())),
                    };
                    result += st.beta * le * w;
                }
            }

            if let Some(max) = self.max_depth {
                if st.depth + 1 >= max {
                    break;
                }
            }

            if st.depth == 0 && branches > 1 {
                let mut sum = Spectrum::ZERO;
                for b in 0..branches {
                    let mut branch = sampler.branch(b, branches);
                    let (direct, next) = self.vertex(scene, &si, st, &mut branch);
                    sum += direct;
                    if let Some(next) = next {
                        sum += self.walk(scene, next, &mut branch, 1);
                    }
                }
                return result + sum / branches as f32;
            }
            let (direct, next) = self.vertex(scene, &si, st, sampler);
            result += direct;
            match next {
                Some(next) => st = next,
                None => break,
            }
        }
        result
    }

    /// One surface vertex: the light arriving there by next-event estimation (weighted by the
    /// throughput so far), and the path state after sampling the BSDF and Russian roulette
    /// (`None`: the path ends).
    #[inline(always)]
    fn vertex(&self, scene: &Scene, si: &SurfaceInteraction, mut st: PathState, sampler: &mut PixelSampler) -> (Spectrum, Option<PathState>) {
        let bsdf = scene.bsdf(si);
        let sp = ShadingPoint::new(si);
        let wo = si.to_local(si.wo);

        // Six numbers per vertex, drawn in a fixed order so that with Sobol points each pair
        // is a well-stratified 2-D projection: light (2-D), BSDF direction (2-D), lobe
        // choice, Russian roulette (drawn even when unused, to keep the layout fixed).
        let u_light = sampler.next_2d();
        let u2 = sampler.next_2d();
        let u1 = sampler.next_1d();
        let u_rr = sampler.next_1d();

        // next-event estimation
        let mut direct = Spectrum::ZERO;
        if bsdf.has_smooth_lobe() {
            if let Some(es) = scene.sample_emitter_direction(si.p, u_light) {
                let wi = si.to_local(es.wi);
                let f = bsdf.eval(&sp, wo, wi) * wi.z.abs();
                if f != Spectrum::ZERO && scene.unoccluded(si.p, si.n, &es) {
                    let w = match es.support {
                        Support::Delta => 1.0,
                        Support::Extended => power_heuristic(es.pdf, bsdf.pdf(&sp, wo, wi)),
                    };
                    direct = st.beta * f * es.weight * w;
                }
            }
        }

        // continue the path by sampling the BSDF
        let Some(bs) = bsdf.sample(&sp, wo, u1, u2) else { return (direct, None) };
        st.beta *= bs.weight;
        st.eta *= bs.eta;
        st.prev_p = si.p;
        st.prev_pdf = bs.pdf;
        st.prev_lobe = bs.lobe;
        st.ray = si.spawn_ray(si.to_world(bs.wi).normalize());
        st.depth += 1;

        let beta_max = st.beta.max_element();
        if !is_positive(beta_max) {
            return (direct, None);
        }
        if st.depth >= self.rr_depth {
            let q = (beta_max * st.eta * st.eta).min(0.95);
            if u_rr >= q {
                return (direct, None);
            }
            st.beta /= q;
        }
        (direct, Some(st))
    }
}
