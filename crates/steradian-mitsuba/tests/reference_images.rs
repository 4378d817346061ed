//! Renders the shared reference scenes and compares them with Mitsuba 3.9.1's converged
//! renders (4096–8192 spp, copied into `tests/reference/`).
//!
//! relMSE = mean((a − b)² / (b² + 0.01)) over pixels and channels. Renders use 64 camera
//! samples per pixel, each split by `path` into the branches its pilot chooses
//! (integrator/branching.rs); at seed 1 that gives relMSE 6.0e-5 (cornell), 6.3e-6 (furnace),
//! 1.2e-5 (pointlight), 2.1e-4 (veach), 1.0e-4 (materials), 3.0e-5 (plastics) and 1.4e-4
//! (textures), all below what 256 unsplit samples gave, plus the references' own noise
//! floor. The bounds below are those the issue set for 256 unsplit samples, about twice
//! their noise. A biased renderer fails them; so does one that gets a convention (camera,
//! units, one-sidedness) wrong. Channel means must agree within 0.5 %.

use std::path::PathBuf;

use steradian::film::{read_exr, rel_mse, Image};
use steradian::render::{render, RenderOptions};

/// Camera samples per pixel of every comparison.
const SPP: u32 = 64;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference").join(name)
}

fn render_scene(name: &str, spp: u32) -> Image {
    let scene = steradian_mitsuba::load_file(&data(&format!("{name}.xml")), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    let out =
        render(&scene, &RenderOptions { spp: Some(spp), seed: Some(1), ..Default::default() })
            .unwrap();
    assert_eq!(out.spp, spp);
    assert_eq!(out.dropped_samples, 0, "NaN/Inf samples in {name}");
    out.film().develop()
}

fn compare(name: &str, spp: u32, max_rel_mse: f64, max_mean_error: f64) {
    let img = render_scene(name, spp);
    let reference = read_exr(&data(&format!("{name}-ref.exr"))).unwrap();
    assert_eq!((img.width, img.height), (reference.width, reference.height));
    let e = rel_mse(&img, &reference);
    let (m, r) = (img.channel_means(), reference.channel_means());
    let ratios: Vec<f64> = (0..3).map(|c| m[c] / r[c]).collect();
    eprintln!(
        "{name} @ {spp} spp: relMSE {e:.3e} (bound {max_rel_mse:.1e}), mean ratios {ratios:.5?}"
    );
    assert!(e <= max_rel_mse, "{name}: relMSE {e:.3e} exceeds {max_rel_mse:.1e}");
    for (c, ratio) in ratios.iter().enumerate() {
        assert!(
            (ratio - 1.0).abs() <= max_mean_error,
            "{name}: channel {c} mean ratio {ratio:.5} off by more than {max_mean_error}"
        );
    }
}

#[test]
fn cornell_matches_mitsuba() {
    compare("cornell", SPP, 6.7e-4, 0.005);
}

#[test]
fn furnace_matches_mitsuba() {
    compare("furnace", SPP, 2.0e-4, 0.005);
}

#[test]
fn pointlight_matches_mitsuba() {
    compare("pointlight", SPP, 1.0e-4, 0.005);
}

#[test]
fn veach_matches_mitsuba() {
    // glossy GGX plates (roughconductor, α 0.005–0.1): Mitsuba reaches relMSE 9e-3 at 64 spp
    compare("veach", SPP, 4.6e-3, 0.01);
}

#[test]
fn materials_matches_mitsuba() {
    // diffuse, roughplastic (GGX α 0.1, with Mitsuba's coating tables), rough gold and glass
    // spheres; Mitsuba reaches relMSE 1.76e-3 at 64 spp (llvm), so 256 unsplit spp give ≈ 4.4e-4
    compare("materials", SPP, 8.8e-4, 0.005);
}

#[test]
fn plastics_match_mitsuba() {
    // smooth plastic (linear and nonlinear, tinted specular) and roughplastic (Beckmann and
    // GGX without visible-normal sampling), 128×128; Mitsuba's own 256-spp render (seed 5)
    // has relMSE 1.80e-4 against this 4096-spp reference, so the bound is twice that.
    compare("plastics", SPP, 3.6e-4, 0.005);
}

#[test]
fn textures_match_mitsuba() {
    // checkerboard and bitmap (PNG, JPEG, EXR) textures on reflectances, a blend weight, a mask
    // opacity and two area-light radiances; bumpmap, normalmap (with Mitsuba 3.9.1's flip of
    // invalid normals and its shadowing term), blendbsdf and mask; 128×128, reference 8192 spp
    // (llvm_ad_rgb). steradian's 256-spp relMSE is 3.7e-4 (Mitsuba's own 256-spp render, seed
    // 5: 7.3e-4), so the bound is twice steradian's; before the shadowing term was matched the
    // normal-mapped cube was 2–7 % too bright and the mean 0.6 % off.
    compare("textures", SPP, 7.4e-4, 0.005);
}
