//! Splitting at the first hit (`path`'s `branches`) changes the noise, never the expectation:
//! a floor lit by two disk lights, with light bouncing between floor and a wall, renders to the
//! same mean with 1 and with 3 branches; 3 branches lower the standard error of each camera
//! sample; left unset, the count comes from a pilot that splits only where it pays.

use std::path::Path;

use steradian::integrator::{Branches, Integrator, DEFAULT_BRANCHES};
use steradian::render::{render, RenderOptions};

mod common;
use common::SENSOR;

fn scene(branches: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="5"/>{branches}</integrator>
        {SENSOR}
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate y="1" angle="80"/><translate x="-2"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.2"/></bsdf></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.2"/><rotate x="1" angle="180"/><translate x="-1" z="1"/></transform>
            <emitter type="area"><rgb name="radiance" value="200"/></emitter></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate x="1" z="0.5"/></transform>
            <emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
        </scene>"#
    )
}

fn branches_param(n: i64) -> String {
    format!(r#"<integer name="branches" value="{n}"/>"#)
}

fn mean_and_error(branches: i64, seed: u64) -> (f64, f64) {
    common::mean_and_error(&scene(&branches_param(branches)), "branches.xml", seed)
}

#[test]
fn branching_keeps_the_expectation_and_lowers_the_noise() {
    let (one, s1) = mean_and_error(1, 1);
    let (three, s3) = mean_and_error(3, 2);
    let tol = 5.0 * (s1 * s1 + s3 * s3).sqrt();
    assert!(
        one > 0.0 && (one - three).abs() <= tol,
        "1 branch {one} ± {s1}, 3 branches {three} ± {s3}"
    );
    // Most of this scene's noise comes after the first hit (indirect light, and next-event
    // estimation of two lights chosen at random), so three branches must cut the standard
    // error clearly; with the branches ignored the two would agree within their own noise.
    assert!(s3 < 0.8 * s1, "standard error with 3 branches {s3}, with 1 {s1}");
}

/// Unset, `branches` is chosen by the pilot: several branches where indirect light and two
/// lights make the light after the first hit noisy; one where it has no noise at all (a point
/// light and `max_depth` 2: next-event estimation is exact and BSDF samples cannot hit a point).
#[test]
fn the_pilot_splits_only_where_it_pays() {
    let s =
        steradian_mitsuba::load_string(&scene(""), Path::new("branches.xml"), Path::new("."), &[])
            .unwrap();
    assert!(
        matches!(&s.integrator, Integrator::Path(p) if p.branches == Branches::Auto),
        "{:?}",
        s.integrator
    );
    // a 24 × 24 film: 1024 samples per pixel give the pilot 4 stratified camera samples per
    // replicate (its work is at most 1/4 of a one-branch render's)
    let out = render(&s, &RenderOptions { spp: Some(1024), ..Default::default() }).unwrap();
    let pilot = out.pilot.expect("a pilot ran");
    assert!(
        out.branches.unwrap() >= 4 && pilot.var_branch > 10.0 * pilot.var_first,
        "{:?} {pilot:?}",
        out.branches
    );

    let point = r#"<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="2"/></integrator>
        <sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film></sensor>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>
        <emitter type="point"><point name="position" x="0.5" y="0" z="1"/><rgb name="intensity" value="5"/></emitter>
        </scene>"#;
    let s =
        steradian_mitsuba::load_string(point, Path::new("point.xml"), Path::new("."), &[]).unwrap();
    let out = render(&s, &RenderOptions { spp: Some(256), ..Default::default() }).unwrap();
    let pilot = out.pilot.expect("a pilot ran");
    assert_eq!(out.branches, Some(1), "{pilot:?}");
    // every candidate count gives the same pixels: the branches add nothing but work
    assert!(
        pilot.variance.iter().all(|&v| v == pilot.variance[0])
            && pilot.var_branch.abs() <= 1e-9 * pilot.var_first,
        "{pilot:?}"
    );

    // too small a render for a pilot: the default count
    let out = render(&s, &RenderOptions { spp: Some(64), ..Default::default() }).unwrap();
    assert_eq!((out.branches, out.pilot), (Some(DEFAULT_BRANCHES), None));
}

/// The pilot takes the same pixels and numbers whatever the render's seed, so that renders
/// with different seeds are replicates of one estimator (the same count): their spread is its
/// error. The renders themselves still differ.
#[test]
fn the_pilot_is_the_same_for_every_seed() {
    let s =
        steradian_mitsuba::load_string(&scene(""), Path::new("branches.xml"), Path::new("."), &[])
            .unwrap();
    let run = |seed| {
        render(&s, &RenderOptions { spp: Some(256), seed: Some(seed), ..Default::default() })
            .unwrap()
    };
    let (a, b) = (run(1), run(2));
    assert!(a.pilot.is_some() && a.pilot == b.pilot, "{:?} {:?}", a.pilot, b.pilot);
    assert!(a.image().data != b.image().data, "seeds 1 and 2 rendered the same image");
}

#[test]
fn branches_out_of_range_are_errors_at_the_property() {
    for bad in [0, -2, 65] {
        let e = steradian_mitsuba::load_string(
            &scene(&branches_param(bad)),
            Path::new("branches.xml"),
            Path::new("."),
            &[],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("branches.xml:2:")
                && e.contains("branches must be between 1 and 64")
                && e.contains(&bad.to_string()),
            "{e}"
        );
    }
    let e = steradian_mitsuba::load_string(
        &scene(r#"<float name="branches" value="2.5"/>"#),
        Path::new("branches.xml"),
        Path::new("."),
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("branches.xml:2:") && e.contains("branches"), "{e}");
}
