//! `steradian render`.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use steradian::film::false_color_png;
use steradian::film::{
    write_exr, write_exr_channels, write_png, ColorChannels, ComponentFormat, ExrLayer,
};
use steradian::integrator::Integrator;
use steradian::render::{
    image_error, render, Checkpoint, PixelQuantity, Progress, RenderError, RenderOptions,
    RenderSums, SampleAllocation, IMAGE_ERROR_FLOOR, IMAGE_PIXEL_QUANTILE, MIN_ADAPTIVE_GAIN,
};
use steradian::sampling::SamplerKind;

/// The built-in scene, rendered when no scene file is given.
const BUILTIN_SCENE: &str = include_str!("../../../scenes/cornell-box.xml");
const BUILTIN_NAME: &str = "cornell-box";

#[derive(Args)]
pub struct RenderArgs {
    /// Mitsuba 3 XML scene; the built-in Cornell box when omitted.
    scene: Option<PathBuf>,
    /// Output OpenEXR file (a PNG preview is written beside it). Default: the scene's name
    /// with `.exr`, beside the scene file (the current directory for the built-in scene).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Samples per pixel (overrides the scene's sampler).
    #[arg(long)]
    spp: Option<u32>,
    /// Random seed (overrides the scene's sampler).
    #[arg(long)]
    seed: Option<u64>,
    /// Sample generator: `sobol` (Owen-scrambled Sobol points, the default for cameras,
    /// whatever Mitsuba sampler the scene names) or `independent` (i.i.d. numbers, the
    /// default for meters, whose error bars assume them).
    #[arg(long, value_enum)]
    sampler: Option<SamplerArg>,
    /// Render the sensor with this id.
    #[arg(long)]
    sensor: Option<String>,
    /// Override a `<default name=... value=...>` of the scene: -D spp=64.
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    defines: Vec<String>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// What each pixel holds: `radiance` (W/(m²·sr), the default), `irradiance` (W/m² on the
    /// surface each pixel sees) or `illuminance` (lux = 683 lm/W × luminance of the
    /// irradiance). Maps also get a false-colour PNG with a labelled scale.
    #[arg(long, value_enum, default_value_t = Quantity::Radiance)]
    quantity: Quantity,
    /// Also write the per-pixel standard error of the mean to this OpenEXR file.
    #[arg(long, value_name = "FILE.exr")]
    stderr: Option<PathBuf>,
    /// Do not show the progress bar.
    #[arg(long)]
    quiet: bool,
    /// End the render after SECONDS: the image holds the whole passes finished by then (about
    /// half the work done or more), with their standard errors; with --checkpoint, a later
    /// --resume goes on.
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
    /// Stop once 95 % of the pixels are within this fraction of their value at 95 %
    /// confidence (1.96 standard errors; 0.05 = 5 %), a pixel's value counting at least 1 % of
    /// the image's mean (so dark pixels do not hold the render). --spp is then the most
    /// samples taken (default 1048576).
    #[arg(long, value_name = "FRACTION")]
    target_error: Option<f64>,
    /// How samples are spread over the pixels: `auto` (a pilot of 4 independent scrambles of
    /// 1 to 4 samples in one pixel of every 2 × 2, then adaptive where it predicts at least
    /// 1.4× lower relative variance; uniform below 32 spp), `adaptive` (always, after the pilot: each pixel's
    /// samples in proportion to its relative error, 0.75× to 16× the mean; --spp is then the
    /// mean per pixel) or `uniform` (every pixel the same).
    #[arg(long, value_enum, default_value_t = AllocationArg::Auto)]
    allocation: AllocationArg,
    /// Keep the finished passes' sums in FILE (written atomically every
    /// --checkpoint-interval seconds and at Ctrl-C, deleted when the image is written), so that
    /// a killed render can go on with --resume FILE.
    #[arg(long, value_name = "FILE")]
    checkpoint: Option<PathBuf>,
    /// Seconds between checkpoint writes (0: after every pass).
    #[arg(long, value_name = "SECONDS", default_value_t = 60.0)]
    checkpoint_interval: f64,
    /// Continue the render whose checkpoint is FILE (same scene, spp, seed, sensor and
    /// resolution, the same steradian version); it goes on checkpointing to FILE unless
    /// --checkpoint names another. The image is the one an uninterrupted render gives, bit
    /// for bit.
    #[arg(long, value_name = "FILE")]
    resume: Option<PathBuf>,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SamplerArg {
    Sobol,
    Independent,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AllocationArg {
    Auto,
    Adaptive,
    Uniform,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Quantity {
    Radiance,
    Irradiance,
    Illuminance,
}

/// Why a command failed.
#[derive(Debug)]
pub enum CliError {
    /// A scene error: its Display is already a compiler-style `file:line:col: error: ...`
    /// (or `error: ...` when it has no position).
    Load(steradian_mitsuba::LoadError),
    /// Anything else, in plain words.
    Other(String),
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Load(e) => write!(f, "{e}"),
            CliError::Other(m) => write!(f, "error: {m}"),
        }
    }
}

impl From<steradian_mitsuba::LoadError> for CliError {
    fn from(e: steradian_mitsuba::LoadError) -> Self {
        CliError::Load(e)
    }
}

impl From<String> for CliError {
    fn from(m: String) -> Self {
        CliError::Other(m)
    }
}

/// The library's render errors, with options named as the command line spells them.
impl From<RenderError> for CliError {
    fn from(e: RenderError) -> Self {
        match e {
            RenderError::BadOption { option, reason } => {
                CliError::Other(format!("--{option} {reason}"))
            }
            e => CliError::Other(e.to_string()),
        }
    }
}

impl From<&str> for CliError {
    fn from(m: &str) -> Self {
        CliError::Other(m.to_string())
    }
}

/// `--time-limit SECONDS`: a positive, finite number of seconds.
pub fn parse_time_limit(seconds: Option<f64>) -> Result<Option<Duration>, CliError> {
    match seconds {
        None => Ok(None),
        Some(t) if t.is_finite() && t > 0.0 => Ok(Some(Duration::from_secs_f64(t))),
        Some(t) => {
            Err(format!("--time-limit must be a positive number of seconds, got {t}").into())
        }
    }
}

pub fn parse_defines(defines: &[String]) -> Result<Vec<(String, String)>, String> {
    defines
        .iter()
        .map(|d| match d.split_once('=') {
            Some((k, v)) if !k.is_empty() => Ok((k.to_string(), v.to_string())),
            _ => Err(format!("-D expects NAME=VALUE, got '{d}'")),
        })
        .collect()
}

pub fn run(args: RenderArgs) -> Result<(), CliError> {
    // Check the arguments before the (possibly slow) scene load.
    let defines = parse_defines(&args.defines)?;
    if !(args.checkpoint_interval.is_finite() && args.checkpoint_interval >= 0.0) {
        return Err("--checkpoint-interval must be a number of seconds, at least 0".into());
    }
    let time_limit = parse_time_limit(args.time_limit)?;
    let resumed = match &args.resume {
        Some(path) => Some(Checkpoint::read(path)?),
        None => None,
    };
    let checkpoint_path = args.checkpoint.clone().or_else(|| args.resume.clone());
    RenderOptions { spp: args.spp, threads: args.threads, ..Default::default() }.validate()?;
    let output = match (&args.output, &args.scene) {
        (Some(o), _) => o.clone(),
        (None, Some(path)) => path.with_extension("exr"),
        (None, None) => PathBuf::from(format!("{BUILTIN_NAME}.exr")),
    };
    if output.extension().and_then(|e| e.to_str()).map(|e| e.to_ascii_lowercase())
        != Some("exr".into())
    {
        return Err(format!("output file '{}' must end in .exr", output.display()).into());
    }
    let load_start = Instant::now();
    // the XML (and its includes) parsed, then the scene built from it: meshes and images
    // read, BSDF tables made, the BVH built
    let (tree, base) = match &args.scene {
        Some(path) => (
            steradian_mitsuba::parse_file(path, &defines)?,
            path.parent().unwrap_or(Path::new(".")),
        ),
        None => (
            steradian_mitsuba::xml::parse_string_named(
                BUILTIN_SCENE,
                Path::new(&format!("<built-in {BUILTIN_NAME}.xml>")),
                Path::new("."),
                &defines,
            )?,
            Path::new("."),
        ),
    };
    let parse_time = load_start.elapsed();
    let scene = steradian_mitsuba::build_scene(&tree, base)?;
    let load_time = load_start.elapsed();
    // what a checkpoint must match: the contents of every file the scene read, and the -D
    // overrides
    let scene_digest = match checkpoint_path {
        Some(_) => {
            let source = args.scene.is_none().then_some(BUILTIN_SCENE);
            steradian_mitsuba::scene_digest(&scene, &defines, source)?
        }
        None => 0,
    };
    for w in &scene.warnings {
        eprintln!("{w}");
    }
    let sensor = match &args.sensor {
        Some(id) => Some(scene.scene.find_sensor(id)?),
        None => None,
    };

    let cancel = Arc::new(AtomicBool::new(false));
    {
        let cancel = cancel.clone();
        // A second Ctrl-C ends the process at once.
        ctrlc::set_handler(move || {
            if cancel.swap(true, Ordering::SeqCst) {
                std::process::exit(130);
            }
        })
        .map_err(|e| format!("cannot install the Ctrl-C handler: {e}"))?;
    }

    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        let b = ProgressBar::new(1000);
        b.set_style(
            ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}%  ETA {eta}  {msg}",
            )
            .expect("valid progress template"),
        );
        b.enable_steady_tick(Duration::from_millis(200));
        b
    };
    let progress = |p: Progress| {
        bar.set_position(p.samples_done * 1000 / p.samples_total.max(1));
        bar.set_message(format!(
            "{:.1} Msamples/s",
            p.samples_done as f64 / p.elapsed.as_secs_f64().max(1e-9) / 1e6
        ));
    };
    let writer = checkpoint_path
        .as_ref()
        .map(|p| Checkpoint::new(p, Duration::from_secs_f64(args.checkpoint_interval)));
    let on_pass = |sums: &RenderSums| {
        if let Some(w) = &writer {
            w.maybe_save(sums);
        }
    };
    let opts = RenderOptions {
        spp: args.spp,
        seed: args.seed,
        sampler: args.sampler.map(|s| match s {
            SamplerArg::Sobol => SamplerKind::Sobol,
            SamplerArg::Independent => SamplerKind::Independent,
        }),
        threads: args.threads,
        sensor,
        cancel: Some(&cancel),
        progress: Some(&progress),
        quantity: match args.quantity {
            Quantity::Radiance => PixelQuantity::Sensor,
            Quantity::Irradiance => PixelQuantity::SurfaceIrradiance,
            Quantity::Illuminance => PixelQuantity::SurfaceIlluminance,
        },
        range: None,
        branches: None,
        resume: resumed,
        on_pass: writer.as_ref().map(|_| &on_pass as &(dyn Fn(&_) + Sync)),
        scene_digest,
        time_limit,
        target_error: args.target_error,
        batch: None,
        allocation: match args.allocation {
            AllocationArg::Auto => SampleAllocation::Auto,
            AllocationArg::Adaptive => SampleAllocation::Adaptive,
            AllocationArg::Uniform => SampleAllocation::Uniform,
        },
    };
    let out = render(&scene, &opts).map_err(|e| match (e, &args.resume) {
        (RenderError::Resume(e), Some(path)) => {
            CliError::Other(format!("cannot resume from {}: the checkpoint {e}", path.display()))
        }
        (e, _) => e.into(),
    })?;
    bar.finish_and_clear();
    if let Some(w) = &writer {
        if let Some(e) = w.failure() {
            eprintln!("warning: {e}");
        }
        // a render that reached its target error is done, not interrupted
        if out.interrupted && !out.target_reached {
            w.save(&out.sums)?;
            eprintln!(
                "checkpoint: {} holds {} of {} samples per pixel; continue with --resume {}",
                w.path().display(),
                out.spp,
                out.spp_requested,
                w.path().display()
            );
        }
    }

    let write_start = Instant::now();
    let (image, error) = (out.image(), out.stderr_image());
    let aovs = out.aov_images();
    let color = out.film().pixel_format.color();
    // f32 whatever the scene's `component_format` says (float16 would only lose precision),
    // except `uint32`, whose values are Mitsuba's integers (`steradian::film::hdrfilm`)
    let format = match out.film().component_format {
        ComponentFormat::UInt32 => ComponentFormat::UInt32,
        ComponentFormat::Float16 | ComponentFormat::Float32 => ComponentFormat::Float32,
    };
    if aovs.is_empty() && color == ColorChannels::Rgb && format == ComponentFormat::Float32 {
        write_exr(&output, &image)?;
    } else {
        // the image in the film's `pixel_format` (R, G, B; Y; or X, Y, Z), then each AOV
        // layer's channels (`moment`, `aov`, and last the alpha channel `A`: Mitsuba's layout)
        let converted = color.convert(&image);
        let mut layers = vec![ExrLayer { prefix: "", channels: color.names(), image: &converted }];
        layers.extend(aovs.iter().map(|(layer, img)| ExrLayer {
            prefix: &layer.name,
            channels: &layer.channels,
            image: img,
        }));
        write_exr_channels(&output, &layers, format)?;
    }
    let png = output.with_extension("png");
    match args.quantity {
        Quantity::Radiance => write_png(&png, &image, 1.0)?,
        Quantity::Irradiance => false_color_png(&png, &image, "irradiance", "W/m²")?,
        Quantity::Illuminance => false_color_png(&png, &image, "illuminance", "lx")?,
    }
    if let Some(path) = &args.stderr {
        write_exr(path, &error)?;
        println!("wrote the standard error of each pixel to {}", path.display());
    }

    let write_time = write_start.elapsed();
    let secs = out.elapsed.as_secs_f64();
    if out.time_limited {
        eprintln!(
            "time limit reached: the image holds {} of {} samples per pixel",
            out.spp, out.spp_requested
        );
    } else if out.interrupted && !out.target_reached {
        eprintln!(
            "interrupted: the image holds {} of {} samples per pixel",
            out.spp, out.spp_requested
        );
    }
    crate::measure::report_target(args.target_error, out.target_reached, out.spp);
    if out.quantity == PixelQuantity::Sensor || args.target_error.is_some() {
        println!(
            "error reached: {:.0} % of the pixels within ±{:.2} % of their value at 95 % confidence (a pixel's value counting at least {:.0} % of the image's mean)",
            IMAGE_PIXEL_QUANTILE * 100.0,
            image_error(out.film()) * 100.0,
            IMAGE_ERROR_FLOOR * 100.0
        );
    }
    // the work counted as it is done: a camera sample of `path` with n branches traces n
    // paths from its first hit; the particle tracer's samples are light paths; rays are the
    // ray queries made (camera, continuation and shadow rays), the unit of a ray tracer's speed
    let per_second = |n: u64| n as f64 / secs.max(1e-9) / 1e6;
    let done = out.samples_rendered();
    let rays = format!("{:.2} Mrays/s", per_second(out.rays));
    let rate = match (&scene.integrator, out.branches) {
        (Integrator::ParticleTracer(_), _) => {
            format!("{:.2} M light paths/s, {rays}", per_second(done))
        }
        (_, Some(n)) if n > 1 => format!(
            "{:.2} Msamples/s, {:.2} Mpaths/s, {rays}",
            per_second(done),
            per_second(done * n as u64)
        ),
        _ => format!("{:.2} Msamples/s, {rays}", per_second(done)),
    };
    let resumed_note = if out.spp_rendered < out.spp {
        format!(" ({} resumed from the checkpoint)", out.spp - out.spp_rendered)
    } else {
        String::new()
    };
    println!(
        "rendered {}x{} at {} spp{resumed_note} in {:.2} s ({rate}), {} dropped NaN/Inf samples",
        out.film().width,
        out.film().height,
        out.spp,
        secs,
        out.dropped_samples
    );
    if let Some(a) = out.adaptive {
        let decided = if a.adaptive {
            format!("adaptive, {} samples in all", out.samples())
        } else {
            format!("uniform (less than {MIN_ADAPTIVE_GAIN}× to gain)")
        };
        println!(
            "allocation: a pilot of {} spp ({:.2} s) predicted {:.2}× lower relative variance adaptive: {decided}",
            a.pilot_spp,
            a.pilot_time.as_secs_f64(),
            a.predicted_gain
        );
    }
    match (out.branches, out.pilot) {
        (Some(n), Some(p)) => println!(
            "path: {n} {} per camera sample, chosen by a pilot of {} samples",
            plural(n, "branch", "branches"),
            p.samples
        ),
        (Some(n), None) => {
            println!("path: {n} {} per camera sample", plural(n, "branch", "branches"))
        }
        _ => {}
    }
    let build_time = scene.scene.build_time().as_secs_f64();
    println!(
        "time: load {:.2} s (parse {:.2} s, files {:.2} s, BVH build {:.2} s), render {:.2} s, write {:.2} s",
        load_time.as_secs_f64(),
        parse_time.as_secs_f64(),
        (load_time - parse_time).as_secs_f64() - build_time,
        build_time,
        secs,
        write_time.as_secs_f64()
    );
    let stats = scene.scene.accel_stats();
    let prims = stats.triangles + stats.analytic_prims;
    println!(
        "bvh: {prims} primitives, built at {:.2} M/s, {:.1} MB ({:.1} bytes per primitive)",
        prims as f64 / build_time.max(1e-9) / 1e6,
        stats.bytes as f64 / 1e6,
        stats.bytes as f64 / prims.max(1) as f64
    );
    println!("wrote {} and {}", output.display(), png.display());
    if let (Some(w), false) = (&writer, out.interrupted && !out.target_reached) {
        // the image holds every sample: the checkpoint has done its work
        w.remove();
    }
    Ok(())
}

fn plural<'a>(n: u32, one: &'a str, many: &'a str) -> &'a str {
    if n == 1 {
        one
    } else {
        many
    }
}
