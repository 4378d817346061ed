//! The image driver's passes (`render/`): threads take tiles from one queue with
//! no barrier between passes, yet the image is the same for any thread count, and a render
//! cancelled part-way keeps exactly the passes it finished.

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use steradian::render::Job;
use steradian::render::{render, Progress, RenderOptions, RenderOutput};

/// A 40 × 24 film (2 × 1 tiles, so each pass is split into sample ranges too) of a floor and a
/// wall lit by a disk, with a gaussian filter (blocks overlap across tile borders).
fn scene() -> Job {
    let xml = r#"<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="4"/><integer name="branches" value="2"/></integrator>
        <sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="24"/></film></sensor>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate y="1" angle="80"/><translate x="-2"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.2"/></bsdf></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate x="1" z="1"/></transform>
            <emitter type="area"><rgb name="radiance" value="20"/></emitter></shape>
        </scene>"#;
    steradian_mitsuba::load_string(xml, Path::new("passes.xml"), Path::new("."), &[]).unwrap()
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
        let opts = RenderOptions {
            spp: Some(256),
            seed: Some(7),
            threads: Some(threads),
            cancel: Some(&cancel),
            progress: Some(&progress),
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
