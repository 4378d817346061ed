//! What a render is asked for ([`RenderOptions`]), what it returns ([`RenderOutput`]), and the
//! plan that checks the one against the scene before any work starts ([`Plan`]).

use std::fmt;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use super::quantity::PixelQuantity;
use super::sums::{RenderSums, SumsError, SumsHeader};
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
    /// Render only the samples `first..end` of every pixel (both on the render's pass
    /// boundaries, [`pass_bounds`](super::pass_bounds)); `None` = all (or, resuming, the rest).
    pub range: Option<(u32, u32)>,
    /// `path`'s branch count when the scene leaves it to the pilot: the count a first range
    /// or an earlier process chose, so that every range renders the same paths.
    pub branches: Option<u32>,
    /// Sums to continue (a checkpoint): the render adds its passes to them, starting where
    /// they end, and returns the whole.
    pub resume: Option<RenderSums>,
    /// Called on the merging thread with the sums so far after each pass is added.
    pub on_pass: Option<&'a (dyn Fn(&RenderSums) + Sync)>,
    /// Written into the sums' header ([`SumsHeader::scene_digest`](super::SumsHeader)).
    pub scene_digest: u64,
    /// End the render this long after it began: like a cancel, the passes finished by then
    /// are kept and those under way abandoned (`RenderOutput::time_limited` tells). Passes
    /// double in size up to spp/32, so about half the work done or more is kept; the first
    /// pass is always finished.
    pub time_limit: Option<Duration>,
    /// Stop after the first pass at which every reading's error (meters, work planes) or 95 %
    /// of the pixels' errors (images) is at most this fraction of the value
    /// (`target_error.rs`); `spp` is then the most samples taken (`MAX_SPP_FOR_TARGET` where
    /// it is unset).
    pub target_error: Option<f64>,
    /// Meters and work planes only: each sample is the mean of this many Owen-scrambled Sobol
    /// points under a scramble of its own (a randomised quasi-Monte Carlo replicate), so the
    /// samples stay independent (their standard error honest) while each integrates far
    /// better than one point (`block.rs`); `spp` then counts replicates and the points taken
    /// are spp × batch. `None` or 1: one independent point per sample.
    pub batch: Option<u32>,
    /// How a camera image's samples are spread over its pixels (`adaptive.rs`): `Auto` (the
    /// default) takes a short pilot and renders adaptively where that is predicted to pay.
    pub allocation: SampleAllocation,
}

/// How a camera image's samples are spread over its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SampleAllocation {
    /// A pilot, then adaptive sampling when it predicts at least
    /// [`MIN_ADAPTIVE_GAIN`](super::MIN_ADAPTIVE_GAIN) for the image's relative error, uniform
    /// otherwise; uniform for meters, surface maps, AOV and particle renders, and renders of
    /// fewer than [`MIN_SPP_FOR_AUTO`](super::MIN_SPP_FOR_AUTO) samples per pixel.
    #[default]
    Auto,
    /// The same samples in every pixel.
    Uniform,
    /// A pilot, then samples where they lower the image's relative error most (camera
    /// radiance renders only).
    Adaptive,
}

/// The largest `batch`: one Sobol epoch.
pub const MAX_BATCH: u32 = 1 << 16;

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
        if self.target_error.is_some_and(|e| !(e.is_finite() && e > 0.0 && e < 1.0)) {
            return Err(RenderError::BadOption {
                option: "target-error",
                reason: "must be a fraction between 0 and 1 (0.01 = 1 %)",
            });
        }
        if self.batch.is_some_and(|b| !(1..=MAX_BATCH).contains(&b)) {
            return Err(RenderError::BadOption {
                option: "batch",
                reason: "must be between 1 and 65536 points per sample",
            });
        }
        if self.allocation == SampleAllocation::Adaptive && self.quantity != PixelQuantity::Sensor {
            return Err(RenderError::BadOption {
                option: "allocation",
                reason: "adaptive applies to radiance images, not irradiance maps",
            });
        }
        if self.time_limit.is_some_and(|t| t.is_zero()) {
            return Err(RenderError::BadOption {
                option: "time-limit",
                reason: "must be more than 0 seconds",
            });
        }
        Ok(())
    }
}

/// The result of a render.
#[derive(Debug)]
pub struct RenderOutput {
    /// The raw sums: of the whole render so far for a render from sample 0 (resumed or not),
    /// else of the range rendered.
    pub sums: RenderSums,
    /// What the film's pixels hold before [`RenderOutput::image`] converts them.
    pub quantity: PixelQuantity,
    /// Paths continued from each camera ray's first hit (`path` only).
    pub branches: Option<u32>,
    /// What the pilot that chose `branches` measured, when one ran.
    pub pilot: Option<Pilot>,
    /// Samples per pixel actually in the film.
    pub spp: u32,
    pub spp_requested: u32,
    /// Samples per pixel rendered by this call (less than `spp` when it resumed sums).
    pub spp_rendered: u32,
    /// Samples whose value was NaN or infinite: dropped, never splatted.
    pub dropped_samples: u64,
    pub elapsed: Duration,
    /// The film holds fewer samples than asked for (a cancel, or the time limit).
    pub interrupted: bool,
    /// The render stopped at its time limit before its last sample.
    pub time_limited: bool,
    /// The render stopped because it reached `RenderOptions::target_error`.
    pub target_reached: bool,
    /// Samples in the film, all pixels (pixels × `spp` for a uniform render).
    pub film_samples: u64,
    /// Samples rendered by this call, all pixels.
    pub rendered_samples: u64,
    /// Ray queries (closest hits and shadow rays) made by this call's passes, pilots not
    /// counted: the work behind `elapsed`, for rays per second.
    pub rays: u64,
    /// The adaptive pilot and what it decided, when one ran.
    pub adaptive: Option<super::AdaptiveReport>,
}

