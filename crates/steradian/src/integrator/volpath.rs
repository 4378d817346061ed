//! `volpath` and `volpathmis`: path tracing through participating media.
//!
//! | parameter       | type    | default | meaning |
//! |-----------------|---------|---------|---------|
//! | `max_depth`     | integer | −1 (∞)  | longest path in scattering events (surface bounces and medium scatterings); 1 = emitters seen directly |
//! | `rr_depth`      | integer | 5       | depth from which Russian roulette may end paths |
//! | `hide_emitters` | boolean | false   | camera rays pass through the area lights they meet first (to what lies behind them) and see no environment or light through null surfaces and media, as in Mitsuba 3.9.1 |
//! | `light_selection` | string | `uniform` | steradian's own: `uniform` or `power` (see `emitter/light_selection.rs`) |
//!
//! **Estimator** (Mitsuba 3's `volpath`). A ray in a medium (`crate::medium`) first samples a
//! free flight: light scatters before the next surface, or reaches it, with the weight that
//! keeps every channel unbiased. At a scattering event in a medium whose `sample_emitters` is
//! true, one light is sampled and weighted by the phase function and by the transmittance to
//! it; the phase function is sampled to continue; the two are combined by MIS with the power
//! heuristic. Surfaces are handled as `path` handles them, except that
//! - crossing a surface whose shape bounds media changes the medium (`exterior` on the side of
//!   the geometric normal, `interior` behind it);
//! - a null crossing (the `null` BSDF, a `mask`'s transparent part) is not a scattering event:
//!   it does not count towards `max_depth` and MIS at the next emitter hit still uses the last
//!   real scattering vertex;
//! - shadow rays pass null surfaces, weighted by their null transmission, and media, weighted by
//!   their transmittance (`Scene::transmittance`); `path`'s stop at every surface.
//!
//! Russian roulette past `rr_depth` keeps a path with probability min(max(β)·η², 0.95), as in
//! Mitsuba. Depths follow Mitsuba: camera rays start at 0; each surface bounce and each medium
//! scattering adds one; emitters are seen while the depth is below `max_depth`, lights are
//! sampled from a vertex only while depth + 1 is.
//!
//! **Where steradian differs on purpose.** `volpath` and `volpathmis` are one estimator: free
//! flights are drawn in a channel chosen once per path, and the path is weighted by the
//! balance heuristic over the three channels' path densities (`volpathmis`'s spectral MIS,
//! `crate::medium`), where Mitsuba's `volpath` divides by the chosen channel's density alone.
//! Both are unbiased, so the images agree in expectation; the MIS weights stay bounded where a
//! single channel's blow up. Mitsuba's `volpathmis` combines light and phase/BSDF samples by
//! the balance heuristic, steradian by the power heuristic (as `volpath`): the same
//! expectation. A shape's `<medium>` must be named `interior` or `exterior` (Mitsuba ignores
//! other names silently); all sensors share one medium. A sensor's medium that no shape
//! bounds (no shape has it as `interior`) fills all space, and no light from infinity
//! (environment, sun, directional light) crosses it: steradian renders that light black and
//! warns at load, where Mitsuba 3.9.1 lets it in (a camera in such a fog under a uniform sky:
//! image mean 0.145, more than the 0.065 of the same fog bounded by a null sphere of 20 m;
//! `tests/volpath.rs`).
//!
//! Measured (`benches/render_vs_mitsuba.py`, 1024 spp, against Mitsuba 3.9.1 `llvm_ad_rgb`,
//! time to relMSE 10⁻³; 2026-12-06, Intel Xeon, 2 cores; `benches/results/`):
//! `volpath-sphere` (homogeneous, grey) 2.52× faster, `volpathmis-chromatic` 2.13×,
//! `volpath-cloud` (heterogeneous, delta tracking) 0.98×.

use glam::Vec3;

use super::mis::power_heuristic;
use super::path::EmitterVisibility;
use crate::bsdf::{Lobe, ShadingPoint};
use crate::emitter::{LightSelection, Support};
use crate::geometry::{is_positive, Ray};
use crate::medium::{FlightWeight, FreeFlight};
use crate::sampling::PixelSampler;
use crate::scene::{MediaAlong, Scene};
use crate::Spectrum;

/// The `volpath` (and `volpathmis`) integrator.
#[derive(Clone, Debug, PartialEq)]
pub struct VolPathTracer {
    /// Maximum number of scattering events; `None` = unbounded.
    pub max_depth: Option<u32>,
    pub rr_depth: u32,
    pub emitters: EmitterVisibility,
    pub light_selection: LightSelection,
}

impl Default for VolPathTracer {
    fn default() -> Self {
        VolPathTracer {
            max_depth: super::DEFAULT_MAX_DEPTH,
            rr_depth: super::DEFAULT_RR_DEPTH,
            emitters: EmitterVisibility::default(),
            light_selection: LightSelection::default(),
        }
    }
}

