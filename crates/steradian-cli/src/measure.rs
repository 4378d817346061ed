//! `steradian measure`: a sensor's value with its standard error, in physical units.

use std::path::PathBuf;

use clap::Args;
use steradian::render::{measure, RenderOptions};

use crate::render::{parse_defines, parse_time_limit, CliError};

#[derive(Args)]
pub struct MeasureArgs {
    /// Mitsuba 3 XML scene with a meter (radiancemeter, irradiancemeter) or a camera.
    scene: PathBuf,
    /// The sensor to read, by id (default: the first).
    #[arg(long)]
    sensor: Option<String>,
    /// Samples (overrides the scene's sampler).
    #[arg(long)]
    spp: Option<u32>,
    #[arg(long)]
    seed: Option<u64>,
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    defines: Vec<String>,
    #[arg(long)]
    threads: Option<usize>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// End the measurement after SECONDS: the reading is that of the whole passes finished by
    /// then, with its standard error.
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
}

pub fn run(args: MeasureArgs) -> Result<(), CliError> {
    let defines = parse_defines(&args.defines)?;
    let time_limit = parse_time_limit(args.time_limit)?;
    RenderOptions { spp: args.spp, threads: args.threads, ..Default::default() }.validate()?;
    let scene = steradian_mitsuba::load_file(&args.scene, &defines)?;
    for w in &scene.warnings {
        eprintln!("{w}");
    }
    let sensor = match &args.sensor {
        Some(id) => scene.scene.find_sensor(id)?,
        None => 0,
    };
    let s = scene.scene.sensors.get(sensor).ok_or("the scene has no sensor")?;
    let m = measure(
        &scene,
        &RenderOptions {
            spp: args.spp,
            seed: args.seed,
            sensor: Some(sensor),
            threads: args.threads,
            time_limit,
            ..Default::default()
        },
    )?;
    if m.interrupted {
        eprintln!("time limit reached: {} of {} samples", m.spp, m.spp_requested);
    }
    let (quantity, unit, mean, se) = (m.quantity, m.unit(), m.value, m.stderr);
    let id = if s.id.is_empty() { format!("#{sensor}") } else { s.id.clone() };
    if args.json {
        println!(
            "{{\"sensor\":{id:?},\"quantity\":\"{quantity:?}\",\"unit\":{unit:?},\"spp\":{},\"value\":[{},{},{}],\"stderr\":[{},{},{}],\"dropped_samples\":{}}}",
            m.spp, mean[0], mean[1], mean[2], se[0], se[1], se[2], m.dropped_samples
        );
    } else {
        println!("sensor {id}: {quantity:?} at {} spp", m.spp);
        for (c, name) in ["R", "G", "B"].iter().enumerate() {
            println!("  {name}: {:.6e} ± {:.2e} {unit}", mean[c], se[c]);
        }
    }
    Ok(())
}
