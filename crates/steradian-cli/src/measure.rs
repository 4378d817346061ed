//! `steradian measure`: a sensor's value with its standard error, in physical units.

use std::path::PathBuf;

use clap::Args;
use steradian::integrator::{render, RenderOptions};

use crate::render::{parse_defines, CliError};

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
}

pub fn run(args: MeasureArgs) -> Result<(), CliError> {
    let defines = parse_defines(&args.defines)?;
    let scene = steradian_mitsuba::load_file(&args.scene, &defines)?;
    let sensor = match &args.sensor {
        Some(id) => scene.sensor_index(id).ok_or_else(|| format!("the scene has no sensor with id '{id}'"))?,
        None => 0,
    };
    if args.spp == Some(0) {
        return Err("--spp must be at least 1".into());
    }
    let s = scene.sensors.get(sensor).ok_or("the scene has no sensor")?;
    let (quantity, unit) = (s.quantity(), s.quantity().unit());
    let out = render(&scene, &RenderOptions { spp: args.spp, seed: args.seed, sensor: Some(sensor), threads: args.threads, ..Default::default() })
        .map_err(|e| e.to_string())?;
    let (value, error) = (out.film.develop(), out.film.develop_stderr());
    // a meter has one pixel; for a camera report the image mean and the error of that mean
    let n = (value.width * value.height) as f64;
    let mean = value.channel_means();
    let mut var = [0.0f64; 3];
    for y in 0..error.height {
        for x in 0..error.width {
            let e = error.get(x, y);
            for c in 0..3 {
                var[c] += (e[c] as f64).powi(2);
            }
        }
    }
    let se = var.map(|v| v.sqrt() / n);
    let id = if s.id.is_empty() { format!("#{sensor}") } else { s.id.clone() };
    if args.json {
        println!(
            "{{\"sensor\":{id:?},\"quantity\":\"{quantity:?}\",\"unit\":{unit:?},\"spp\":{},\"value\":[{},{},{}],\"stderr\":[{},{},{}],\"dropped_samples\":{}}}",
            out.spp, mean[0], mean[1], mean[2], se[0], se[1], se[2], out.dropped_samples
        );
    } else {
        println!("sensor {id}: {quantity:?} at {} spp", out.spp);
        for (c, name) in ["R", "G", "B"].iter().enumerate() {
            println!("  {name}: {:.6e} ± {:.2e} {unit}", mean[c], se[c]);
        }
    }
    Ok(())
}
