//! [`render`]: a plan, a branch-count pilot where `path` leaves it open, the pass schedule,
//! worker threads that render items, and this thread merging them into passes and the passes
//! into the render's sums.

use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use super::adaptive::{self, AdaptiveReport, MIN_SPP_FOR_AUTO};
use super::block::BlockRenderer;
use super::densities::Densities;
use super::merge::{PassGate, PassMerger};
use super::options::{Plan, Progress, RenderError, RenderOptions, RenderOutput, SampleAllocation};
use super::quantity::PixelQuantity;
use super::schedule::{self, schedule};
use super::sums::RenderSums;
use super::Job;
use crate::film::ImageBlock;
use crate::integrator::{pilot, Branches, Integrator, PathTracer, Pilot, DEFAULT_BRANCHES};

/// The samples per pixel at which the passes of a render of `spp` samples with `integrator`
/// end, from 0 to `spp`: ranges, checkpoints and distributed tasks start and end on them.
pub fn pass_bounds(integrator: &Integrator, spp: u32) -> Vec<u32> {
    match integrator {
        // one whole-film pass of light paths per sample
        Integrator::ParticleTracer(_) => (0..=spp).collect(),
        _ => schedule::pass_bounds(spp),
    }
}

/// What a render will do, decided before it starts: its passes, its branch count (the
/// pilot's, which this runs where `path` leaves it open) and the header of its sums.
#[derive(Clone, Debug)]
pub struct RenderPlan {
    pub header: super::SumsHeader,
    /// [`pass_bounds`] of the render.
    pub pass_bounds: Vec<u32>,
    /// What the pilot measured, when one ran.
    pub pilot: Option<Pilot>,
    /// What the adaptive pilot found, when one ran.
    pub adaptive: Option<AdaptiveReport>,
}

/// Plans the render `opts` asks for (see [`RenderPlan`]) without rendering it (the pilots
/// run: their results are part of the plan).
pub fn plan(job: &Job, opts: &RenderOptions) -> Result<RenderPlan, RenderError> {
    let plan = Plan::new(job, opts)?;
    let pool = thread_pool(opts)?;
    let (integrator, pilot, mut header) = resolve_branches(job, &plan, opts, &pool);
    let (_, adaptive) =
        resolve_allocation(&job.scene, &integrator, &plan, opts, &pool, &|| false, &mut header)?;
    Ok(RenderPlan { header, pass_bounds: pass_bounds(&job.integrator, plan.spp), pilot, adaptive })
}

/// The adaptive pilot where the options call for one (`adaptive.rs`): the densities when the
/// render is adaptive, recorded in `header`, and what the pilot found. A resumed render
/// follows its sums.
fn resolve_allocation(
    scene: &crate::scene::Scene,
    integrator: &Integrator,
    plan: &Plan,
    opts: &RenderOptions,
    pool: &rayon::ThreadPool,
    cancelled: &(impl Fn() -> bool + Sync),
    header: &mut super::SumsHeader,
) -> Result<(Option<Densities>, Option<AdaptiveReport>), RenderError> {
    let applies = plan.quantity == PixelQuantity::Sensor
        && !plan.meter
        && integrator.aov_layers().is_empty()
        && !matches!(integrator, Integrator::ParticleTracer(_) | Integrator::Depth(_));
    let mode = match &opts.resume {
        Some(r) if r.header.allocation == 0 => SampleAllocation::Uniform,
        Some(_) => SampleAllocation::Adaptive,
        None => opts.allocation,
    };
    match mode {
        SampleAllocation::Uniform => return Ok((None, None)),
        SampleAllocation::Adaptive if !applies => {
            return Err(RenderError::BadOption {
                option: "allocation",
                reason: "adaptive applies to camera radiance images (not meters, AOV, depth \
                         or particle renders)",
            })
        }
        SampleAllocation::Auto if !applies || plan.spp < MIN_SPP_FOR_AUTO => {
            return Ok((None, None))
        }
        _ => {}
    }
    let blocks = BlockRenderer::new(scene, integrator, plan);
    let force = mode == SampleAllocation::Adaptive;
    let (densities, report) = match adaptive::pilot(&blocks, plan.spp, force, pool, cancelled) {
        Some((densities, report)) => (densities, Some(report)),
        None => (None, None),
    };
    header.allocation = densities.as_ref().map_or(0, |d| d.digest);
    Ok((densities, report))
}

fn thread_pool(opts: &RenderOptions) -> Result<rayon::ThreadPool, RenderError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build()
        .map_err(|e| RenderError::ThreadPool(e.to_string()))
}

