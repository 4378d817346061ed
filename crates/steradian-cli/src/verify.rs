//! `steradian verify`: the built-in closed-form suite, so users can trust their installation.

use clap::Args;
use steradian_mitsuba::verify::{case_names, run_case, run_math_cases};

use crate::render::CliError;

#[derive(Args)]
pub struct VerifyArgs {
    /// Print JSON lines instead of a table.
    #[arg(long)]
    json: bool,
    #[arg(long)]
    threads: Option<usize>,
}

pub fn run(args: VerifyArgs) -> Result<(), CliError> {
    let mut failures = 0;
    let math = run_math_cases()?;
    if !args.json {
        println!("{:<40} {:>16} {:>16} {:>6}", "math case", "expected", "computed", "");
    }
    for m in &math {
        failures += usize::from(!m.pass);
        if args.json {
            println!(
                "{{\"kind\":\"math\",\"case\":{:?},\"expected\":{},\"measured\":{},\"tolerance\":{},\"pass\":{}}}",
                m.name, m.expected, m.measured, m.tolerance, m.pass
            );
        } else {
            println!(
                "{:<40} {:>16.10} {:>16.10} {:>6}",
                m.name,
                m.expected,
                m.measured,
                if m.pass { "pass" } else { "FAIL" }
            );
        }
    }
    if !args.json {
        println!();
        println!(
            "{:<34} {:>3} {:>12} {:>24} {:>7} {:>6}  units",
            "rendered case", "ch", "expected", "measured ± stderr", "z", ""
        );
    }
    for name in case_names() {
        let r = run_case(&name, 7, None, args.threads)?;
        failures += usize::from(!r.pass);
        if args.json {
            println!(
                "{{\"kind\":\"render\",\"case\":{:?},\"units\":{:?},\"spp\":{},\"expected\":{:?},\"measured\":{:?},\"stderr\":{:?},\"z\":{:?},\"pass\":{}}}",
                r.name, r.units, r.spp, r.expected, r.measured, r.stderr, r.z.map(|z| if z.is_finite() { z } else { 1e300f64.copysign(z) }), r.pass
            );
            continue;
        }
        for (c, ch) in ["R", "G", "B"].iter().enumerate() {
            let label = if c == 0 { r.name.as_str() } else { "" };
            let status = if c == 0 {
                if r.pass {
                    "pass"
                } else {
                    "FAIL"
                }
            } else {
                ""
            };
            println!(
                "{label:<34} {ch:>3} {:>12.6} {:>12.6} ± {:<9.2e} {:>7.2} {status:>6}  {}",
                r.expected[c],
                r.measured[c],
                r.stderr[c],
                r.z[c],
                if c == 0 { r.units.as_str() } else { "" }
            );
        }
    }
    let total = math.len() + case_names().len();
    if !args.json {
        println!();
        println!("{} passed, {} failed", total - failures, failures);
    }
    if failures > 0 {
        return Err(format!("{failures} verification case(s) failed").into());
    }
    Ok(())
}
