//! One work item rendered into an image block: every sample of its pixels and sample range,
//! estimated by the integrator and splatted through the film's reconstruction filter.
//! Samples whose value is NaN or infinite are dropped and counted, never splatted.

use glam::{IVec2, UVec2, Vec2};

use super::densities::Densities;
use super::options::Plan;
use super::quantity::PixelQuantity;
use super::schedule::WorkItem;
use crate::film::{FilmWindow, ImageBlock, ReconstructionFilter};
use crate::integrator::{camera_ray_alpha, estimate_irradiance, AlphaRule, Integrator};
use crate::sampling::{mix64, PixelSampler, Sampler, SamplerKind};
use crate::scene::{rays_traced_on_this_thread, Scene};
use crate::sensor::{film_position, film_position_signed, Sensor, SensorKind};
use crate::Spectrum;

/// Renders work items of one plan; shared by all worker threads.
pub(super) struct BlockRenderer<'a> {
    pub scene: &'a Scene,
    /// The integrator with its branch count resolved.
    pub integrator: &'a Integrator,
    pub sensor: &'a Sensor,
    pub sampler: Sampler,
    pub quantity: PixelQuantity,
    pub meter: bool,
    /// Sobol points per sample (meters; 1 = one point from `sampler`).
    pub batch: u32,
    pub filter: ReconstructionFilter,
    pub width: u32,
    pub height: u32,
    /// Where the film lies in the camera's frame (a crop window, or all of it).
    pub window: FilmWindow,
    /// Pixels sampled beyond each edge of the film (`film::SampleBorder`; 0 for meters).
    pub margin: u32,
    /// AOV layers of the film (`moment`'s, the alpha channel's), 0 for most renders.
    pub aov_layers: usize,
    /// How camera samples fill the alpha channel, the last AOV layer (`rgba` films).
    pub alpha: Option<AlphaRule>,
    /// An adaptive render's per-pixel sample counts and weights (`adaptive.rs`); `None`:
    /// every pixel takes the item's samples with weight 1.
    pub densities: Option<&'a Densities>,
}

/// The most AOV layers a sample carries (`moment` with 8 nested integrators, `aov` with 16
/// layers in all); the loader refuses more, and so does the render plan.
pub const MAX_AOV_LAYERS: usize = 16;

/// A rendered work item.
pub(super) struct RenderedBlock {
    /// The sums, with the count of samples dropped for a NaN or infinite value.
    pub block: ImageBlock,
    /// Samples taken, all pixels.
    pub samples: u64,
    /// Ray queries made for them.
    pub rays: u64,
}

impl<'a> BlockRenderer<'a> {
    pub fn new(scene: &'a Scene, integrator: &'a Integrator, plan: &Plan<'a>) -> Self {
        BlockRenderer {
            scene,
            integrator,
            sensor: plan.sensor,
            sampler: plan.sampler,
            quantity: plan.quantity,
            meter: plan.meter,
            batch: plan.batch,
            filter: plan.film.filter,
            width: plan.film.width,
            height: plan.film.height,
            window: plan.film.window(),
            margin: if plan.meter { 0 } else { plan.film.sample_margin() },
            aov_layers: plan.film.aov_layers().len(),
            alpha: if plan.film.has_alpha_layer() { integrator.alpha_rule() } else { None },
            densities: None,
        }
    }

    /// The item's block, or `None` when `cancelled` turns true before it is finished (checked
    /// once per pixel row).
    pub fn render(&self, item: &WorkItem, cancelled: impl Fn() -> bool) -> Option<RenderedBlock> {
        if self.aov_layers == 0 {
            return self.render_samples(item, cancelled, &mut [], |s, film_uv, _| {
                match self.quantity {
                    PixelQuantity::Sensor => self.sensor_value(film_uv, s),
                    PixelQuantity::SurfaceIrradiance | PixelQuantity::SurfaceIlluminance => {
                        self.surface_irradiance(film_uv, s)
                    }
                }
            });
        }
        // `moment`, `aov`, the alpha channel (the plan gives AOV layers to camera radiance
        // renders only)
        let mut aovs = [Spectrum::ZERO; MAX_AOV_LAYERS];
        let n = self.aov_layers;
        let alpha = self.alpha;
        self.render_samples(item, cancelled, &mut aovs[..n], |s, film_uv, aovs| {
            aovs.fill(Spectrum::ZERO);
            let Some(ray) = self.sensor.start_ray(film_uv, s) else { return Spectrum::ZERO };
            let (own, alpha_layer) = aovs.split_at_mut(n - usize::from(alpha.is_some()));
            let l = match self.integrator {
                Integrator::Moment(m) => m.li_aovs(self.scene, &ray, s, own),
                Integrator::Aov(a) => a.li_aovs(self.scene, &ray, s, own),
                other => other.li(self.scene, &ray, s),
            };
            // after the radiance, so that the image does not depend on the alpha channel
            if let (Some(rule), [a]) = (alpha, alpha_layer) {
                *a = Spectrum::splat(camera_ray_alpha(self.scene, &ray, rule, s));
            }
            l
        })
    }

