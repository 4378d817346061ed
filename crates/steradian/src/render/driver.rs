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

    if let Integrator::ParticleTracer(tracer) = &job.integrator {
        let threads = pool.current_num_threads();
        return Ok(super::particles::render_particles(job, tracer, plan, opts, threads));
    }

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
            Integrator::Direct(_)
            | Integrator::Depth(_)
            | Integrator::Moment(_)
            | Integrator::Aov(_)
            | Integrator::ParticleTracer(_) => None,
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

#[cfg(test)]
mod tests {
    use std::sync::atomic::AtomicBool;

    use glam::Vec3;

    use super::*;
    use crate::film::{Film, GaussianFilter};
    use crate::geometry::Transform;
    use crate::integrator::PathTracer;
    use crate::sampling::{Sampler, SamplerKind};
    use crate::sensor::{Perspective, Sensor, SensorKind};
    use crate::testkit::scenes::lit_plane;
    use crate::Spectrum;

    /// The testkit's lit plane seen from above by a 24×16 camera (Gaussian filter: samples
    /// splat into neighbouring tiles, so merge order matters to the sums).
    fn job(branches: Branches) -> Job {
        let tracer = PathTracer { branches, ..PathTracer::default() };
        let mut job = lit_plane(Spectrum::splat(0.5), Spectrum::splat(3.0), Vec3::Z, 4.0, tracer);
        let to_world = Transform::look_at(Vec3::new(0.0, -1.0, 3.0), Vec3::ZERO, Vec3::Y)
            .expect("a valid camera frame");
        let camera = Perspective::new(to_world, 0.8, 1.5, 0.01, 100.0).expect("valid camera");
        job.scene.sensors.push(Sensor {
            kind: SensorKind::Perspective(camera),
            film: Film::new(24, 16, GaussianFilter::default().into()).expect("valid film"),
            sampler: Sampler { kind: SamplerKind::Sobol, sample_count: 9, seed: 4 },
            id: "camera".into(),
        });
        job
    }

    fn bits(out: &RenderOutput) -> Vec<u32> {
        out.image().data.iter().chain(&out.stderr_image().data).map(|v| v.to_bits()).collect()
    }

    #[test]
    fn the_image_is_the_same_for_any_thread_count() {
        let job = job(Branches::Fixed(2));
        let render_with = |threads| {
            render(&job, &RenderOptions { threads: Some(threads), ..Default::default() })
                .expect("renders")
        };
        let one = render_with(1);
        assert_eq!((one.spp, one.dropped_samples, one.interrupted), (9, 0, false));
        assert!(one.image().data.iter().any(|&v| v > 0.0), "the plane is lit");
        for threads in [2, 3, 5] {
            assert_eq!(bits(&render_with(threads)), bits(&one), "{threads} threads");
        }
    }

    #[test]
    fn a_cancel_keeps_only_complete_passes() {
        let job = job(Branches::Fixed(1));
        let cancel = AtomicBool::new(false);
        // cancel as soon as the first item is done: passes of 1, 2, … samples, so the film
        // holds 0 or 1 sample per pixel (the first pass) whatever the threads did meanwhile
        let stop = |_: Progress| cancel.store(true, Ordering::Relaxed);
        let opts = RenderOptions {
            spp: Some(64),
            threads: Some(2),
            cancel: Some(&cancel),
            progress: Some(&stop),
            ..Default::default()
        };
        let out = render(&job, &opts).expect("renders");
        assert!(out.interrupted && out.spp <= 1, "spp {}", out.spp);
        // what it holds is the uninterrupted render's first pass, bit for bit
        if out.spp == 1 {
            let first = render(&job, &RenderOptions { spp: Some(1), ..Default::default() });
            assert_eq!(out.image().data, first.expect("renders").image().data);
        }
    }

    #[test]
    fn options_are_checked_against_the_scene() {
        let job = job(Branches::Auto);
        let err = |opts: RenderOptions| render(&job, &opts).expect_err("an invalid option");
        assert_eq!(
            err(RenderOptions { spp: Some(0), ..Default::default() }),
            RenderError::BadOption { option: "spp", reason: "must be at least 1" }
        );
        assert_eq!(
            err(RenderOptions { threads: Some(0), ..Default::default() }),
            RenderError::BadOption { option: "threads", reason: "must be at least 1" }
        );
        assert_eq!(
            err(RenderOptions { sensor: Some(1), ..Default::default() }),
            RenderError::BadSensor(1)
        );
        // the pilot chooses a branch count (at 400 spp its work fits in its budget); a surface
        // map uses the default count, without a pilot
        let out = render(&job, &RenderOptions { spp: Some(400), ..Default::default() });
        let out = out.expect("renders");
        assert!(out.pilot.is_some() && out.branches == out.pilot.map(|p| p.branches));
        let map =
            RenderOptions { quantity: PixelQuantity::SurfaceIrradiance, ..Default::default() };
        let out = render(&job, &map).expect("renders");
        assert_eq!((out.pilot, out.branches), (None, Some(DEFAULT_BRANCHES)));
    }
}
