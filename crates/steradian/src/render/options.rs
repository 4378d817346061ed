//! What a render is asked for ([`RenderOptions`]), what it returns ([`RenderOutput`]), and the
//! plan that checks the one against the scene before any work starts ([`Plan`]).

use std::fmt;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use super::Job;
use crate::film::{Film, Image};
use crate::integrator::Pilot;
use crate::sampling::{Sampler, SamplerKind};
use crate::sensor::Sensor;

/// How far a render has come.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Samples finished so far (all pixels).
    pub samples_done: u64,
    pub samples_total: u64,
    pub elapsed: Duration,
}

/// What each pixel holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelQuantity {
    /// What the sensor measures (radiance for cameras, the meter's quantity for meters).
    #[default]
    Sensor,
    /// The irradiance (W/m²) on the surface point each camera pixel sees, on the side facing
    /// the camera (0 where the ray escapes): an irradiance map.
    SurfaceIrradiance,
    /// The same as illuminance (lx): 683 lm/W × the luminance of the irradiance (see
    /// [`Image::to_illuminance`]).
    SurfaceIlluminance,
}

impl PixelQuantity {
    /// The names the command line and Python take, in order: `radiance` (what the sensor
    /// measures), `irradiance`, `illuminance`.
    pub const NAMES: [&'static str; 3] = ["radiance", "irradiance", "illuminance"];

    /// The quantity of one of [`PixelQuantity::NAMES`].
    pub fn from_name(name: &str) -> Option<PixelQuantity> {
        match name {
            "radiance" => Some(PixelQuantity::Sensor),
            "irradiance" => Some(PixelQuantity::SurfaceIrradiance),
            "illuminance" => Some(PixelQuantity::SurfaceIlluminance),
            _ => None,
        }
    }

    /// True for the maps of what a camera sees (irradiance, illuminance).
    pub fn is_surface_map(self) -> bool {
        self != PixelQuantity::Sensor
    }
}

/// Options of one render.
#[derive(Default)]
pub struct RenderOptions<'a> {
    /// Samples per pixel; `None` = the sensor's sampler's `sample_count`.
    pub spp: Option<u32>,
    /// Seed; `None` = the sensor's sampler's seed.
    pub seed: Option<u64>,
    /// Sample generator; `None` = Sobol points for cameras, i.i.d. numbers for meters (whose
    /// error bars assume independent samples).
    pub sampler: Option<SamplerKind>,
    /// Worker threads; `None` = all cores.
    pub threads: Option<usize>,
    /// Which sensor; `None` = the first.
    pub sensor: Option<usize>,
    /// Set to stop early; the passes finished so far are kept.
    pub cancel: Option<&'a AtomicBool>,
    /// What each pixel holds.
    pub quantity: PixelQuantity,
    /// Called from worker threads as tiles finish.
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
}

impl RenderOptions<'_> {
    /// Checks what can be checked without the scene (the command line does so before a slow
    /// scene load); [`render`](super::render) checks it again with the scene.
    pub fn validate(&self) -> Result<(), RenderError> {
        if self.spp == Some(0) {
            return Err(RenderError::BadOption { option: "spp", reason: "must be at least 1" });
        }
        if self.threads == Some(0) {
            return Err(RenderError::BadOption { option: "threads", reason: "must be at least 1" });
        }
        Ok(())
    }
}

/// The result of a render.
#[derive(Debug)]
pub struct RenderOutput {
    pub film: Film,
    /// What the film's pixels hold before [`RenderOutput::image`] converts them.
    pub quantity: PixelQuantity,
    /// Paths continued from each camera ray's first hit (`path` only).
    pub branches: Option<u32>,
    /// What the pilot that chose `branches` measured, when one ran.
    pub pilot: Option<Pilot>,
    /// Samples per pixel actually in the film.
    pub spp: u32,
    pub spp_requested: u32,
    /// Samples whose value was NaN or infinite: dropped, never splatted.
    pub dropped_samples: u64,
    pub elapsed: Duration,
    pub interrupted: bool,
}

impl RenderOutput {
    /// Samples in the film (pixels × spp).
    pub fn samples(&self) -> u64 {
        self.film.width as u64 * self.film.height as u64 * self.spp as u64
    }

    /// The image in the unit of the requested quantity (illuminance converted from the
    /// film's irradiance).
    pub fn image(&self) -> Image {
        self.in_quantity(self.film.develop())
    }

    /// The standard error of each pixel of [`RenderOutput::image`], same unit.
    pub fn stderr_image(&self) -> Image {
        self.in_quantity(self.film.develop_stderr())
    }

