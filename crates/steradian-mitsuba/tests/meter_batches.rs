//! Purpose: a meter's samples taken as randomised quasi-Monte Carlo replicates (`batch`: each
//! sample the mean of N Sobol points under a scramble of its own) keep honest error bars (the
//! spread of readings over seeds matches the reported standard errors), integrate the work
//! plane of `scenes/lighting_room.xml` with a much smaller error than independent points at
//! the same number of points, give the same reading on any thread count, and are refused
//! where they mean nothing (cameras) or are out of range; a work plane carries its own `batch`.

use std::path::Path;

use steradian::render::{render, Job, RenderError, RenderOptions};

fn room() -> Job {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/lighting_room.xml");
    steradian_mitsuba::load_file(&path, &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// Every cell's (values, standard errors), green channel, for `seed`.
fn grid(job: &Job, spp: u32, batch: u32, seed: u64, threads: usize) -> (Vec<f64>, Vec<f64>) {
    let out = render(
        job,
        &RenderOptions {
            spp: Some(spp),
            seed: Some(seed),
            batch: Some(batch),
            threads: Some(threads),
            ..Default::default()
        },
    )
    .unwrap();
    let (img, se) = (out.film().develop(), out.film().develop_stderr());
    let values = img.data.chunks_exact(3).map(|p| p[1] as f64).collect();
    let errors = se.data.chunks_exact(3).map(|p| p[1] as f64).collect();
    (values, errors)
}

/// Per cell: the spread of the readings over `seeds` and the mean reported standard error.
fn spread(job: &Job, spp: u32, batch: u32, seeds: u64) -> (Vec<f64>, Vec<f64>) {
    let runs: Vec<_> = (0..seeds).map(|s| grid(job, spp, batch, 11 + s, 2)).collect();
    let cells = runs[0].0.len();
    let n = seeds as f64;
    let sd = (0..cells)
        .map(|i| {
            let mean = runs.iter().map(|r| r.0[i]).sum::<f64>() / n;
            (runs.iter().map(|r| (r.0[i] - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt() / mean
        })
        .collect();
    let se = (0..cells)
        .map(|i| {
            let mean = runs.iter().map(|r| r.0[i]).sum::<f64>() / n;
            runs.iter().map(|r| r.1[i]).sum::<f64>() / n / mean
        })
        .collect();
    (sd, se)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[test]
fn replicates_keep_honest_errors_and_beat_independent_points() {
    let job = room();
    // 1024 points per cell either way: 1024 independent samples, or 64 replicates of 16
    let (sd1, se1) = spread(&job, 1024, 1, 8);
    let (sd16, se16) = spread(&job, 64, 16, 8);
    let honest = |sd: &[f64], se: &[f64]| median(sd.iter().zip(se).map(|(a, b)| a / b).collect());
    let (h1, h16) = (honest(&sd1, &se1), honest(&sd16, &se16));
    let (e1, e16) = (median(sd1), median(sd16));
    eprintln!("independent: spread {e1:.2e}, spread/se {h1:.2}; replicates of 16: spread {e16:.2e}, spread/se {h16:.2}");
    // the spread of 8 readings is itself uncertain (±25 % per cell); over 100 cells the
    // median ratio of an honest error bar lies well inside [0.7, 1.3]
    for h in [h1, h16] {
        assert!((0.7..1.3).contains(&h), "spread / reported error = {h:.2}");
    }
    assert!(e16 < 0.6 * e1, "replicates of 16 Sobol points: {e16:.2e} vs {e1:.2e}");
}

#[test]
fn replicates_are_the_same_on_any_thread_count() {
    let job = room();
    assert_eq!(grid(&job, 8, 16, 3, 1), grid(&job, 8, 16, 3, 2));
}

#[test]
fn batches_are_for_meters_and_in_range() {
    let job = room();
    let bad = |batch: u32, sensor: Option<usize>| {
        render(
            &job,
            &RenderOptions { spp: Some(1), batch: Some(batch), sensor, ..Default::default() },
        )
        .err()
    };
    assert!(matches!(bad(0, None), Some(RenderError::BadOption { option: "batch", .. })));
    assert!(matches!(bad(1 << 17, None), Some(RenderError::BadOption { option: "batch", .. })));
    let camera = r#"<scene version="3.0.0"><integrator type="path"/><sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor></scene>"#;
    let cam =
        steradian_mitsuba::load_string(camera, Path::new("c.xml"), Path::new("."), &[]).unwrap();
    let e =
        render(&cam, &RenderOptions { spp: Some(1), batch: Some(4), ..Default::default() }).err();
    assert!(matches!(e, Some(RenderError::BadOption { option: "batch", .. })), "{e:?}");
}

/// A work plane's own `batch` (the lighting room's is 64) applies unless the options give
/// one; it must be 1 to 65536, at the parameter.
#[test]
fn a_work_plane_carries_its_batch() {
    let job = room();
    let steradian::sensor::SensorKind::Workplane(w) = &job.scene.sensors[0].kind else {
        panic!("the room's first sensor is its work plane")
    };
    assert_eq!(w.batch, 64);
    // the scene's batch against one given: different numbers, same scene
    assert_ne!(grid(&job, 2, 1, 5, 2).0, {
        let out = render(
            &job,
            &RenderOptions { spp: Some(2), seed: Some(5), threads: Some(2), ..Default::default() },
        )
        .unwrap();
        out.film().develop().data.chunks_exact(3).map(|p| p[1] as f64).collect::<Vec<_>>()
    });
    for bad in ["0", "70000"] {
        let xml = format!("<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<sensor type=\"workplane\">\n<integer name=\"batch\" value=\"{bad}\"/>\n</sensor>\n</scene>");
        let e = steradian_mitsuba::load_string(&xml, Path::new("w.xml"), Path::new("."), &[])
            .unwrap_err();
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(4), "{e}");
        assert!(e.message.contains("batch"), "{e}");
    }
}