/// The integrator with `path`'s branch count fixed (the options' or the resumed sums' count,
/// else the pilot's; surface maps estimate irradiance, whose paths keep the default count: no
/// pilot for them), the pilot that ran, and the header of the render's sums.
fn resolve_branches(
    job: &Job,
    plan: &Plan,
    opts: &RenderOptions,
    pool: &rayon::ThreadPool,
) -> (Integrator, Option<Pilot>, super::SumsHeader) {
    let (integrator, pilot) = match &job.integrator {
        Integrator::Path(p)
            if p.branches == Branches::Auto && plan.quantity == PixelQuantity::Sensor =>
        {
            let given = opts.branches.or(opts.resume.as_ref().map(|r| r.header.branches));
            let (n, pilot_run) = match given.filter(|&n| n >= 1) {
                Some(n) => (n, None),
                None => {
                    let (sensor, sampler) = (plan.sensor, &plan.sampler);
                    let (w, h) = (plan.film.width, plan.film.height);
                    let run =
                        pool.install(|| pilot(p, &job.scene, sensor, w, h, plan.spp, sampler));
                    (run.map_or(DEFAULT_BRANCHES, |p| p.branches), run)
                }
            };
            (Integrator::Path(PathTracer { branches: Branches::Fixed(n), ..p.clone() }), pilot_run)
        }
        other => (other.clone(), None),
    };
    let header =
        plan.header(branch_count(&integrator), opts.sensor.unwrap_or(0), opts.scene_digest);
    (integrator, pilot, header)
}

/// `path`'s branch count, 0 for the other integrators (as the sums' header records it).
fn branch_count(integrator: &Integrator) -> u32 {
    match integrator {
        Integrator::Path(p) => p.branches.count(),
        Integrator::VolPath(_)
        | Integrator::Direct(_)
        | Integrator::Depth(_)
        | Integrator::Moment(_)
        | Integrator::Aov(_)
        | Integrator::ParticleTracer(_) => 0,
    }
}

