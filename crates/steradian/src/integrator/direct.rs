//! `direct`: direct illumination only (one bounce from the camera).
//!
//! | parameter         | type    | default        | meaning |
//! |-------------------|---------|----------------|---------|
//! | `shading_samples` | integer | 1              | sets both counts below at once |
//! | `emitter_samples` | integer | shading_samples| light samples per camera ray |
//! | `bsdf_samples`    | integer | shading_samples| BSDF samples per camera ray |
//! | `hide_emitters`   | boolean | false          | camera rays pass through the area lights they meet (to what lies behind them) and see no environment, as in Mitsuba 3.9.1 |
//! | `light_selection` | string | `uniform`     | steradian's own: `uniform` or `power` (see `emitter/light_selection.rs`) |
//!
//! Light samples and BSDF samples are combined with the power heuristic, each strategy weighted
//! by its sample count, as Mitsuba 3's `direct` does.
//!
//! **Where steradian differs on purpose.** Mitsuba 3.9.1 weighs a light sample of a delta light
//! (point, spot, directional, projector) by 1 instead of 1/`emitter_samples`, so with
//! `emitter_samples` = n those lights shine n times too bright (a directional light over a
//! principled floor at n = 2: Mitsuba's image mean twice steradian's, which equals the image
//! at n = 1). steradian divides every light sample by n (`tests/direct.rs`).

use super::mis::power_heuristic;
use super::path::EmitterVisibility;
use crate::bsdf::{Lobe, ShadingPoint};
use crate::emitter::LightSelection;
use crate::emitter::Support;
use crate::geometry::Ray;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct DirectIntegrator {
    pub emitter_samples: u32,
    pub bsdf_samples: u32,
    pub emitters: EmitterVisibility,
    pub light_selection: LightSelection,
}

impl Default for DirectIntegrator {
    fn default() -> Self {
        DirectIntegrator {
            emitter_samples: Self::DEFAULT_SHADING_SAMPLES,
            bsdf_samples: Self::DEFAULT_SHADING_SAMPLES,
            emitters: EmitterVisibility::default(),
            light_selection: LightSelection::default(),
        }
    }
}

impl DirectIntegrator {
    /// Default `shading_samples` (Mitsuba's), which `emitter_samples` and `bsdf_samples`
    /// default to.
    pub const DEFAULT_SHADING_SAMPLES: u32 = 1;

    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut PixelSampler) -> Spectrum {
        let show = self.emitters == EmitterVisibility::Visible;
        let ray = &self.emitters.camera_ray(scene, ray);
        let Some(si) = scene.intersect(ray) else {
            return match show {
                true => scene.escaped_radiance(ray.d, |_| 1.0),
                false => Spectrum::ZERO,
            };
        };
        let mut result = Spectrum::ZERO;
        if let (Some((_, emitter)), true) = (scene.area_emitter(&si), show) {
            result += emitter.radiance(si.wo, si.sh_frame.n, si.uv);
        }
        let bsdf = scene.bsdf(&si);
        let sp = ShadingPoint::new(&si);
        let wo = si.to_local(si.wo);
        let (ne, nb) = (self.emitter_samples as f32, self.bsdf_samples as f32);

        if bsdf.has_smooth_lobe() {
            for _ in 0..self.emitter_samples {
                let Some(es) = scene.sample_emitter_direction(si.p, sampler.next_2d()) else {
                    continue;
                };
                let wi = si.to_local(es.wi);
                let f = bsdf.eval(&sp, wo, wi) * wi.z.abs();
                if f == Spectrum::ZERO || !scene.unoccluded(si.p, si.n, &es) {
                    continue;
                }
                let w = match es.support {
                    Support::Delta => 1.0,
                    Support::Extended if nb > 0.0 => {
                        power_heuristic(es.pdf * ne, bsdf.pdf(&sp, wo, wi) * nb)
                    }
                    Support::Extended => 1.0,
                };
                result += f * es.weight * (w / ne);
            }
        }

        for _ in 0..self.bsdf_samples {
            let u2 = sampler.next_2d();
            let Some(bs) = bsdf.sample(&sp, wo, sampler.next_1d(), u2) else { continue };
            let d = si.to_world(bs.wi).normalize();
            let next = si.spawn_ray(d);
            let mis = |light_pdf: f32| match bs.lobe {
                Lobe::Delta | Lobe::Null => 1.0,
                Lobe::Smooth if ne > 0.0 && bsdf.has_smooth_lobe() => {
                    power_heuristic(bs.pdf * nb, light_pdf * ne)
                }
                Lobe::Smooth => 1.0,
            };
            let le = match scene.intersect(&next) {
                Some(hit) => match scene.area_emitter(&hit) {
                    Some((e, emitter)) => {
                        let le = emitter.radiance(hit.wo, hit.sh_frame.n, hit.uv);
                        if le == Spectrum::ZERO {
                            continue;
                        }
                        let light = hit.surface_point();
                        le * mis(scene.pdf_emitter_direction(e, si.p, d, &light))
                    }
                    None => continue,
                },
                // the environment and the sun, each with its own density
                None => scene.escaped_radiance(d, mis),
            };
            result += bs.weight * le * (1.0 / nb);
        }
        result
    }
}