impl RenderOutput {
    /// The film: the sums' passes folded.
    pub fn film(&self) -> &Film {
        self.sums.film()
    }

    /// Samples in the film, all pixels (pixels × spp for a uniform render; `spp` is then
    /// the mean per pixel of an adaptive render).
    pub fn samples(&self) -> u64 {
        self.film_samples
    }

    /// Samples rendered by this call, all pixels (the adaptive pilot's not counted).
    pub fn samples_rendered(&self) -> u64 {
        self.rendered_samples
    }

    /// The image in the unit of the requested quantity (illuminance converted from the
    /// film's irradiance).
    pub fn image(&self) -> Image {
        self.sums.image()
    }

    /// The standard error of each pixel of [`RenderOutput::image`], same unit.
    pub fn stderr_image(&self) -> Image {
        self.sums.stderr_image()
    }

    /// The AOV layers the integrator wrote (`moment`'s), developed, each with its name and
    /// channel names.
    pub fn aov_images(&self) -> Vec<(crate::film::AovLayer, Image)> {
        let film = self.film();
        let layers = film.aov_layers();
        layers.iter().enumerate().map(|(k, l)| (l.clone(), film.develop_aov(k))).collect()
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
    /// The particle tracer renders images through `perspective` and `thinlens` cameras only.
    ParticlesNeedPinhole,
    /// An option out of its range: the option's name and what it must be.
    BadOption {
        option: &'static str,
        reason: &'static str,
    },
    ThreadPool(String),
    /// A range that does not start and end on pass boundaries: the range and the boundaries.
    BadRange {
        first: u32,
        end: u32,
        bounds: Vec<u32>,
    },
    /// Sums to resume that do not belong to this render.
    Resume(SumsError),
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
                "the ptracer integrator renders images through a perspective or thinlens camera only (no orthographic, batch or meters, no irradiance maps): use `path` for those"
            ),
            RenderError::BadOption { option, reason } => write!(f, "{option} {reason}"),
            RenderError::ThreadPool(e) => write!(f, "could not start worker threads: {e}"),
            RenderError::BadRange { first, end, bounds } => {
                let shown: Vec<String> = bounds.iter().take(40).map(u32::to_string).collect();
                let more = if bounds.len() > 40 { ", …" } else { "" };
                write!(
                    f,
                    "the sample range {first}..{end} does not fall on this render's pass boundaries ({}{more})",
                    shown.join(", ")
                )
            }
            RenderError::Resume(e) => write!(f, "cannot resume: the sums {e}"),
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
    /// Sobol points per sample (meters only; 1 = one independent point).
    pub batch: u32,
    /// The sensor's film, cleared.
    pub film: Film,
    pub quantity: PixelQuantity,
}

impl<'a> Plan<'a> {
    /// The header of this render's sums, with its branch count (0: not `path`).
    pub fn header(&self, branches: u32, sensor: usize, scene_digest: u64) -> SumsHeader {
        SumsHeader {
            width: self.film.width,
            height: self.film.height,
            aov_layers: self.film.aov_layers().len() as u32,
            spp: self.spp,
            seed: self.sampler.seed,
            sampler: self.sampler.kind,
            branches,
            quantity: self.quantity,
            sensor: sensor as u32,
            scene_digest,
            // set once the adaptive pilot has run
            allocation: 0,
        }
    }

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
            && (opts.quantity.is_surface_map() || sensor.sample_lens(glam::Vec2::ZERO).is_none())
        {
            return Err(RenderError::ParticlesNeedPinhole);
        }
        let mut sampler = sensor.sampler;
        // with a target error and no spp, the samples are capped, not set
        match (opts.spp, opts.target_error) {
            (Some(spp), _) => sampler.sample_count = spp,
            (None, Some(_)) => sampler.sample_count = super::MAX_SPP_FOR_TARGET,
            (None, None) => {}
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
            if film.pixel_format.has_alpha() && job.integrator.alpha_rule().is_none() {
                return Err(RenderError::BadOption {
                    option: "pixel_format",
                    reason: "an alpha channel needs camera samples; ptracer has none",
                });
            }
            let layers = job.camera_layers(sensor);
            if layers.len() > super::MAX_AOV_LAYERS {
                return Err(RenderError::BadOption {
                    option: "integrator",
                    reason: "writes more AOV layers than a sample carries (16)",
                });
            }
            film = film.with_aov_layers(layers);
        }
        // the options' batch, else a work plane's own
        let own = match &sensor.kind {
            crate::sensor::SensorKind::Workplane(w) if w.batch > 1 => Some(w.batch),
            _ => None,
        };
        let batch = match (opts.batch.or(own), meter) {
            (None | Some(1), _) => 1,
            (Some(b), true) => b,
            (Some(_), false) => {
                return Err(RenderError::BadOption {
                    option: "batch",
                    reason: "applies to meters and work planes (a camera's pixels already take \
                             Sobol points)",
                })
            }
        };
        Ok(Plan {
            sensor,
            sampler,
            spp: sampler.sample_count,
            meter,
            batch,
            film,
            quantity: opts.quantity,
        })
    }
}