    /// Every sample of the item: `estimate` gives a sample's value from its sampler and film
    /// position, and fills `aovs` (empty without AOV layers); samples with a non-finite value
    /// are dropped and counted.
    #[inline(always)]
    fn render_samples(
        &self,
        item: &WorkItem,
        cancelled: impl Fn() -> bool,
        aovs: &mut [Spectrum],
        mut estimate: impl FnMut(&mut PixelSampler, Vec2, &mut [Spectrum]) -> Spectrum,
    ) -> Option<RenderedBlock> {
        let WorkItem { offset, size, s0, s1 } = *item;
        let (width, height) = (self.width, self.height);
        // blocks as `Film::create_block` makes them (the film itself is borrowed for merging)
        let mut block =
            ImageBlock::with_clip(offset, size, &self.filter, [width as i64, height as i64])
                .with_aov_layers(self.aov_layers);
        let (mut dropped, mut samples) = (0u64, 0u64);
        // the block is rendered on this one thread
        let rays_before = rays_traced_on_this_thread();
        // tiles on the film's edges also take the margin beyond it (`sample_border`)
        let m = self.margin as i32;
        let span = |o: u32, n: u32, full: u32| {
            let (lo, hi) = (o as i32, (o + n) as i32);
            (if o == 0 { lo - m } else { lo }, if o + n == full { hi + m } else { hi })
        };
        let ((x0, x1), (y0, y1)) = (span(offset.x, size.x, width), span(offset.y, size.y, height));
        let film = IVec2::new(width as i32, height as i32);
        for y in y0..y1 {
            if cancelled() {
                return None;
            }
            for x in x0..x1 {
                let signed = IVec2::new(x, y);
                // a margin pixel samples as its nearest film pixel does
                let pixel = signed.clamp(IVec2::ZERO, film - 1).as_uvec2();
                let inside = signed == pixel.as_ivec2();
                // this pixel's samples of the item, and their weight
                let (first, end, scale) = match self.densities {
                    None => (s0, s1, 1.0),
                    Some(d) => {
                        let i = pixel.y as usize * width as usize + pixel.x as usize;
                        (d.count(i, s0), d.count(i, s1), d.weight(i))
                    }
                };
                samples += (end - first) as u64;
                for index in first..end {
                    let (mut s, (mut pos, film_uv)) = if inside {
                        let mut s = self.sampler.pixel_sampler(pixel, width, index);
                        let at = film_position(pixel, &mut s, &self.window);
                        (s, at)
                    } else {
                        // numbered after the film's pixels, row by row over film and margin
                        let row = (width + 2 * self.margin) as u64;
                        let id =
                            width as u64 * height as u64 + (y + m) as u64 * row + (x + m) as u64;
                        let mut s = self.sampler.pixel_sampler_of(id, index);
                        let at = film_position_signed(signed, &mut s, &self.window);
                        (s, at)
                    };
                    let l = match self.batch {
                        1 => estimate(&mut s, film_uv, aovs),
                        n => self.replicate(pixel, index, n, &mut estimate, aovs),
                    };
                    if self.meter {
                        // meters ignore the film position: equal weights
                        pos = pixel.as_vec2() + Vec2::splat(0.5);
                    }
                    if l.is_finite() && aovs.iter().all(|a| a.is_finite()) {
                        block.put_scaled(pos, l, aovs, scale);
                    } else {
                        dropped += 1;
                    }
                }
            }
        }
        block.add_dropped(dropped);
        let rays = rays_traced_on_this_thread() - rays_before;
        Some(RenderedBlock { block, samples, rays })
    }

    /// Sample `index` of a meter as a randomised quasi-Monte Carlo replicate: the mean of
    /// points 0..`n` of a Sobol sequence under a scramble of its own, drawn from the render's
    /// seed and the sample's index, so that replicates are independent of each other (the
    /// film's standard error stays that of independent samples) and each is a stratified set
    /// (on `scenes/lighting_room.xml`'s work plane, Sobol points spread 5.2× less than
    /// independent ones at 1024 per point: `benches/results/2026-12-06-intel-xeon.md`).
    #[inline]
    fn replicate(
        &self,
        pixel: UVec2,
        index: u32,
        n: u32,
        estimate: &mut impl FnMut(&mut PixelSampler, Vec2, &mut [Spectrum]) -> Spectrum,
        aovs: &mut [Spectrum],
    ) -> Spectrum {
        let scramble = Sampler {
            kind: SamplerKind::Sobol,
            seed: mix64(self.sampler.seed ^ mix64(index as u64 ^ 0x5eed_ba7c_4000_0000)),
            ..self.sampler
        };
        let mut sum = Spectrum::ZERO;
        for j in 0..n {
            let mut s = scramble.pixel_sampler(pixel, self.width, j);
            let (_, film_uv) = film_position(pixel, &mut s, &self.window);
            sum += estimate(&mut s, film_uv, aovs);
        }
        sum / n as f32
    }

    /// One sample of the sensor's measurement at film position `film_uv ∈ [0,1]²`: for cameras
    /// the radiance arriving along the ray through that position, for meters their quantity
    /// (film position plays no part).
    #[inline]
    fn sensor_value(&self, film_uv: Vec2, s: &mut PixelSampler) -> Spectrum {
        let scene = self.scene;
        match &self.sensor.kind {
            SensorKind::IrradianceMeter(m) => {
                let ps = scene.shapes[m.shape as usize].sample_position(s.next_2d());
                return estimate_irradiance(scene, self.integrator, ps.p, ps.n, s);
            }
            SensorKind::Workplane(w) => {
                let (p, n) = w.point(film_uv);
                return estimate_irradiance(scene, self.integrator, p, n, s);
            }
            _ => {}
        }
        match self.sensor.start_ray(film_uv, s) {
            Some(ray) => self.integrator.li(scene, &ray, s),
            None => Spectrum::ZERO,
        }
    }

    /// Irradiance on the surface seen through film position `film_uv`, on the camera's side.
    fn surface_irradiance(&self, film_uv: Vec2, s: &mut PixelSampler) -> Spectrum {
        let Some(ray) = self.sensor.camera_ray(film_uv, s) else { return Spectrum::ZERO };
        let Some(si) = self.scene.intersect(&ray) else { return Spectrum::ZERO };
        let n = if si.n.dot(ray.d) < 0.0 { si.n } else { -si.n };
        estimate_irradiance(self.scene, self.integrator, si.p, n, s)
    }
}
