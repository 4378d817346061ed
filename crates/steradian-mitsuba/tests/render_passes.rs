//! The image driver's passes (`render/`): threads take tiles from one queue with
//! no barrier between passes, yet the image is the same for any thread count, and a render
//! cancelled part-way keeps exactly the passes it finished.

mod common;

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use steradian::render::Job;
use steradian::render::{render, Progress, RenderOptions, RenderOutput, SampleAllocation};

/// A 40 × 24 film (2 × 1 tiles, so each pass is split into sample ranges too) of the lit
/// corner (`common::lit_corner`), blocks overlapping across tile borders.
fn scene() -> Job {
    let path = r#"<integrator type="path"><integer name="max_depth" value="4"/><integer name="branches" value="2"/></integrator>"#;
    common::lit_corner(path, 40, 24)
}

fn pixels(out: &RenderOutput) -> Vec<f32> {
    out.film().develop().data
}

#[test]
fn the_image_does_not_depend_on_the_thread_count() {
    let s = scene();
    let run = |threads| {
        render(
            &s,
            &RenderOptions {
                spp: Some(24),
                seed: Some(3),
                threads: Some(threads),
                ..Default::default()
            },
        )
        .unwrap()
    };
    let one = run(1);
    assert!(!one.interrupted && one.spp == 24);
    let reference = pixels(&one);
    assert!(reference.iter().any(|&v| v > 0.0));
    for threads in [2, 3, 5] {
        assert_eq!(pixels(&run(threads)), reference, "{threads} threads");
    }
}

/// Cancelled after a few tiles, the render stops with whole passes only, and those passes hold
/// what an uncancelled render of that many samples holds (a tile of an unfinished pass in the
/// film would leave its pixels with other samples than the rest).
#[test]
fn a_cancelled_render_keeps_only_whole_passes() {
    let s = scene();
    for (threads, after) in [(1, 5), (2, 9), (3, 40)] {
        let cancel = AtomicBool::new(false);
        let tiles = AtomicUsize::new(0);
        let progress = |_: Progress| {
            if tiles.fetch_add(1, Ordering::Relaxed) + 1 == after {
                cancel.store(true, Ordering::Relaxed);
            }
        };
        // uniform: an adaptive render's densities depend on the spp asked for, so its first
        // passes are not a shorter render's
        let opts = RenderOptions {
            spp: Some(256),
            seed: Some(7),
            threads: Some(threads),
            cancel: Some(&cancel),
            progress: Some(&progress),
            allocation: SampleAllocation::Uniform,
            ..Default::default()
        };
        let out = render(&s, &opts).unwrap();
        assert!(out.interrupted, "{threads} threads, cancelled after {after} tiles");
        assert!((1..256).contains(&out.spp), "{threads} threads: {} spp kept", out.spp);
        let full = render(
            &s,
            &RenderOptions {
                spp: Some(out.spp),
                seed: Some(7),
                threads: Some(1),
                allocation: SampleAllocation::Uniform,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(!full.interrupted);
        // the same samples, summed in other groups: equal to float rounding
        for (a, b) in pixels(&out).iter().zip(pixels(&full)) {
            assert!((a - b).abs() <= 1e-5 * b.abs().max(1e-3), "{threads} threads: {a} vs {b}");
        }
    }
}
