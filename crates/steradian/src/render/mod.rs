//! The render driver: turns a [`Job`] (a scene and its integrator) into a film, and a film into
//! readings with standard errors.
//!
//! A render is planned once ([`RenderOptions`] validated against the scene: `options.rs`),
//! organised in *passes* (`schedule.rs`): each pass adds the same number of samples to every
//! pixel, and the film only ever holds complete passes, so stopping early (Ctrl-C) still yields
//! an image with the same sample count everywhere. Work items (a tile and a range of its samples)
//! are rendered on all cores (`block.rs`) and merged into the film in a fixed order
//! (`merge.rs`); every sample's random numbers are addressed by (pixel, sample index, seed), so
//! the image is bit-for-bit the same for any thread count. `driver.rs` ties these together;
//! `measure.rs` reduces a film to one reading. The particle tracer renders whole-film passes of
//! light paths instead (`particles.rs`), with the same guarantees.
//!
//! A camera image's samples are spread over its pixels uniformly or, after a short pilot of
//! independent scrambles, adaptively where they lower the image's relative error most
//! (`adaptive.rs`, [`SampleAllocation`]; `Auto`, the default, decides from the pilot): the
//! pass structure stays, each pixel holding ⌈d · s⌉ samples at the pass bound s, d its
//! density (`densities.rs`).
//!
//! A render's result is its raw sums (`sums.rs`): each pass summed from zero, the passes folded
//! in order. A render may cover only a range of the passes ([`RenderOptions::range`]) or continue
//! sums from a checkpoint ([`RenderOptions::resume`]); ranges rendered anywhere and joined in
//! order ([`RenderSums::append`]) are the whole render bit for bit, which is what checkpoints
//! and distributed renders rest on. Splitting the passes this way costs a single-process render
//! one film-sized addition per pass (cornell at 256×256, 64 spp: within the noise of its render
//! time, `benches/results/2026-12-06-intel-xeon.md`).

mod adaptive;
mod block;
mod checkpoint;
mod densities;
mod driver;
mod grid_reading;
mod measure;
mod merge;
mod options;
mod particles;
mod quantity;
mod schedule;
mod sums;
mod target_error;

pub use adaptive::{
    pilot_spp as adaptive_pilot_spp, AdaptiveReport, ERROR_FLOOR as ADAPTIVE_ERROR_FLOOR,
    MAX_DENSITY, MIN_ADAPTIVE_GAIN, MIN_DENSITY, MIN_SPP_FOR_AUTO,
};
pub use block::MAX_AOV_LAYERS;
pub use checkpoint::Checkpoint;
pub use driver::{pass_bounds, plan, render, RenderPlan};
pub use grid_reading::{Estimate, GridReading, GridStats};
pub use measure::{measure, Measurement};
pub use options::{
    Progress, RenderError, RenderOptions, RenderOutput, SampleAllocation, MAX_BATCH,
};
pub use quantity::PixelQuantity;
pub use sums::{digest_inputs, RenderSums, SumsError, SumsHeader};
pub use target_error::{
    image_error, CONFIDENCE_Z, IMAGE_ERROR_FLOOR, IMAGE_PIXEL_QUANTILE, MAX_SPP_FOR_TARGET,
    MIN_SAMPLES_FOR_TARGET,
};

use crate::integrator::Integrator;
use crate::scene::Scene;

/// What a scene file describes: the scene, and the integrator that estimates its light.
#[derive(Debug)]
pub struct Job {
    pub scene: Scene,
    pub integrator: Integrator,
    /// What the scene's loader warned about, one located line each
    /// (`scene.xml:3:7: warning: …`): the scene renders as written; front ends print them.
    pub warnings: Vec<String>,
    /// The files the scene was read from (the scene file, its includes, meshes, images), in
    /// the order first read: what a distributed render ships, and what a checkpoint's scene
    /// digest covers. Empty for a scene built in code.
    pub inputs: Vec<std::path::PathBuf>,
}

impl Job {
    /// The AOV layers a radiance render of camera `sensor` keeps beside the image: the
    /// integrator's (`moment`, `aov`), then the alpha channel of an `rgba`-like film. Meters
    /// keep none.
    pub fn camera_layers(&self, sensor: &crate::sensor::Sensor) -> Vec<crate::film::AovLayer> {
        if sensor.is_meter() {
            return Vec::new();
        }
        let mut layers = self.integrator.aov_layers();
        if sensor.film.pixel_format.has_alpha() && self.integrator.alpha_rule().is_some() {
            layers.push(crate::film::AovLayer::alpha());
        }
        layers
    }
}
