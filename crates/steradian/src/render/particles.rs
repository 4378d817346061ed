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

use glam::UVec2;

use super::options::Plan;
use super::Job;
use crate::film::{Film, SplatBlock};
use crate::integrator::ParticleTracer;
use crate::scene::rays_traced_on_this_thread;

/// Renders the passes `first..end` of `plan` with the particle tracer `tracer` on `threads`
/// worker threads, handing each finished pass, in order, to `pass_done` (as a film holding
/// one unit-weight sample per pixel); `report` counts light paths as passes finish and `rays`
/// the ray queries they made; once `cancelled`, the passes under way are abandoned.
pub(super) fn render_particles(
    job: &Job,
    tracer: &ParticleTracer,
    plan: &Plan,
    (first, end): (u32, u32),
    threads: usize,
    cancelled: &(dyn Fn() -> bool + Sync),
    report: &(dyn Fn(u64) + Sync),
    rays: &AtomicU64,
    pass_done: &mut dyn FnMut(u32, Film),
) {
    let (scene, sensor, sampler) = (&job.scene, plan.sensor, plan.sampler);
    let mut template = plan.film.clone();
    template.clear();
    let (width, height, filter) = (template.width, template.height, template.filter);
    // one light path per pixel of the camera's full frame, a crop window's included (as
    // Mitsuba traces them): each pixel of the window is then as noisy as in the full render
    let frame = template.window().full_size();
    let paths_per_pass = frame.x as u64 * frame.y as u64;
    let next = AtomicUsize::new(first as usize);
    let mut merged = first;
    std::thread::scope(|scope| {
        let (tx, rx) = mpsc::channel::<(u32, SplatBlock)>();
        for _ in 0..threads.max(1) {
            let tx = tx.clone();
            let next = &next;
            scope.spawn(move || loop {
                let pass = next.fetch_add(1, Ordering::Relaxed) as u32;
                if pass >= end || cancelled() {
                    break;
                }
                let mut block = SplatBlock::new(width, height, filter);
                let rays_before = rays_traced_on_this_thread();
                for y in 0..frame.y {
                    if cancelled() {
                        return;
                    }
                    for x in 0..frame.x {
                        let mut s = sampler.pixel_sampler(UVec2::new(x, y), frame.x, pass);
                        tracer.trace(scene, sensor, &mut s, &mut block);
                    }
                }
                rays.fetch_add(rays_traced_on_this_thread() - rays_before, Ordering::Relaxed);
                report(paths_per_pass);
                if tx.send((pass, block)).is_err() {
                    break;
                }
            });
        }
        drop(tx);
        // passes join the sums in order; later ones wait here for the earlier
        let mut waiting = BTreeMap::new();
        for (pass, block) in rx {
            waiting.insert(pass, block);
            while let Some(block) = waiting.remove(&merged) {
                let mut film = template.clone();
                film.add_pass(&block);
                merged += 1;
                pass_done(merged, film);
            }
        }
    });
}
