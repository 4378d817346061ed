//! Renders as sums (`steradian::render::RenderSums`): any split of a render's passes into
//! ranges, rendered apart (other thread counts, through bytes, resumed), joined in range order,
//! gives the uninterrupted render's sums bit for bit; sums of another render are refused.

mod common;

use steradian::render::Job;
use steradian::render::{
    pass_bounds, plan, render, RenderError, RenderOptions, RenderSums, SumsError,
};

/// The lit corner (`common::lit_corner`), 40 × 36, with `integrator`.
fn scene(integrator: &str) -> Job {
    common::lit_corner(integrator, 40, 36)
}

const PATH: &str = r#"<integrator type="path"><integer name="max_depth" value="4"/></integrator>"#;
const PTRACER: &str =
    r#"<integrator type="ptracer"><integer name="max_depth" value="4"/></integrator>"#;

fn opts(spp: u32, threads: usize) -> RenderOptions<'static> {
    RenderOptions { spp: Some(spp), seed: Some(11), threads: Some(threads), ..Default::default() }
}

/// Every f64 of the sums, as bits.
fn bits(s: &RenderSums) -> Vec<u64> {
    let (px, aov) = s.film().sums();
    px.iter()
        .flat_map(|p| p.wl.iter().chain([&p.w]).chain(&p.wl2).chain([&p.w2]).copied())
        .chain(aov.iter().flatten().copied())
        .map(f64::to_bits)
        .collect()
}

/// The render split at `cuts` (pass boundaries), each range rendered with its own thread
/// count and, for the later ones, sent through bytes, then joined in order.
fn joined(job: &Job, spp: u32, branches: Option<u32>, cuts: &[u32]) -> RenderSums {
    let mut bounds = vec![0];
    bounds.extend_from_slice(cuts);
    bounds.push(spp);
    let mut total: Option<RenderSums> = None;
    for (k, w) in bounds.windows(2).enumerate() {
        let o = RenderOptions { range: Some((w[0], w[1])), branches, ..opts(spp, 1 + k % 3) };
        let part = render(job, &o).expect("renders").sums;
        assert_eq!((part.first(), part.end()), (w[0], w[1]));
        let part = RenderSums::from_bytes(&part.to_bytes()).expect("reads back");
        match &mut total {
            None => total = Some(part),
            Some(t) => t.append(part).expect("the next range"),
        }
    }
    total.expect("one range at least")
}

#[test]
fn ranges_joined_in_order_are_the_whole_render_bit_for_bit() {
    for (integrator, spp) in [(PATH, 64), (PTRACER, 6)] {
        let job = scene(integrator);
        let planned = plan(&job, &opts(spp, 2)).expect("plans");
        let branches = (planned.header.branches > 0).then_some(planned.header.branches);
        assert_eq!(planned.pass_bounds, pass_bounds(&job.integrator, spp));
        let whole = render(&job, &opts(spp, 2)).expect("renders");
        assert!(whole.sums.is_complete() && whole.dropped_samples == 0);
        assert!(whole.image().data.iter().any(|&v| v > 0.0), "the floor is lit");
        let b = &planned.pass_bounds;
        let n = b.len();
        for cuts in [vec![b[1]], vec![b[n / 3], b[n / 2], b[n - 2]], b[1..n - 1].to_vec()] {
            let parts = joined(&job, spp, branches, &cuts);
            assert!(parts.is_complete());
            assert_eq!(bits(&parts), bits(&whole.sums), "{integrator}: cut at {cuts:?}");
        }
    }
}

/// The same sums, checked to fail where they should: the pass structure is what makes them
/// add up, so ranges merged by plain addition of their folded films are not the render.
#[test]
fn folded_ranges_added_together_are_not_the_render() {
    let job = scene(PATH);
    let spp = 64;
    let b = pass_bounds(&job.integrator, spp);
    let whole = render(&job, &opts(spp, 1)).expect("renders").sums;
    let branches = Some(whole.header.branches);
    let (a, c) = (b[5], b[b.len() - 3]);
    let mut naive = render(&job, &RenderOptions { range: Some((0, a)), branches, ..opts(spp, 1) })
        .expect("renders")
        .sums
        .into_film();
    for r in [(a, c), (c, spp)] {
        let part = render(&job, &RenderOptions { range: Some(r), branches, ..opts(spp, 1) });
        naive.accumulate(part.expect("renders").sums.film()).expect("same film");
    }
    let naive_bits: Vec<u64> = naive.sums().0.iter().map(|p| p.wl[0].to_bits()).collect();
    let whole_bits: Vec<u64> = whole.film().sums().0.iter().map(|p| p.wl[0].to_bits()).collect();
    assert_ne!(naive_bits, whole_bits, "f64 addition would have to be associative");
}

