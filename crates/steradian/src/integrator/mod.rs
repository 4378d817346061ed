//! Integrators: estimators of the radiance arriving along a camera ray, and the driver that
//! turns them into images.

mod branching;
mod direct;
mod irradiance;
mod light_selection;
mod measure;
mod mis;
mod path;
mod render;

pub use branching::{Pilot, CAMERA_SAMPLE_COST, MAX_AUTO_BRANCHES};
pub use direct::DirectIntegrator;
pub use irradiance::estimate_irradiance;
pub use light_selection::LightSelection;
pub use measure::{measure, Measurement};
pub use path::{
    parse_branches, parse_max_depth, parse_rr_scale, Branches, EmitterVisibility, LastVertex,
    PathTracer, DEFAULT_BRANCHES, DEFAULT_MAX_DEPTH, DEFAULT_RR_DEPTH, DEFAULT_RR_SCALE,
    MAX_BRANCHES,
};
pub use render::{render, PixelQuantity, Progress, RenderError, RenderOptions, RenderOutput};

use crate::geometry::Ray;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::Spectrum;

/// The light transport algorithms. Closed enum: one variant per integrator plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Integrator {
    Path(PathTracer),
    Direct(DirectIntegrator),
}

impl Integrator {
    /// How next-event estimation chooses among lights.
    pub fn light_selection(&self) -> LightSelection {
        match self {
            Integrator::Path(p) => p.light_selection,
            Integrator::Direct(d) => d.light_selection,
        }
    }

    /// An unbiased estimate of the radiance L (W/(m²·sr)) arriving at the ray's origin from
    /// direction −ray.d.
    #[inline]
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut PixelSampler) -> Spectrum {
        match self {
            Integrator::Path(i) => i.li(scene, ray, sampler),
            Integrator::Direct(i) => i.li(scene, ray, sampler),
        }
    }
}
