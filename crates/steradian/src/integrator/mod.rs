//! Integrators: estimators of the radiance arriving along a camera ray (and of the irradiance
//! at a surface point), over a [`Scene`]. The render driver (`crate::render`) turns them into
//! images.

mod alpha;
mod aov;
mod branching;
mod depth;
mod direct;
mod irradiance;
mod mis;
mod moment;
mod path;
mod ptracer;
mod volpath;

pub use alpha::{camera_ray_alpha, AlphaRule};
pub use aov::{AovField, AovIntegrator};
pub use branching::{pilot, Pilot, CAMERA_SAMPLE_COST, MAX_AUTO_BRANCHES};
pub use depth::DepthIntegrator;
pub use direct::DirectIntegrator;
pub use irradiance::estimate_irradiance;
pub use moment::MomentIntegrator;
pub use path::{
    parse_branches, parse_max_depth, parse_rr_scale, Branches, EmitterVisibility, LastVertex,
    NextEvent, NullPaths, PathTracer, DEFAULT_BRANCHES, DEFAULT_MAX_DEPTH, DEFAULT_RR_DEPTH,
    DEFAULT_RR_SCALE, MAX_BRANCHES,
};
pub use ptracer::ParticleTracer;
pub use volpath::VolPathTracer;

use crate::emitter::LightSelection;
use crate::geometry::Ray;
use crate::sampling::PixelSampler;
use crate::scene::{MediaAlong, Scene};
use crate::Spectrum;

/// The light transport algorithms. Closed enum: one variant per integrator plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Integrator {
    Path(PathTracer),
    /// `volpath` and `volpathmis`: path tracing through participating media.
    VolPath(VolPathTracer),
    Direct(DirectIntegrator),
    Depth(DepthIntegrator),
    Moment(MomentIntegrator),
    Aov(AovIntegrator),
    /// `ptracer`: rendered by the render driver's particle passes, not through `li`.
    ParticleTracer(ParticleTracer),
}

impl Integrator {
    /// How next-event estimation chooses among lights.
    pub fn light_selection(&self) -> LightSelection {
        match self {
            Integrator::Path(p) => p.light_selection,
            Integrator::VolPath(p) => p.light_selection,
            Integrator::Direct(d) => d.light_selection,
            Integrator::Depth(_) | Integrator::ParticleTracer(_) => LightSelection::default(),
            Integrator::Moment(MomentIntegrator { nested })
            | Integrator::Aov(AovIntegrator { nested, .. }) => {
                nested.first().map_or(LightSelection::default(), |(_, i)| i.light_selection())
            }
        }
    }

    /// An unbiased estimate of the radiance L (W/(m²·sr)) arriving at the ray's origin from
    /// direction −ray.d (`moment`: its first integrator's, without the AOVs).
    #[inline]
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut PixelSampler) -> Spectrum {
        match self {
            Integrator::Path(i) => i.li(scene, ray, sampler),
            Integrator::VolPath(i) => i.li(scene, ray, sampler),
            Integrator::Direct(i) => i.li(scene, ray, sampler),
            Integrator::Depth(i) => i.li(scene, ray),
            // camera rays carry nothing in particle tracing (the render plan never asks)
            Integrator::ParticleTracer(_) => Spectrum::ZERO,
            Integrator::Moment(MomentIntegrator { nested })
            | Integrator::Aov(AovIntegrator { nested, .. }) => {
                nested.first().map_or(Spectrum::ZERO, |(_, i)| i.li(scene, ray, sampler))
            }
        }
    }

    /// Whether its estimates are light (radiance): false for `depth`, whose values are
    /// distances, so meters and irradiance maps refuse it.
    pub fn estimates_light(&self) -> bool {
        match self {
            Integrator::Depth(_) => false,
            Integrator::Moment(MomentIntegrator { nested })
            | Integrator::Aov(AovIntegrator { nested, .. }) => {
                nested.first().is_some_and(|(_, i)| i.estimates_light())
            }
            _ => true,
        }
    }

    /// How its camera samples cover an `rgba` film (`alpha.rs`); `None` for `ptracer`, whose
    /// image is not made of camera samples.
    pub fn alpha_rule(&self) -> Option<AlphaRule> {
        match self {
            Integrator::Path(p) => {
                Some(AlphaRule::Scattering { media: MediaAlong::Ignored, emitters: p.emitters })
            }
            Integrator::VolPath(p) => {
                Some(AlphaRule::Scattering { media: MediaAlong::Followed, emitters: p.emitters })
            }
            Integrator::Direct(d) => Some(AlphaRule::AnySurface { emitters: d.emitters }),
            Integrator::Depth(_) | Integrator::Aov(_) => {
                Some(AlphaRule::AnySurface { emitters: EmitterVisibility::Visible })
            }
            Integrator::Moment(MomentIntegrator { nested }) => {
                nested.first().and_then(|(_, i)| i.alpha_rule())
            }
            Integrator::ParticleTracer(_) => None,
        }
    }

    /// The AOV layers it writes beside the image (`moment`'s; none for the others).
    pub fn aov_layers(&self) -> Vec<crate::film::AovLayer> {
        match self {
            Integrator::Moment(m) => m.aov_layers(),
            Integrator::Aov(a) => a.aov_layers(),
            _ => Vec::new(),
        }
    }
}
