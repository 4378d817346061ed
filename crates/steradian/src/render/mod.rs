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

mod block;
mod driver;
mod measure;
mod merge;
mod options;
mod particles;
mod schedule;

pub use block::MAX_AOV_LAYERS;
pub use driver::render;
pub use measure::{measure, Measurement};
pub use options::{PixelQuantity, Progress, RenderError, RenderOptions, RenderOutput};

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
}
