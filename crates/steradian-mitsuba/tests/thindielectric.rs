//! Purpose: `thindielectric` renders `reference/thindielectric.xml` as Mitsuba 3.9.1 does under
//! `path` and `volpath` (its render-test rule, 4096-spp `llvm_ad_rgb` references), where its
//! transmission is a null lobe: `volpath`'s shadow rays cross a pane weighted by
//! (1 − R')·`specular_transmittance` where `path`'s stop at it, and under `path` a null-BSDF
//! light seen through a pane against the void is black. Each integrator's image fails the
//! other's reference, so each reference tells the two behaviours apart.

mod common;

use common::{reference_scene as data, z_test_against};
use steradian::render::Job;

const SPP: u32 = 64;

fn load(integrator: &str) -> Job {
    let defines = [("integrator".to_string(), integrator.to_string())];
    steradian_mitsuba::load_file(&data("thindielectric.xml"), &defines)
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn panes_under_path_match_mitsuba() {
    let z = z_test_against(&load("path"), SPP, "thindielectric-path", "path");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    let z = z_test_against(&load("volpath"), SPP, "thindielectric-path", "volpath against path");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

#[test]
fn panes_under_volpath_match_mitsuba() {
    let job = load("volpath");
    let z = z_test_against(&job, SPP, "thindielectric-volpath", "volpath");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
    let mean_z = common::image_mean_z(&job, SPP, "thindielectric-volpath", 4096);
    eprintln!("thindielectric volpath image mean: z = {mean_z:.2}");
    assert!(mean_z < 4.0, "image mean off by {mean_z:.2} standard errors");
    let z = z_test_against(&load("path"), SPP, "thindielectric-volpath", "path against volpath");
    assert!(!z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}
