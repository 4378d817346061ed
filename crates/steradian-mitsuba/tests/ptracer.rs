//! Purpose: the `ptracer` integrator renders `reference/ptracer.xml` (an area light seen by
//! the camera, a point light, a spot light and a constant sky over diffuse, rough-gold and
//! plastic objects, gaussian film filter) as Mitsuba 3.9.1's `ptracer` renders it (its Z-test
//! rule, a 4096-spp `llvm_ad_rgb` reference); hiding the emitters or stopping paths at direct
//! light moves the image mean by more than 4 standard errors; on a bump-mapped floor, through a
//! masked bump-mapped panel, on measured materials, under a rotated environment map and through
//! a camera with a shifted principal point it renders `path`'s image; the image does not depend on the thread count;
//! light paths start from projectors as Mitsuba's do and connect to a thin lens's aperture as
//! Mitsuba's do (`reference/ptracer-thinlens.xml`); sensors it cannot connect to are refused.

mod common;

use std::path::Path;

use common::{reference_scene as data, z_test_against};
use steradian::render::{render, RenderError, RenderOptions};

const SPP: u32 = 64;

fn scene_with(from: &str, to: &str) -> steradian::render::Job {
    common::reference_scene_with("ptracer.xml", from, to)
}

/// `reference/{name}.xml` passes Mitsuba's render-test rule against its Mitsuba `ptracer`
/// reference, and its image mean is within 4 standard errors of the reference's.
#[track_caller]
fn matches_mitsuba(name: &str, label: &str, spp: u32) {
    let job = steradian_mitsuba::load_file(&data(&format!("{name}.xml")), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(z_test_against(&job, spp, name, label).passes());
    let mean_z = common::image_mean_z(&job, spp, name, 4096);
    eprintln!("{label}, image mean: z = {mean_z:.2}");
    assert!(mean_z < 4.0, "image mean off by {mean_z:.2} standard errors");
}

#[test]
fn ptracer_matches_mitsuba() {
    matches_mitsuba("ptracer", "ptracer", SPP);
}

/// Light paths through a rough glass sphere (refractions in and out, connections from inside
/// the glass) match Mitsuba's `ptracer` (`reference/ptracer-glass.xml`); with the radiance
/// factor kept at refractions (β without bs.eta², checked by hand) the image mean is off by
/// 7.2 standard errors.
#[test]
fn ptracer_through_glass_matches_mitsuba() {
    matches_mitsuba("ptracer-glass", "ptracer through glass", SPP);
}

/// Light paths connect to points of a thin lens's aperture (`reference/ptracer-thinlens.xml`:
/// diffuse objects under `ptracer.xml`'s lights, the rectangle light in view, an aperture of
/// radius 0.25 m, in focus at 3 m) and match Mitsuba's `ptracer`, at 256 spp, where the
/// images of splatted sky samples pass the rule at 0.9990 of the pixels or more (seeds 1-6).
/// Connecting every path to the aperture's centre instead (a pinhole's sharp image, checked
/// by hand) passes 0.9056 of them.
#[test]
fn ptracer_through_a_thin_lens_matches_mitsuba() {
    matches_mitsuba("ptracer-thinlens", "ptracer through a thin lens", 256);
}

#[test]
fn hidden_emitters_or_a_bounce_less_fail() {
    let job = scene_with(
        "<integer name=\"max_depth\" value=\"5\"/>",
        "<integer name=\"max_depth\" value=\"5\"/><boolean name=\"hide_emitters\" value=\"true\"/>",
    );
    // the sky seen directly is a light path of one segment, rare among particles: the
    // per-pixel rule hardly sees it go, the image mean does
    let z = common::image_mean_z(&job, SPP, "ptracer", 4096);
    eprintln!("hidden emitters, image mean: z = {z:.2}");
    assert!(z > 4.0);
    let job = scene_with(
        "<integer name=\"max_depth\" value=\"5\"/>",
        "<integer name=\"max_depth\" value=\"2\"/>",
    );
    let z = common::image_mean_z(&job, SPP, "ptracer", 4096);
    eprintln!("max_depth 2 (direct light only), image mean: z = {z:.2}");
    assert!(z > 4.0);
}

/// Light paths leaving two projectors (a textured one at an angle, a constant one with a
/// scale and a vertical field of view) through their images (`reference/ptracer-projector.xml`,
/// Mitsuba 3.9.1's Mitsuba test scene `various_emitters` has one) match Mitsuba's `ptracer`.
#[test]
fn ptracer_from_projectors_matches_mitsuba() {
    matches_mitsuba("ptracer-projector", "ptracer from projectors", SPP);
}

/// Asserts that the image means of `scene` (a reference scene whose `integrator` default
/// names it) with `ptracer` at `pt_spp` and `path` at `path_spp`, each over 8 seeds, differ by
/// less than 4 standard errors (z from the spread over the seeds).
#[track_caller]
fn assert_ptracer_renders_path(scene: &str, pt_spp: u32, path_spp: u32) {
    let mean_over_seeds = |integrator: &str, spp: u32| {
        let job = steradian_mitsuba::load_file(
            &data(scene),
            &[("integrator".to_string(), integrator.to_string())],
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let means: Vec<f64> = (0..8)
            .map(|seed| {
                let opts = RenderOptions { spp: Some(spp), seed: Some(seed), ..Default::default() };
                let img = render(&job, &opts).unwrap().image();
                img.data.iter().map(|&v| v as f64).sum::<f64>() / img.data.len() as f64
            })
            .collect();
        let n = means.len() as f64;
        let mean = means.iter().sum::<f64>() / n;
        let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (var / n).sqrt())
    };
    let (pt, pt_se) = mean_over_seeds("ptracer", pt_spp);
    let (path, path_se) = mean_over_seeds("path", path_spp);
    let z = (pt - path) / (pt_se * pt_se + path_se * path_se).sqrt();
    eprintln!("{scene}: ptracer {pt:.6} ± {pt_se:.6}, path {path:.6} ± {path_se:.6}, z = {z:.2}");
    assert!(z.abs() < 4.0, "ptracer and path differ by {z:.2} standard errors");
}

/// A BSDF that bends its normal is not symmetric in its two directions: light paths must
/// evaluate it with the direction the light goes next as the viewer's, and reach every such
/// direction (`ParticleTracer::next_direction`). A bump-mapped floor under a rectangle light
/// (`reference/ptracer-bump.xml`): the image mean of `ptracer` over 8 seeds equals `path`'s
/// within 4 standard errors. Evaluated with the light's direction as the viewer's it was
/// 1.15 % bright (z = 23.4); sampled by the BSDF alone, 0.13 % dark (z = −4.9).
#[test]
fn a_bump_mapped_floor_renders_as_path_renders_it() {
    assert_ptracer_renders_path("ptracer-bump.xml", 2048, 64);
}

/// The same through a mask over a bump-mapped BSDF (`reference/ptracer-mask-bump.xml`): the
/// mask's null lobe, which only the BSDF's own sampling reaches, keeps its weight when a
/// share of the directions is drawn uniformly. Without that (the null lobe's weight not
/// divided by the BSDF branch's probability) the image was 19 % dark (z = −51).
#[test]
fn a_masked_bump_mapped_panel_renders_as_path_renders_it() {
    assert_ptracer_renders_path("ptracer-mask-bump.xml", 128, 16);
}

/// A camera with its principal point offset (`reference/ptracer-principal-point.xml`): light
/// paths connect to the window the camera sees, so the image mean of `ptracer` over 8 seeds
/// equals `path`'s within 4 standard errors. Culled by the unshifted window, as Mitsuba 3.9.1
/// culls them, a band 0.16 of the width wide stays black and the mean is 9 % low.
#[test]
fn a_shifted_principal_point_renders_as_path_renders_it() {
    assert_ptracer_renders_path("ptracer-principal-point.xml", 256, 16);
}

/// Light paths scatter off measured materials (`reference/measured.xml`: isotropic and
/// anisotropic RGL tables, one of them two-sided) as camera paths do: the image mean of
/// `ptracer` over 8 seeds equals `path`'s within 4 standard errors.
#[test]
fn measured_materials_render_as_path_renders_them() {
    assert_ptracer_renders_path("measured.xml", 128, 4);
}

/// Light paths leaving a rotated environment map (`reference/ptracer-envmap.xml`): the image
/// mean of `ptracer` over 8 seeds equals `path`'s within 4 standard errors. Mitsuba 3.9.1's
/// `ptracer` renders this scene 38 % brighter than its `path` (24.58 against 17.78; unrotated
/// 16.88 against 16.86).
#[test]
fn a_rotated_environment_map_renders_as_path_renders_it() {
    assert_ptracer_renders_path("ptracer-envmap.xml", 512, 16);
}

#[test]
fn the_image_is_the_same_for_any_thread_count() {
    let job =
        steradian_mitsuba::load_file(&data("ptracer.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let bits = |threads| {
        let opts = RenderOptions { spp: Some(4), threads: Some(threads), ..Default::default() };
        let out = render(&job, &opts).unwrap();
        assert_eq!((out.spp, out.interrupted), (4, false));
        out.image()
            .data
            .iter()
            .chain(&out.stderr_image().data)
            .map(|v| v.to_bits())
            .collect::<Vec<_>>()
    };
    let one = bits(1);
    assert_eq!(bits(3), one);
}

#[test]
fn what_it_cannot_connect_to_is_refused() {
    let job = scene_with(
        "<sensor type=\"perspective\">\n        <float name=\"fov\" value=\"45\"/>",
        "<sensor type=\"orthographic\">",
    );
    let e = render(&job, &RenderOptions { spp: Some(1), ..Default::default() }).unwrap_err();
    assert_eq!(e, RenderError::ParticlesNeedPinhole);
    assert!(e.to_string().contains("perspective or thinlens camera only"), "{e}");
    let xml = "<scene version=\"3.0.0\"><integrator type=\"moment\"><integrator type=\"ptracer\"/></integrator></scene>";
    let e =
        steradian_mitsuba::load_string(xml, Path::new("m.xml"), Path::new("."), &[]).unwrap_err();
    assert!(e.message.contains("cannot nest"), "{e}");
}
