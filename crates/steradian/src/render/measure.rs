//! A sensor's reading with its standard error: what `steradian measure` prints and what the
//! Python `Scene.measure` returns.
//!
//! A meter (radiancemeter, irradiancemeter) has a one-pixel film, so its reading is that
//! pixel. For a camera the reading is the image mean: the mean radiance (W/(m²·sr)) over the
//! film, and its standard error combines the pixels' errors as independent estimates,
//! σ_mean = √(Σ σ_p²) / N for N pixels.

use super::{render, Job, RenderError, RenderOptions, RenderOutput};
use crate::sensor::Quantity;

/// One sensor reading.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// Index of the sensor read.
    pub sensor: usize,
    /// What was measured: radiance (W/(m²·sr)) or irradiance (W/m²).
    pub quantity: Quantity,
    /// The estimate per RGB channel, in the unit of `quantity`.
    pub value: [f64; 3],
    /// Standard error of `value` per channel, same unit.
    pub stderr: [f64; 3],
    /// Samples per pixel actually taken (fewer than requested when interrupted).
    pub spp: u32,
    pub spp_requested: u32,
    /// NaN/Inf samples dropped.
    pub dropped_samples: u64,
    pub interrupted: bool,
    /// The measurement stopped because it reached `RenderOptions::target_error`.
    pub target_reached: bool,
    /// Paths continued from each sample's first hit (`path`'s branches, chosen by its pilot
    /// when the scene leaves them unset); `None` for other integrators.
    pub branches: Option<u32>,
}

/// Reads sensor `opts.sensor` (the first when `None`): renders it with `opts` and reduces the
/// film to one value per channel with its standard error.
pub fn measure(job: &Job, opts: &RenderOptions) -> Result<Measurement, RenderError> {
    let sensor = opts.sensor.unwrap_or(0);
    let out = render(job, opts)?;
    // `render` has checked the index
    let quantity = job.scene.sensors[sensor].quantity();
    Ok(Measurement::from_render(&out, sensor, quantity))
}

impl Measurement {
    /// The image mean of a finished render and the standard error of that mean.
    pub fn from_render(out: &RenderOutput, sensor: usize, quantity: Quantity) -> Measurement {
        let (value, error) = (out.film().develop(), out.film().develop_stderr());
        let n = value.pixel_count().max(1) as f64;
        let mut var = [0.0f64; 3];
        for e in error.data.chunks_exact(3) {
            for c in 0..3 {
                var[c] += (e[c] as f64).powi(2);
            }
        }
        Measurement {
            sensor,
            quantity,
            value: value.channel_means(),
            stderr: var.map(|v| v.sqrt() / n),
            spp: out.spp,
            spp_requested: out.spp_requested,
            dropped_samples: out.dropped_samples,
            interrupted: out.interrupted,
            target_reached: out.target_reached,
            branches: out.branches,
        }
    }

    /// The unit of the reading.
    pub fn unit(&self) -> &'static str {
        self.quantity.unit()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::{BoxFilter, Film, ReconstructionFilter};
    use glam::{UVec2, Vec2};
    use std::time::Duration;

    /// The reduction by hand on a 2×1 film with known samples per pixel.
    #[test]
    fn image_mean_and_its_standard_error() {
        let mut film = Film::new(2, 1, ReconstructionFilter::Box(BoxFilter)).unwrap();
        let mut block = film.create_block(UVec2::ZERO, UVec2::new(2, 1));
        // pixel 0: samples 1, 3 (mean 2, sample variance 2, stderr 1); pixel 1: 5, 5, 5, 5
        // (mean 5, stderr 0)
        for v in [1.0f32, 3.0] {
            block.put(Vec2::new(0.5, 0.5), crate::Spectrum::splat(v));
        }
        for _ in 0..4 {
            block.put(Vec2::new(1.5, 0.5), crate::Spectrum::splat(5.0));
        }
        film.merge(&block);
        let header = crate::render::SumsHeader {
            width: 2,
            height: 1,
            aov_layers: 0,
            spp: 2,
            seed: 0,
            sampler: crate::sampling::SamplerKind::Independent,
            branches: 3,
            quantity: crate::render::PixelQuantity::Sensor,
            sensor: 0,
            scene_digest: 0,
            allocation: 0,
        };
        let mut sums = crate::render::RenderSums::empty(header, &film, 0);
        sums.push_pass(2, film);
        let out = RenderOutput {
            sums,
            quantity: crate::render::PixelQuantity::Sensor,
            branches: Some(3),
            pilot: None,
            spp: 2,
            spp_requested: 2,
            spp_rendered: 2,
            dropped_samples: 0,
            elapsed: Duration::ZERO,
            interrupted: false,
            time_limited: false,
            target_reached: false,
            film_samples: 4,
            rendered_samples: 4,
            rays: 0,
            adaptive: None,
        };
        let m = Measurement::from_render(&out, 0, Quantity::Radiance);
        let se = out.film().develop_stderr();
        for c in 0..3 {
            assert!((m.value[c] - 3.5).abs() < 1e-6, "{:?}", m.value);
            let want = ((se.data[c] as f64).powi(2) + (se.data[3 + c] as f64).powi(2)).sqrt() / 2.0;
            assert!(
                (m.stderr[c] - want).abs() <= 1e-12 * want.max(1.0),
                "{:?} vs {want}",
                m.stderr
            );
            assert!(m.stderr[c] > 0.0);
        }
        assert_eq!(m.unit(), "W/(m²·sr)");
        assert_eq!(m.branches, Some(3));
    }
}
