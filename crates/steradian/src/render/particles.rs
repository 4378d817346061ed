//! Rendering with the particle tracer (`ptracer`): passes of light paths splatted over the
//! whole film.
//!
//! A render of N samples per pixel on a W × H film is N passes of W·H light paths. Path k of
//! pass s draws its random numbers as the camera sample s of "pixel" (k mod W, k div W) would,
//! so the image depends only on the scene, spp and seed. Passes render on all cores, each into
//! its own whole-film [`SplatBlock`], and are added to the film in pass order (a pass is one
//! unit-weight sample per pixel: [`Film::add_pass`]), so the image is bit-for-bit the same for
//! any thread count and a stopped render holds only complete passes.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use glam::UVec2;

use super::options::{Plan, Progress, RenderOptions, RenderOutput};
use super::Job;
use crate::film::{Film, SplatBlock};
use crate::integrator::ParticleTracer;

/// Renders `plan` with the particle tracer `tracer` on `threads` worker threads.
pub(super) fn render_particles(
    job: &Job,
    tracer: &ParticleTracer,
    plan: Plan,
    opts: &RenderOptions,
    threads: usize,
) -> RenderOutput {
    let start = Instant::now();
    let (scene, sensor, sampler, spp) = (&job.scene, plan.sensor, plan.sampler, plan.spp);
    let mut film: Film = plan.film;
    let (width, height, filter) = (film.width, film.height, film.filter);
    let cancelled = || opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let paths_per_pass = width as u64 * height as u64;
    let samples_total = paths_per_pass * spp as u64;
    let (next, samples_done) = (AtomicUsize::new(0), AtomicU64::new(0));
    let mut merged = 0u32;
    std::thread::scope(|scope| {
        let (tx, rx) = mpsc::channel::<(u32, SplatBlock)>();
        for _ in 0..threads.max(1) {
            let tx = tx.clone();
            let (next, samples_done, cancelled) = (&next, &samples_done, &cancelled);
            scope.spawn(move || loop {
                let pass = next.fetch_add(1, Ordering::Relaxed) as u32;
                if pass >= spp || cancelled() {
                    break;
                }
                let mut block = SplatBlock::new(width, height, filter);
                for y in 0..height {
                    if cancelled() {
                        return;
                    }
                    for x in 0..width {
                        let mut s = sampler.pixel_sampler(UVec2::new(x, y), width, pass);
                        tracer.trace(scene, sensor, &mut s, &mut block);
                    }
                }
                let done =
                    samples_done.fetch_add(paths_per_pass, Ordering::Relaxed) + paths_per_pass;
                if let Some(cb) = opts.progress {
                    cb(Progress { samples_done: done, samples_total, elapsed: start.elapsed() });
                }
                if tx.send((pass, block)).is_err() {
                    break;
                }
            });
        }
        drop(tx);
        // passes join the film in order; later ones wait here for the earlier
        let mut waiting = BTreeMap::new();
        for (pass, block) in rx {
            waiting.insert(pass, block);
            while let Some(block) = waiting.remove(&merged) {
                film.add_pass(&block);
                merged += 1;
            }
        }
    });
    let dropped = film.dropped();
    RenderOutput {
        film,
        quantity: plan.quantity,
        branches: None,
        pilot: None,
        spp: merged,
        spp_requested: spp,
        dropped_samples: dropped,
        elapsed: start.elapsed(),
        interrupted: merged < spp,
    }
}
