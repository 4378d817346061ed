//! `steradian measure`: a sensor's value with its standard error, in physical units.

use std::path::PathBuf;

use clap::Args;
use steradian::film::isolux_png;
use steradian::render::{measure, render, Estimate, GridReading, RenderOptions};
use steradian::sensor::SensorKind;

use crate::render::{parse_defines, parse_time_limit, CliError};

#[derive(Args)]
pub struct MeasureArgs {
    /// Mitsuba 3 XML scene with a meter (radiancemeter, irradiancemeter, workplane) or a camera.
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
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// For a work plane: print CSV, one line per cell (column i, row j, value, stderr).
    #[arg(long)]
    csv: bool,
    /// For a work plane: also write an isolux picture (false colour, contour lines, each
    /// cell's value, a scale) to this PNG file.
    #[arg(long, value_name = "FILE.png")]
    picture: Option<PathBuf>,
    /// Stop once every reading (a meter's, each cell of a work plane) is within this fraction
    /// of its value at 95 % confidence in every channel (1.96 standard errors; 0.01 = 1 %; a
    /// channel counting at least 1 % of the brightest). --spp is then the most samples taken
    /// (default 1048576).
    #[arg(long, value_name = "FRACTION")]
    target_error: Option<f64>,
    /// End the measurement after SECONDS: the reading is that of the whole passes finished by
    /// then, with its standard error.
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
    /// Each sample is the mean of N Owen-scrambled Sobol points under a scramble of its own
    /// (randomised quasi-Monte Carlo): the samples stay independent, so the standard errors
    /// stay honest, and each integrates far better than one point. --spp then counts these
    /// replicates (spp × N points per reading). Default 1: one independent point per sample.
    #[arg(long, value_name = "N")]
    batch: Option<u32>,
}

pub fn run(args: MeasureArgs) -> Result<(), CliError> {
    let defines = parse_defines(&args.defines)?;
    let time_limit = parse_time_limit(args.time_limit)?;
    RenderOptions {
        spp: args.spp,
        threads: args.threads,
        target_error: args.target_error,
        batch: args.batch,
        ..Default::default()
    }
    .validate()?;

    let scene = steradian_mitsuba::load_file(&args.scene, &defines)?;
    for w in &scene.warnings {
        eprintln!("{w}");
    }
    let sensor = match &args.sensor {
        Some(id) => scene.scene.find_sensor(id)?,
        None => 0,
    };
    let s = scene.scene.sensors.get(sensor).ok_or("the scene has no sensor")?;
    let opts = RenderOptions {
        spp: args.spp,
        target_error: args.target_error,
        seed: args.seed,
        sensor: Some(sensor),
        threads: args.threads,
        time_limit,
        batch: args.batch,
        ..Default::default()
    };
    let id = if s.id.is_empty() { format!("#{sensor}") } else { s.id.clone() };
    let own_batch = match &s.kind {
        SensorKind::Workplane(w) => w.batch,
        _ => 1,
    };
    if let Some(n) = args.batch.or(Some(own_batch)).filter(|&n| n > 1) {
        eprintln!("each sample: the mean of {n} Sobol points under a scramble of its own");
    }
    if let SensorKind::Workplane(w) = &s.kind {
        let out = render(&scene, &opts)?;
        if out.time_limited {
            eprintln!("time limit reached: {} of {} samples", out.spp, out.spp_requested);
        }
        let format = match (args.json, args.csv) {
            (true, _) => GridFormat::Json,
            (_, true) => GridFormat::Csv,
            _ => GridFormat::Text,
        };
        report_target(args.target_error, out.target_reached, out.spp);
        let grid = GridReading::from_render(&out, w.unit);
        print_grid(&id, out.spp, &grid, format);
        if let Some(path) = &args.picture {
            let title = if grid.unit == "lx" { "illuminance" } else { "irradiance" };
            isolux_png(path, &grid.values, grid.nx, grid.ny, title, grid.unit)?;
            eprintln!("wrote {}", path.display());
        }
        return Ok(());
    }
    if args.csv || args.picture.is_some() {
        return Err("--csv and --picture apply to a workplane sensor's grid".into());
    }
    let m = measure(&scene, &opts)?;
    report_target(args.target_error, m.target_reached, m.spp);
    if m.interrupted && !m.target_reached {
        eprintln!("time limit reached: {} of {} samples", m.spp, m.spp_requested);
    }
    let (quantity, unit, mean, se) = (m.quantity, m.unit(), m.value, m.stderr);
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

/// Says whether the target error was reached, and at how many samples.
pub(crate) fn report_target(target: Option<f64>, reached: bool, spp: u32) {
    if let Some(e) = target {
        if reached {
            eprintln!("target error {}% reached at {spp} spp", e * 100.0);
        } else {
            eprintln!("target error {}% not reached: stopped at {spp} spp", e * 100.0);
        }
    }
}

/// How `measure` prints a work plane's grid.
#[derive(Clone, Copy, PartialEq, Eq)]
enum GridFormat {
    Text,
    /// One object: `values` and `stderr` as ny rows of nx, `stats`.
    Json,
    /// One line per cell: `i,j,value,stderr` (i the column, j the row from the top).
    Csv,
}

/// A work plane's grid in `format`.
fn print_grid(id: &str, spp: u32, g: &GridReading, format: GridFormat) {
    let rows = |v: &[f64]| -> String {
        let rows: Vec<String> = v
            .chunks(g.nx)
            .map(|r| format!("[{}]", r.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(",")))
            .collect();
        format!("[{}]", rows.join(","))
    };
    let est = |e: Estimate| format!("{{\"value\":{},\"stderr\":{}}}", e.value, e.stderr);
    let st = &g.stats;
    if format == GridFormat::Csv {
        let unit = if g.unit == "lx" { "lx" } else { "W_m2" };
        println!("i,j,value_{unit},stderr_{unit}");
        for (k, (v, e)) in g.values.iter().zip(&g.stderr).enumerate() {
            println!("{},{},{v},{e}", k % g.nx, k / g.nx);
        }
        return;
    }
    if format == GridFormat::Json {
        println!(
            "{{\"sensor\":{id:?},\"quantity\":\"{}\",\"unit\":{:?},\"spp\":{spp},\"nx\":{},\"ny\":{},\"values\":{},\"stderr\":{},\"stats\":{{\"avg\":{},\"min\":{},\"max\":{},\"u0\":{},\"min_max\":{}}}}}",
            if g.unit == "lx" { "Illuminance" } else { "Irradiance" },
            g.unit,
            g.nx,
            g.ny,
            rows(&g.values),
            rows(&g.stderr),
            est(st.avg),
            est(st.min),
            est(st.max),
            est(st.u0),
            est(st.min_max)
        );
        return;
    }
    println!("sensor {id}: {}x{} work plane at {spp} spp, {}", g.nx, g.ny, g.unit);
    let line = |name: &str, e: Estimate, unit: &str| {
        println!("  {name:<8} {:.6e} ± {:.2e} {unit}", e.value, e.stderr)
    };
    line("avg", st.avg, g.unit);
    line("min", st.min, g.unit);
    line("max", st.max, g.unit);
    line("U0", st.u0, "(min/avg)");
    line("min/max", st.min_max, "");
    for row in g.values.chunks(g.nx) {
        println!("  {}", row.iter().map(|v| format!("{v:10.4}")).collect::<Vec<_>>().join(" "));
    }
}