/// Renders the job's sensor (`opts.sensor`, the first by default): all its samples, the
/// range `opts.range`, or what `opts.resume` lacks.
pub fn render(job: &Job, opts: &RenderOptions) -> Result<RenderOutput, RenderError> {
    let plan = Plan::new(job, opts)?;
    let (scene, spp) = (&job.scene, plan.spp);
    let (width, height) = (plan.film.width, plan.film.height);
    let start = Instant::now();
    // a Ctrl-C, or the time limit: the passes finished by then are kept, the rest abandoned;
    // the time limit never leaves a render without its first pass
    let have_pass = AtomicBool::new(false);
    let out_of_time = || {
        opts.time_limit.is_some_and(|t| start.elapsed() >= t) && have_pass.load(Ordering::Relaxed)
    };
    let stopped = || opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    // the target error, checked as each pass is added
    let reached = AtomicBool::new(false);
    let cancelled = || stopped() || out_of_time() || reached.load(Ordering::Relaxed);
    let pool = thread_pool(opts)?;
    let (integrator, pilot_run, mut header) = resolve_branches(job, &plan, opts, &pool);
    let (densities, adaptive) =
        resolve_allocation(scene, &integrator, &plan, opts, &pool, &stopped, &mut header)?;
    let samples_at = |s: u32| match &densities {
        Some(d) => d.samples_at(s),
        None => width as u64 * height as u64 * s as u64,
    };

    // the range: on pass boundaries, continuing the resumed sums
    let bounds = pass_bounds(&job.integrator, spp);
    let (first, end) = match (opts.range, &opts.resume) {
        (Some(r), _) => r,
        (None, Some(sums)) => (sums.end(), spp),
        (None, None) => (0, spp),
    };
    // resumed sums of another render (another spp, seed, scene, ...) say which option differs,
    // before their range is measured against this render's passes
    if let Some(resumed) = &opts.resume {
        resumed.check_same_render(&header).map_err(RenderError::Resume)?;
    }
    if first > end || !bounds.contains(&first) || !bounds.contains(&end) {
        return Err(RenderError::BadRange { first, end, bounds });
    }
    let mut sums = match &opts.resume {
        Some(resumed) => {
            if resumed.end() != first {
                return Err(RenderError::Resume(super::SumsError::NotContiguous {
                    expected: resumed.end(),
                    got: first,
                }));
            }
            resumed.clone().on_film(&plan.film)
        }
        None => RenderSums::empty(header, &plan.film, first),
    };
    let samples_total = samples_at(end);
    let samples_done = AtomicU64::new(samples_at(first));
    let rays = AtomicU64::new(0);
    let progress = |done: u64| {
        if let Some(cb) = opts.progress {
            cb(Progress { samples_done: done, samples_total, elapsed: start.elapsed() });
        }
    };
    let mut add_pass = |pass_end: u32, pass: crate::film::Film| {
        sums.push_pass(pass_end, pass);
        have_pass.store(true, Ordering::Relaxed);
        if let Some(e) = opts.target_error {
            let (film, spp) = (sums.film(), sums.end() - sums.first());
            let done = if plan.sensor.is_meter() {
                super::target_error::reached(film, spp, e)
            } else {
                super::target_error::image_reached(film, spp, e)
            };
            if done {
                reached.store(true, Ordering::Relaxed);
            }
        }
        if let Some(cb) = opts.on_pass {
            cb(&sums);
        }
    };

    if let Integrator::ParticleTracer(tracer) = &job.integrator {
        let threads = pool.current_num_threads();
        let report = |n: u64| progress(samples_done.fetch_add(n, Ordering::Relaxed) + n);
        super::particles::render_particles(
            job,
            tracer,
            &plan,
            (first, end),
            threads,
            &cancelled,
            &report,
            &rays,
            &mut add_pass,
        );
    } else {
        let sched = schedule(width, height, spp);
        // the items of the passes in the range
        let pass_of = |bound: u32| bounds.iter().position(|&b| b == bound).expect("checked");
        let (p0, p1) = (pass_of(first), pass_of(end));
        let item_start = if p0 == 0 { 0 } else { sched.pass_ends[p0 - 1].0 };
        let item_end = if p1 == 0 { 0 } else { sched.pass_ends[p1 - 1].0 };
        let items = &sched.items[item_start..item_end];
        let pass_ends: Vec<(usize, u32)> =
            sched.pass_ends[p0..p1].iter().map(|&(e, s)| (e - item_start, s)).collect();

        let blocks = BlockRenderer {
            densities: densities.as_ref(),
            ..BlockRenderer::new(scene, &integrator, &plan)
        };
        let next = AtomicUsize::new(0);
        let gate = PassGate::new(sched.window);
        let mut merger = PassMerger::new(items.len(), pass_ends, &plan.film);
        std::thread::scope(|scope| {
            let (tx, rx) = mpsc::channel::<(usize, ImageBlock)>();
            for _ in 0..pool.current_num_threads() {
                let tx = tx.clone();
                let (next, gate, blocks) = (&next, &gate, &blocks);
                let (samples_done, cancelled, progress) = (&samples_done, &cancelled, &progress);
                let rays = &rays;
                scope.spawn(move || loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= items.len() || cancelled() {
                        break;
                    }
                    gate.wait_for(i, cancelled);
                    // an item cut short by a cancel is not sent, so its pass is never merged
                    let Some(r) = blocks.render(&items[i], cancelled) else { break };
                    let n = r.samples;
                    rays.fetch_add(r.rays, Ordering::Relaxed);
                    progress(samples_done.fetch_add(n, Ordering::Relaxed) + n);
                    if tx.send((i, r.block)).is_err() {
                        break;
                    }
                });
            }
            drop(tx);
            for (i, block) in rx {
                gate.advance(merger.add(i, block, &mut add_pass));
            }
        });
    }
    let film_spp = sums.end() - sums.first();
    Ok(RenderOutput {
        quantity: plan.quantity,
        branches: Some(branch_count(&integrator)).filter(|&n| n > 0),
        pilot: pilot_run,
        spp: film_spp,
        spp_requested: end - sums.first(),
        spp_rendered: sums.end() - first,
        dropped_samples: sums.film().dropped(),
        elapsed: start.elapsed(),
        // a cancel that came after the last tile changes nothing
        interrupted: sums.end() < end,
        time_limited: sums.end() < end && out_of_time() && !stopped(),
        target_reached: reached.load(Ordering::Relaxed),
        film_samples: samples_at(sums.end()) - samples_at(sums.first()),
        rendered_samples: samples_at(sums.end()) - samples_at(first),
        rays: rays.into_inner(),
        adaptive,
        sums,
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
    use crate::render::SampleAllocation;
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
            let other = render_with(threads);
            assert_eq!(bits(&other), bits(&one), "{threads} threads");
            // the ray queries are the samples' own, whatever thread made them
            assert_eq!(other.rays, one.rays, "{threads} threads");
        }
        // each camera sample traces its camera ray, two branches their paths and shadow rays
        let samples = one.samples_rendered();
        assert!(one.rays > 3 * samples && one.rays < 50 * samples, "{} {samples}", one.rays);
    }

    /// A camera that looks away from the plane into the empty sky makes one ray query per
    /// sample, counted exactly.
    #[test]
    fn rays_are_counted() {
        let mut job = job(Branches::Fixed(2));
        let away = Transform::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::new(0.0, 0.0, 9.0), Vec3::Y)
            .expect("a valid camera frame");
        let camera = Perspective::new(away, 0.8, 1.5, 0.01, 100.0).expect("valid camera");
        job.scene.sensors[0].kind = SensorKind::Perspective(camera);
        let out = render(&job, &RenderOptions { threads: Some(2), ..Default::default() })
            .expect("renders");
        assert_eq!(out.samples_rendered(), 24 * 16 * 9);
        assert_eq!(out.rays, out.samples_rendered());
    }

    #[test]
    fn adaptive_images_are_the_same_for_any_thread_count_and_any_split() {
        let job = job(Branches::Fixed(2));
        let opts = |threads, range| RenderOptions {
            spp: Some(40),
            threads: Some(threads),
            allocation: SampleAllocation::Adaptive,
            range,
            ..Default::default()
        };
        let one = render(&job, &opts(1, None)).expect("renders");
        let report = one.adaptive.expect("a pilot ran");
        assert!(report.adaptive && one.sums.header.allocation != 0);
        // the samples follow the densities: ⌈d·40⌉ per pixel, 40 on average
        let pixels = 24 * 16;
        assert!(one.samples() >= pixels * 40 && one.samples() < pixels * 41, "{}", one.samples());
        assert_eq!(bits(&render(&job, &opts(3, None)).expect("renders")), bits(&one));
        // two ranges joined (a distributed render: each re-runs the pilot) are the whole
        let bounds = pass_bounds(&job.integrator, 40);
        let mid = bounds[bounds.len() / 2];
        let mut first = render(&job, &opts(2, Some((0, mid)))).expect("renders").sums;
        let rest = render(&job, &opts(2, Some((mid, 40)))).expect("renders").sums;
        first.append(rest).expect("the same render");
        assert_eq!(first.image().data, one.image().data);
        // a uniform render's sums are another render's
        let uniform = RenderOptions { allocation: SampleAllocation::Uniform, ..opts(2, None) };
        let uniform = render(&job, &uniform).expect("renders");
        assert_eq!((uniform.sums.header.allocation, uniform.adaptive), (0, None));
        assert!(uniform.sums.check_same_render(&one.sums.header).is_err());
    }

    /// The mean over seeds of an adaptive render of the furnace (every pixel Le/(1 − ρ), noisy
    /// through Russian roulette, Gaussian filter: samples weighed by 1/density splat into
    /// neighbours) equals that of uniform renders within 4 standard errors of the difference,
    /// and the closed form within 0.2 % (uniform renders of this furnace read 0.05–0.1 % low
    /// with or without adaptive sampling: the reference is the uniform render).
    #[test]
    fn adaptive_renders_are_unbiased() {
        let tracer =
            PathTracer { branches: Branches::Fixed(1), rr_depth: 2, ..PathTracer::default() };
        let (le, rho) = (Spectrum::splat(1.0), Spectrum::splat(0.8));
        let mut job = crate::testkit::scenes::furnace(le, rho, tracer);
        let truth = crate::testkit::scenes::furnace_radiance(le, rho, None)[1] as f64;
        let to_world = Transform::look_at(Vec3::ZERO, Vec3::X, Vec3::Z).expect("a camera frame");
        let camera = Perspective::new(to_world, 0.8, 1.0, 0.01, 100.0).expect("valid camera");
        job.scene.sensors.push(Sensor {
            kind: SensorKind::Perspective(camera),
            film: Film::new(16, 16, GaussianFilter::default().into()).expect("valid film"),
            sampler: Sampler { kind: SamplerKind::Sobol, sample_count: 32, seed: 0 },
            id: "camera".into(),
        });
        // the image mean over seeds, and its standard error
        let mean_over_seeds = |allocation, seeds: std::ops::Range<u64>| {
            let means: Vec<f64> = seeds
                .map(|seed| {
                    let opts = RenderOptions { seed: Some(seed), allocation, ..Default::default() };
                    let out = render(&job, &opts).expect("renders");
                    let adaptive = out.adaptive.is_some_and(|a| a.adaptive);
                    assert_eq!(adaptive, allocation == SampleAllocation::Adaptive);
                    out.image().data.chunks_exact(3).map(|p| p[1] as f64).sum::<f64>() / 256.0
                })
                .collect();
            let n = means.len() as f64;
            let mean = means.iter().sum::<f64>() / n;
            let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, (var / n).sqrt())
        };
        let (a, se_a) = mean_over_seeds(SampleAllocation::Adaptive, 0..24);
        let (u, se_u) = mean_over_seeds(SampleAllocation::Uniform, 100..124);
        eprintln!("furnace: adaptive {a} ± {se_a}, uniform {u} ± {se_u}, closed form {truth}");
        let z = (a - u) / se_a.hypot(se_u);
        assert!(z.abs() < 4.0, "adaptive {a} ± {se_a} against uniform {u} ± {se_u}");
        assert!(se_a < 0.001 * truth, "the test resolves 0.1 %: {se_a}");
        assert!((a - truth).abs() < 0.002 * truth, "{a} against {truth}");
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