#[test]
fn a_resumed_render_is_the_uninterrupted_render() {
    for (integrator, spp) in [(PATH, 48), (PTRACER, 5)] {
        let job = scene(integrator);
        let whole = render(&job, &opts(spp, 2)).expect("renders");
        let b = pass_bounds(&job.integrator, spp);
        for cut in [b[1], b[b.len() / 2], b[b.len() - 2]] {
            // a checkpoint: the prefix, as a file holds it
            let head = render(&job, &RenderOptions { range: Some((0, cut)), ..opts(spp, 1) });
            let head = RenderSums::from_bytes(&head.expect("renders").sums.to_bytes()).unwrap();
            let out = render(&job, &RenderOptions { resume: Some(head), ..opts(spp, 3) });
            let out = out.expect("resumes");
            assert_eq!((out.spp, out.spp_rendered, out.interrupted), (spp, spp - cut, false));
            assert_eq!(bits(&out.sums), bits(&whole.sums), "{integrator}: resumed at {cut}");
        }
    }
}

#[test]
fn sums_of_another_render_or_range_are_refused() {
    let job = scene(PATH);
    let spp = 32;
    let b = pass_bounds(&job.integrator, spp);
    let head = render(&job, &RenderOptions { range: Some((0, b[3])), ..opts(spp, 1) })
        .expect("renders")
        .sums;
    let refused = |o: RenderOptions| render(&job, &o).expect_err("refused");
    // another seed, spp, digest
    for (o, what) in [
        (RenderOptions { seed: Some(12), ..opts(spp, 1) }, "seed"),
        (opts(64, 1), "spp"),
        (RenderOptions { scene_digest: 7, ..opts(spp, 1) }, "scene"),
    ] {
        let o = RenderOptions { resume: Some(head.clone()), ..o };
        match refused(o) {
            RenderError::Resume(SumsError::Mismatch(m)) => assert!(m.starts_with(what), "{m}"),
            e => panic!("{what}: {e}"),
        }
    }
    // a range that does not continue the sums
    let o = RenderOptions { resume: Some(head.clone()), range: Some((b[4], spp)), ..opts(spp, 1) };
    assert!(matches!(refused(o), RenderError::Resume(SumsError::NotContiguous { .. })));
    // a range off the pass boundaries
    let o = RenderOptions { range: Some((0, 2)), ..opts(64, 1) };
    let e = refused(o);
    assert!(matches!(e, RenderError::BadRange { .. }), "{e}");
    assert!(e.to_string().contains("pass boundaries (0, 1, 3, 5, "), "{e}");
    // appending out of order
    let tail = render(&job, &RenderOptions { range: Some((b[4], spp)), ..opts(spp, 1) });
    let mut h = head.clone();
    let e = h.append(tail.expect("renders").sums).expect_err("a gap");
    assert_eq!(e, SumsError::NotContiguous { expected: b[3], got: b[4] });
}

#[test]
fn damaged_or_foreign_records_are_refused() {
    let job = scene(PATH);
    let sums = render(&job, &opts(8, 1)).expect("renders").sums;
    let bytes = sums.to_bytes();
    assert_eq!(bits(&RenderSums::from_bytes(&bytes).expect("reads")), bits(&sums));
    let e = RenderSums::from_bytes(&bytes[..bytes.len() - 1]).expect_err("truncated");
    assert!(e.to_string().contains("truncated"), "{e}");
    assert!(matches!(RenderSums::from_bytes(b"not sums at all"), Err(SumsError::Malformed(_))));
    // another version: the version string follows the mark and the format number
    let mut other = bytes.clone();
    let at = 8 + 4 + 4;
    other[at] = b'9';
    assert!(matches!(RenderSums::from_bytes(&other), Err(SumsError::Version(_))));
}

/// A render with a time limit stops taking passes once the time is spent: it returns soon,
/// with whole passes only, and they are exactly the render's first passes.
#[test]
fn a_time_limited_render_holds_the_first_whole_passes() {
    use std::time::{Duration, Instant};
    for (integrator, spp) in [(PATH, 1 << 20), (PTRACER, 1 << 16)] {
        let job = scene(integrator);
        let limit = Duration::from_millis(300);
        let t = Instant::now();
        let o = RenderOptions { time_limit: Some(limit), ..opts(spp, 2) };
        let out = render(&job, &o).expect("renders");
        let took = t.elapsed();
        // the pilot, then at most the passes under way at the limit (each far below 10 s)
        assert!(took < Duration::from_secs(20), "{integrator}: took {took:?}");
        assert!(out.time_limited && out.interrupted, "{integrator}");
        assert!(out.spp > 0 && out.spp < spp, "{integrator}: {} spp", out.spp);
        assert!(pass_bounds(&job.integrator, spp).contains(&out.spp));
        let branches = Some(out.sums.header.branches);
        let head =
            render(&job, &RenderOptions { range: Some((0, out.spp)), branches, ..opts(spp, 1) });
        assert_eq!(bits(&head.expect("renders").sums), bits(&out.sums), "{integrator}");
    }
    let e = render(&scene(PATH), &RenderOptions { time_limit: Some(Duration::ZERO), ..opts(4, 1) });
    assert!(matches!(e, Err(RenderError::BadOption { option: "time-limit", .. })));
}
