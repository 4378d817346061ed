//! `steradian`: render Mitsuba 3 scenes in physical units.
//!
//! A thin shell over the `steradian` and `steradian-mitsuba` libraries: argument parsing,
//! progress display, file output and error reporting live here, nothing else.

mod measure;
mod render;
mod verify;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "steradian",
    version,
    about = "Physically based rendering and light measurement of Mitsuba 3 scenes"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene to OpenEXR (linear RGB radiance, W/(m²·sr)) plus an sRGB PNG preview.
    Render(render::RenderArgs),
    /// Read a sensor (radiancemeter, irradiancemeter, or a camera's image mean) with its
    /// standard error, in W/(m²·sr) or W/m².
    Measure(measure::MeasureArgs),
    /// Run the built-in closed-form radiometry suite and report each case's z-score.
    Verify(verify::VerifyArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render::run(args),
        Command::Measure(args) => measure::run(args),
        Command::Verify(args) => verify::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // `e` displays as `error: ...` or, for scene errors, `file:line:col: error: ...`.
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