/// How the light found by hitting an emitter is weighted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum LastScatter {
    /// Nothing but delta scattering (or media that do not sample lights) since the camera:
    /// no light sample could have found the emitter, so it takes full weight.
    Unsampled,
    /// The last real scattering vertex at `p` sampled the direction with density `pdf`
    /// (1/sr), and sampled a light too: MIS against the light sample from `p`.
    Sampled { p: Vec3, pdf: f32 },
}

impl VolPathTracer {
    /// Radiance arriving along `camera_ray` (W/(m²·sr)), which starts in the scene's camera
    /// medium.
    pub fn li(&self, scene: &Scene, camera_ray: &Ray, sampler: &mut PixelSampler) -> Spectrum {
        let ray = self.emitters.camera_ray(scene, camera_ray);
        self.li_from(scene, &ray, scene.camera_medium, LastScatter::Unsampled, sampler)
    }

    /// Radiance arriving along `ray`, which starts in `medium` at depth 0, chosen by a
    /// strategy described by `last` (a meter's cosine-weighted direction, MIS against its
    /// light sample).
    pub(super) fn li_from(
        &self,
        scene: &Scene,
        ray: &Ray,
        medium: Option<u32>,
        last: LastScatter,
        sampler: &mut PixelSampler,
    ) -> Spectrum {
        let max_depth = self.max_depth.unwrap_or(u32::MAX);
        let mut result = Spectrum::ZERO;
        // the throughput is beta / mean(ratio): spectral MIS over the channels in which free
        // flights could have been drawn (`crate::medium`), `ratio` the path's density in each
        // channel over a common scale; free flights are drawn in `channel`, chosen once
        let mut beta = Spectrum::ONE;
        let mut ratio = Spectrum::ONE;
        let channel = match scene.media.is_empty() {
            true => 0,
            false => ((sampler.next_1d() * 3.0) as usize).min(2),
        };
        let mut eta = 1.0f32;
        let mut depth = 0u32;
        let mut ray = *ray;
        let mut medium = medium;
        let mut last = last;

        while depth < max_depth {
            let hit = scene.intersect(&ray);
            if let Some(m) = medium {
                let medium_ref = &scene.media[m as usize];
                let t_max = hit.as_ref().map_or(f32::INFINITY, |si| si.t);
                match medium_ref.sample_free_flight(&ray, t_max, channel, sampler) {
                    FreeFlight::Pass { weight } => {
                        if !apply(&mut beta, &mut ratio, weight) {
                            break;
                        }
                    }
                    FreeFlight::Scatter { t, weight } => {
                        if !apply(&mut beta, &mut ratio, weight) {
                            break;
                        }
                        depth += 1;
                        if depth >= max_depth {
                            break;
                        }
                        let p = ray.at(t);
                        let wo = -ray.d;
                        let phase = medium_ref.phase();
                        let u_light = sampler.next_2d();
                        let u1 = sampler.next_1d();
                        let u_rr = sampler.next_1d();
                        let u2 = sampler.next_2d();
                        let sample_emitters = medium_ref.sample_emitters();
                        if sample_emitters {
                            let light = next_event(
                                scene,
                                (p, Vec3::ZERO),
                                u_light,
                                sampler,
                                |_| medium,
                                |wi| Spectrum::splat(phase.eval(wo, wi)),
                                |wi| phase.pdf(wo, wi),
                            );
                            result += throughput(beta, ratio) * light;
                        }
                        let ps = phase.sample(wo, u1, u2);
                        if !is_positive(ps.pdf) {
                            break;
                        }
                        beta *= ps.weight;
                        last = match sample_emitters {
                            true => LastScatter::Sampled { p, pdf: ps.pdf },
                            false => LastScatter::Unsampled,
                        };
                        ray = Ray::infinite(p, ps.wi);
                        if !self.roulette(&mut beta, ratio, eta, depth, u_rr) {
                            break;
                        }
                        continue;
                    }
                }
            }

            let show = depth > 0 || self.emitters == EmitterVisibility::Visible;
            let Some(si) = hit else {
                if show && scene.has_light_at_infinity() {
                    result += throughput(beta, ratio)
                        * scene.escaped_radiance(ray.d, |light_pdf| match last {
                            LastScatter::Unsampled => 1.0,
                            LastScatter::Sampled { pdf, .. } => power_heuristic(pdf, light_pdf),
                        });
                }
                break;
            };

            if let (Some((e, emitter)), true) = (scene.area_emitter(&si), show) {
                let le = emitter.radiance(si.wo, si.sh_frame.n, si.uv);
                if le != Spectrum::ZERO {
                    let w = match last {
                        LastScatter::Unsampled => 1.0,
                        LastScatter::Sampled { p, pdf } => power_heuristic(
                            pdf,
                            scene.pdf_emitter_direction(e, p, ray.d, &si.surface_point()),
                        ),
                    };
                    result += throughput(beta, ratio) * le * w;
                }
            }

            let bsdf = scene.bsdf(&si);
            let sp = ShadingPoint::new(&si);
            let wo = si.to_local(si.wo);
            let u_light = sampler.next_2d();
            let u1 = sampler.next_1d();
            let u_rr = sampler.next_1d();
            let u2 = sampler.next_2d();

            let sample_lights = bsdf.has_smooth_lobe() && depth + 1 < max_depth;
            if sample_lights {
                let light = next_event(
                    scene,
                    (si.p, si.n),
                    u_light,
                    sampler,
                    |wi| scene.medium_after(&si, wi, medium),
                    |wi| {
                        let wi = si.to_local(wi);
                        bsdf.eval(&sp, wo, wi) * wi.z.abs()
                    },
                    |wi| bsdf.pdf(&sp, wo, si.to_local(wi)),
                );
                result += throughput(beta, ratio) * light;
            }

            let Some(bs) = bsdf.sample(&sp, wo, u1, u2) else { break };
            beta *= bs.weight;
            eta *= bs.eta;
            let wi = si.to_world(bs.wi);
            ray = si.spawn_ray(wi);
            medium = scene.medium_after(&si, wi, medium);
            match bs.lobe {
                // not a scattering event: depth and the MIS vertex stay
                Lobe::Null => continue,
                Lobe::Delta => last = LastScatter::Unsampled,
                Lobe::Smooth => last = LastScatter::Sampled { p: si.p, pdf: bs.pdf },
            }
            depth += 1;
            if !self.roulette(&mut beta, ratio, eta, depth, u_rr) {
                break;
            }
        }
        result
    }