    /// The AOV layers the integrator wrote (`moment`'s), developed, each with its name and
    /// channel names.
    pub fn aov_images(&self) -> Vec<(crate::film::AovLayer, Image)> {
        let layers = self.film.aov_layers();
        layers.iter().enumerate().map(|(k, l)| (l.clone(), self.film.develop_aov(k))).collect()
    }

    fn in_quantity(&self, image: Image) -> Image {
        match self.quantity {
            PixelQuantity::SurfaceIlluminance => image.to_illuminance(),
            PixelQuantity::Sensor | PixelQuantity::SurfaceIrradiance => image,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum RenderError {
    NoSensor,
    BadSensor(usize),
    /// An irradiance map needs a camera.
    NotACamera,
    /// Meters and irradiance maps need an integrator that estimates light (not `depth`).
    NotLight,
    /// The particle tracer renders images through a pinhole (`perspective`) camera only.
    ParticlesNeedPinhole,
    /// An option out of its range: the option's name and what it must be.
    BadOption {
        option: &'static str,
        reason: &'static str,
    },
    ThreadPool(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::NoSensor => write!(f, "the scene has no sensor to render"),
            RenderError::BadSensor(i) => write!(f, "the scene has no sensor number {i}"),
            RenderError::NotACamera => write!(
                f,
                "irradiance maps need a camera sensor (perspective, thinlens or orthographic), not a meter"
            ),
            RenderError::NotLight => write!(
                f,
                "the depth integrator gives distances (m), not light: meters and irradiance maps need `path` or `direct`"
            ),
            RenderError::ParticlesNeedPinhole => write!(
                f,
                "the ptracer integrator renders images through a perspective camera only (no thinlens, orthographic, batch or meters, no irradiance maps): use `path` for those"
            ),
            RenderError::BadOption { option, reason } => write!(f, "{option} {reason}"),
            RenderError::ThreadPool(e) => write!(f, "could not start worker threads: {e}"),
        }
    }
}

impl std::error::Error for RenderError {}

/// A render's options checked against the scene and resolved: which sensor, with which
/// sampler (kind, spp, seed), on which film.
#[derive(Debug)]
pub(super) struct Plan<'a> {
    pub sensor: &'a Sensor,
    /// The sensor's sampler with the options' spp, seed and kind.
    pub sampler: Sampler,
    /// Samples per pixel asked for (≥ 1).
    pub spp: u32,
    /// The sensor is a meter: samples do not depend on the film position.
    pub meter: bool,
    /// The sensor's film, cleared.
    pub film: Film,
    pub quantity: PixelQuantity,
}

impl<'a> Plan<'a> {
    pub fn new(job: &'a Job, opts: &RenderOptions) -> Result<Plan<'a>, RenderError> {
        opts.validate()?;
        let sensors = &job.scene.sensors;
        if sensors.is_empty() {
            return Err(RenderError::NoSensor);
        }
        let index = opts.sensor.unwrap_or(0);
        let sensor = sensors.get(index).ok_or(RenderError::BadSensor(index))?;
        let meter = sensor.is_meter();
        if opts.quantity.is_surface_map() && meter {
            return Err(RenderError::NotACamera);
        }
        if (opts.quantity.is_surface_map() || meter) && !job.integrator.estimates_light() {
            return Err(RenderError::NotLight);
        }
        if matches!(job.integrator, crate::integrator::Integrator::ParticleTracer(_))
            && (opts.quantity.is_surface_map() || sensor.pinhole().is_none())
        {
            return Err(RenderError::ParticlesNeedPinhole);
        }
        let mut sampler = sensor.sampler;
        if let Some(spp) = opts.spp {
            sampler.sample_count = spp;
        }
        if let Some(seed) = opts.seed {
            sampler.seed = seed;
        }
        if sampler.sample_count == 0 {
            return Err(RenderError::BadOption { option: "spp", reason: "must be at least 1" });
        }
        sampler.kind =
            opts.sampler.unwrap_or(if meter { SamplerKind::Independent } else { sampler.kind });
        let mut film = sensor.film.clone();
        film.clear();
        if !meter && opts.quantity == PixelQuantity::Sensor {
            let layers = job.integrator.aov_layers();
            if layers.len() > super::MAX_AOV_LAYERS {
                return Err(RenderError::BadOption {
                    option: "integrator",
                    reason: "writes more AOV layers than a sample carries (16)",
                });
            }
            film = film.with_aov_layers(layers);
        }
        Ok(Plan {
            sensor,
            sampler,
            spp: sampler.sample_count,
            meter,
            film,
            quantity: opts.quantity,
        })
    }
}
