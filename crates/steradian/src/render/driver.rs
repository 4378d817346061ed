//! [`render`]: a plan, a branch-count pilot where `path` leaves it open, the pass schedule,
//! worker threads that render items, and this thread merging them into the film.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use super::block::BlockRenderer;
use super::merge::{PassGate, PassMerger};
use super::options::{PixelQuantity, Plan, Progress, RenderError, RenderOptions, RenderOutput};
use super::schedule::schedule;
use super::Job;
use crate::film::ImageBlock;
use crate::integrator::{pilot, Branches, Integrator, PathTracer, DEFAULT_BRANCHES};

/// Renders the job's sensor (`opts.sensor`, the first by default) into a film.
pub fn render(job: &Job, opts: &RenderOptions) -> Result<RenderOutput, RenderError> {
    let plan = Plan::new(job, opts)?;
    let (scene, sensor, spp, quantity) = (&job.scene, plan.sensor, plan.spp, plan.quantity);
    let (width, height) = (plan.film.width, plan.film.height);
    let start = Instant::now();
    let cancelled = || opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed));

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build()
        .map_err(|e| RenderError::ThreadPool(e.to_string()))?;

    // `path` with `branches` unset: a pilot picks the count (integrator/branching.rs). Surface
    // maps estimate irradiance, whose paths keep the default count: no pilot for them.
    let mut pilot_run = None;
    let integrator = match &job.integrator {
        Integrator::Path(p)
            if p.branches == Branches::Auto && quantity == PixelQuantity::Sensor =>
        {
            pilot_run = pool.install(|| pilot(p, scene, sensor, width, height, spp, &plan.sampler));
            let n = pilot_run.map_or(DEFAULT_BRANCHES, |p| p.branches);
            Integrator::Path(PathTracer { branches: Branches::Fixed(n), ..p.clone() })
        }
        other => other.clone(),
    };

    let sched = schedule(width, height, spp);
    let blocks = BlockRenderer::new(scene, &integrator, &plan);
    let mut film = plan.film;
    let samples_total = width as u64 * height as u64 * spp as u64;
    let samples_done = AtomicU64::new(0);
    let dropped = AtomicU64::new(0);
    let next = AtomicUsize::new(0);
    let gate = PassGate::new(sched.window);
    let mut merger = PassMerger::new(sched.items.len(), sched.pass_ends.clone());
    std::thread::scope(|scope| {
        let (tx, rx) = mpsc::channel::<(usize, ImageBlock)>();
        for _ in 0..pool.current_num_threads() {
            let tx = tx.clone();
            let (next, gate, items, blocks) = (&next, &gate, &sched.items, &blocks);
            let (samples_done, dropped, cancelled) = (&samples_done, &dropped, &cancelled);
            scope.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= items.len() || cancelled() {
                    break;
                }
                gate.wait_for(i, cancelled);
                // an item cut short by a cancel is not sent, so its pass is never merged
                let Some(r) = blocks.render(&items[i], cancelled) else { break };
                if r.dropped > 0 {
                    dropped.fetch_add(r.dropped, Ordering::Relaxed);
                }
                let item = &items[i];
                let n = item.size.x as u64 * item.size.y as u64 * (item.s1 - item.s0) as u64;
                let done = samples_done.fetch_add(n, Ordering::Relaxed) + n;
                if let Some(cb) = opts.progress {
                    cb(Progress { samples_done: done, samples_total, elapsed: start.elapsed() });
                }
                if tx.send((i, r.block)).is_err() {
                    break;
                }
            });
        }
        drop(tx);
        for (i, block) in rx {
            gate.advance(merger.add(i, block, &mut film));
        }
    });
    let spp_done = merger.spp_done();
    Ok(RenderOutput {
        film,
        quantity,
        branches: match &integrator {
            Integrator::Path(p) => Some(p.branches.count()),
            Integrator::Direct(_) => None,
        },
        pilot: pilot_run,
        spp: spp_done,
        spp_requested: spp,
        dropped_samples: dropped.load(Ordering::Relaxed),
        elapsed: start.elapsed(),
        // a cancel that came after the last tile changes nothing
        interrupted: spp_done < spp,
    })
}