    /// Russian roulette after a scattering event that brought the path to `depth`: whether
    /// the path goes on (its throughput divided by the survival probability).
    #[inline]
    fn roulette(
        &self,
        beta: &mut Spectrum,
        ratio: Spectrum,
        eta: f32,
        depth: u32,
        u_rr: f32,
    ) -> bool {
        let beta_max = throughput(*beta, ratio).max_element();
        if !is_positive(beta_max) {
            return false;
        }
        if depth > self.rr_depth {
            let q = (beta_max * eta * eta).min(0.95);
            if u_rr >= q {
                return false;
            }
            *beta /= q;
        }
        true
    }
}

/// The path throughput beta / mean(ratio) (see [`VolPathTracer::li_from`]).
#[inline(always)]
fn throughput(beta: Spectrum, ratio: Spectrum) -> Spectrum {
    beta * (3.0 / ratio.element_sum())
}

/// Multiplies a free flight's weight into the path's (beta, ratio), rescaled so that the
/// largest ratio is 1; false where no channel could have drawn the path (it ends).
#[inline(always)]
fn apply(beta: &mut Spectrum, ratio: &mut Spectrum, w: FlightWeight) -> bool {
    *beta *= w.f;
    *ratio *= w.pdf;
    let top = ratio.max_element();
    if !(top > 0.0 && top.is_finite()) {
        return false;
    }
    if top != 1.0 {
        *beta /= top;
        *ratio /= top;
    }
    true
}

/// Next-event estimation at a vertex `(p, n)` (`n` the surface's geometric normal, zero for a
/// point in a medium): one light sampled, its light weighted by `scatter(wi)` (the phase
/// function, or the BSDF times the cosine), by the transmittance to the light through
/// `medium_towards(wi)` and whatever it crosses, and by MIS with the power heuristic against
/// `pdf(wi)`, the vertex's own sampling density (not used for delta lights).
#[inline(always)]
fn next_event(
    scene: &Scene,
    (p, n): (Vec3, Vec3),
    u_light: glam::Vec2,
    sampler: &mut PixelSampler,
    medium_towards: impl Fn(Vec3) -> Option<u32>,
    scatter: impl Fn(Vec3) -> Spectrum,
    pdf: impl Fn(Vec3) -> f32,
) -> Spectrum {
    let Some(es) = scene.sample_emitter_direction(p, u_light) else { return Spectrum::ZERO };
    let f = scatter(es.wi);
    if f == Spectrum::ZERO {
        return Spectrum::ZERO;
    }
    let along = MediaAlong::Followed;
    let tr = scene.transmittance(p, n, es.wi, es.dist, medium_towards(es.wi), along, sampler);
    if tr == Spectrum::ZERO {
        return Spectrum::ZERO;
    }
    let w = match es.support {
        Support::Delta => 1.0,
        Support::Extended => power_heuristic(es.pdf, pdf(es.wi)),
    };
    f * tr * es.weight * w
}
