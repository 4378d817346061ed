//! The image driver: splits the film into tiles, renders them on all cores, and splats every
//! sample into the film through the reconstruction filter.
//!
//! Work is organised in *passes*: each pass adds the same number of samples to every pixel,
//! and the film only ever holds complete passes. Stopping early (Ctrl-C) therefore still
//! yields an image with the same sample count everywhere. Threads take work items (a tile and
//! a range of its samples) from one queue in pass order, without waiting for each other at the
//! end of a pass (but at most one pass ahead of the first unmerged one); the calling thread
//! merges a pass into the film once all its items are in.
//! Every sample's random numbers are addressed by (pixel, sample index, seed), and items are
//! merged in a fixed order, so the image is bit-for-bit the same for any thread count.

use std::fmt;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use glam::{UVec2, Vec2};

use crate::film::{Film, ImageBlock};
use crate::geometry::Ray;
use crate::integrator::branching::{self, Pilot};
use crate::integrator::{estimate_irradiance, Branches, Integrator, PathTracer, DEFAULT_BRANCHES};
use crate::sampling::{PixelSampler, SamplerKind};
use crate::scene::Scene;
use crate::sensor::Sensor;
use crate::Spectrum;

/// Samples `s0..s1` of every pixel of the tile at `offset` of `size` pixels.
#[derive(Clone, Copy, Debug)]
struct WorkItem {
    offset: UVec2,
    size: UVec2,
    s0: u32,
    s1: u32,
}

/// Side of a square render tile, pixels.
const TILE: u32 = 32;
/// Passes grow from 1 sample per pixel by doubling up to this fraction of the total, so that
/// an early Ctrl-C still finds a finished pass and later passes merge rarely.
const PASS_FRACTION: u32 = 8;
/// Work items per pass to aim for when the film has few tiles.
const WORK_ITEMS_PER_PASS: u32 = 64;

/// How far a render has come.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Samples finished so far (all pixels).
    pub samples_done: u64,
    pub samples_total: u64,
    pub elapsed: Duration,
}

/// What each pixel holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelQuantity {
    /// What the sensor measures (radiance for cameras, the meter's quantity for meters).
    #[default]
    Sensor,
    /// The irradiance (W/m²) on the surface point each camera pixel sees, on the side facing
    /// the camera (0 where the ray escapes): an irradiance map.
    SurfaceIrradiance,
}

/// Options of one render.
#[derive(Default)]
pub struct RenderOptions<'a> {
    /// Samples per pixel; `None` = the sensor's sampler's `sample_count`.
    pub spp: Option<u32>,
    /// Seed; `None` = the sensor's sampler's seed.
    pub seed: Option<u64>,
    /// Sample generator; `None` = Sobol points for cameras, i.i.d. numbers for meters (whose
    /// error bars assume independent samples).
    pub sampler: Option<SamplerKind>,
    /// Worker threads; `None` = all cores.
    pub threads: Option<usize>,
    /// Which sensor; `None` = the first.
    pub sensor: Option<usize>,
    /// Set to stop early; the passes finished so far are kept.
    pub cancel: Option<&'a AtomicBool>,
    /// What each pixel holds.
    pub quantity: PixelQuantity,
    /// Called from worker threads as tiles finish.
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
}

/// The result of a render.
#[derive(Debug)]
pub struct RenderOutput {
    pub film: Film,
    /// Paths continued from each camera ray's first hit (`path` only).
    pub branches: Option<u32>,
    /// What the pilot that chose `branches` measured, when one ran.
    pub pilot: Option<Pilot>,
    /// Samples per pixel actually in the film.
    pub spp: u32,
    pub spp_requested: u32,
    /// Samples whose value was NaN or infinite: dropped, never splatted.
    pub dropped_samples: u64,
    pub elapsed: Duration,
    pub interrupted: bool,
}

impl RenderOutput {
    /// Samples in the film (pixels × spp).
    pub fn samples(&self) -> u64 {
        self.film.width as u64 * self.film.height as u64 * self.spp as u64
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum RenderError {
    NoSensor,
    BadSensor(usize),
    /// An irradiance map needs a camera.
    NotACamera,
    ThreadPool(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::NoSensor => write!(f, "the scene has no sensor to render"),
            RenderError::BadSensor(i) => write!(f, "the scene has no sensor number {i}"),
            RenderError::NotACamera => write!(
                f,
                "irradiance maps need a camera sensor (perspective or thinlens), not a meter"
            ),
            RenderError::ThreadPool(e) => write!(f, "could not start worker threads: {e}"),
        }
    }
}

impl std::error::Error for RenderError {}

/// Renders the scene's sensor into a film.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Result<RenderOutput, RenderError> {
    let sensor_index = opts.sensor.unwrap_or(0);
    if scene.sensors.is_empty() {
        return Err(RenderError::NoSensor);
    }
    let sensor = scene.sensors.get(sensor_index).ok_or(RenderError::BadSensor(sensor_index))?;
    let mut sampler = sensor.sampler;
    if let Some(spp) = opts.spp {
        sampler.sample_count = spp;
    }
    if let Some(seed) = opts.seed {
        sampler.seed = seed;
    }
    let spp = sampler.sample_count;
    let meter = sensor.is_meter();
    sampler.kind =
        opts.sampler.unwrap_or(if meter { SamplerKind::Independent } else { sampler.kind });
    if opts.quantity == PixelQuantity::SurfaceIrradiance && meter {
        return Err(RenderError::NotACamera);
    }
    let mut film = sensor.film.clone();
    film.clear();
    let (width, height) = (film.width, film.height);
    let tiles: Vec<(UVec2, UVec2)> = (0..height.div_ceil(TILE))
        .flat_map(|ty| (0..width.div_ceil(TILE)).map(move |tx| (tx, ty)))
        .map(|(tx, ty)| {
            let o = UVec2::new(tx * TILE, ty * TILE);
            (o, UVec2::new(TILE.min(width - o.x), TILE.min(height - o.y)))
        })
        .collect();

    // pass boundaries: 1, 2, 4, … samples per pixel, at most ⌈spp/8⌉ per pass; they depend on
    // spp only, so images are reproducible
    let mut bounds = vec![0u32];
    let mut size = 1u32;
    while *bounds.last().unwrap() < spp {
        let next = (bounds.last().unwrap() + size).min(spp);
        bounds.push(next);
        size = (size * 2).min(spp.div_ceil(PASS_FRACTION).max(1));
    }
    let start = Instant::now();
    let samples_total = width as u64 * height as u64 * spp as u64;
    let samples_done = AtomicU64::new(0);
    let dropped = AtomicU64::new(0);
    let cancelled = || opts.cancel.is_some_and(|c| c.load(Ordering::Relaxed));

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build()
        .map_err(|e| RenderError::ThreadPool(e.to_string()))?;

    // `path` with `branches` unset: a pilot picks the count (branching.rs)
    let mut pilot = None;
    let integrator = match &scene.integrator {
        Integrator::Path(p) if p.branches == Branches::Auto => {
            pilot =
                pool.install(|| branching::pilot(p, scene, sensor, width, height, spp, &sampler));
            let n = pilot.map_or(DEFAULT_BRANCHES, |p| p.branches);
            Integrator::Path(PathTracer { branches: Branches::Fixed(n), ..p.clone() })
        }
        other => other.clone(),
    };

    // Work items, pass by pass: tiles, each split into sample ranges when the film has few
    // tiles (a 1×1 meter film would otherwise keep one core busy). The split depends on the
    // film and the pass only, never on the thread count, so images are reproducible.
    let mut items: Vec<WorkItem> = Vec::new();
    let mut pass_ends = Vec::new();
    // the most items in one pass
    let mut window = 1;
    for pass in bounds.windows(2) {
        // samples [first, last) of every pixel
        let (first, last) = (pass[0], pass[1]);
        let pass_start = items.len();
        let per_pass = last - first;
        let chunks = (WORK_ITEMS_PER_PASS.div_ceil(tiles.len() as u32)).clamp(1, per_pass);
        for &(offset, size) in &tiles {
            for c in 0..chunks {
                let s0 = first + (per_pass as u64 * c as u64 / chunks as u64) as u32;
                let s1 = first + (per_pass as u64 * (c as u64 + 1) / chunks as u64) as u32;
                if s1 > s0 {
                    items.push(WorkItem { offset, size, s0, s1 });
                }
            }
        }
        pass_ends.push((items.len(), last));
        window = window.max(items.len() - pass_start);
    }

    // blocks as `Film::create_block` makes them (the film itself is borrowed for merging)
    let filter = film.filter;
    let render_item = |item: &WorkItem| -> Option<ImageBlock> {
        let WorkItem { offset, size, s0, s1 } = *item;
        let mut block = ImageBlock::with_clip(offset, size, &filter, [width as i64, height as i64]);
        let mut bad = 0u64;
        for y in offset.y..offset.y + size.y {
            if cancelled() {
                return None;
            }
            for x in offset.x..offset.x + size.x {
                let pixel = UVec2::new(x, y);
                for index in s0..s1 {
                    let mut s = sampler.pixel_sampler(pixel, width, index);
                    let (mut pos, film_uv) = film_position(pixel, &mut s, width, height);
                    let l = match opts.quantity {
                        PixelQuantity::Sensor => {
                            sensor.measure(scene, &integrator, film_uv, &mut s)
                        }
                        PixelQuantity::SurfaceIrradiance => {
                            surface_irradiance(scene, sensor, film_uv, &mut s)
                        }
                    };
                    if meter {
                        // meters ignore the film position: equal weights
                        pos = pixel.as_vec2() + Vec2::splat(0.5);
                    }
                    if l.is_finite() {
                        block.put(pos, l);
                    } else {
                        bad += 1;
                    }
                }
            }
        }
        if bad > 0 {
            dropped.fetch_add(bad, Ordering::Relaxed);
        }
        let n = size.x as u64 * size.y as u64 * (s1 - s0) as u64;
        let done = samples_done.fetch_add(n, Ordering::Relaxed) + n;
        if let Some(cb) = opts.progress {
            cb(Progress { samples_done: done, samples_total, elapsed: start.elapsed() });
        }
        Some(block)
    };
    // One tile at a time from a shared counter, in pass order, with no barrier between
    // passes: a thread that finishes its last tile of a pass starts on the next pass while
    // the others finish theirs (a barrier per pass idled 4 % of the cores on a 64-spp Cornell
    // box). This thread merges each pass into the film, in item order, once all its tiles are
    // in, so the film still only ever holds complete passes. Items are taken at most `window`
    // (the largest pass) ahead of the first unmerged one, so blocks waiting for a slow tile of
    // an earlier pass hold at most about two passes' worth of memory, as the barrier per pass
    // held one.
    let merged_items = AtomicUsize::new(0);
    let next = AtomicUsize::new(0);
    let mut spp_done = 0u32;
    let mut film_blocks: Vec<Option<ImageBlock>> = (0..items.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let (tx, rx) = mpsc::channel::<(usize, ImageBlock)>();
        for _ in 0..pool.current_num_threads() {
            let (tx, next, merged_items, items, render_item) =
                (tx.clone(), &next, &merged_items, &items, &render_item);
            scope.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= items.len() || cancelled() {
                    break;
                }
                // the items of the first unmerged pass are never held back, so this ends
                while i >= merged_items.load(Ordering::Acquire) + window && !cancelled() {
                    std::thread::sleep(Duration::from_micros(100));
                }
                // an item cut short by a cancel is not sent, so its pass is never merged
                let Some(block) = render_item(&items[i]) else { break };
                if tx.send((i, block)).is_err() {
                    break;
                }
            });
        }
        drop(tx);
        let (mut pass, mut merged) = (0usize, 0usize);
        for (i, block) in rx {
            film_blocks[i] = Some(block);
            while pass < pass_ends.len() {
                let (end, last) = pass_ends[pass];
                if film_blocks[merged..end].iter().any(Option::is_none) {
                    break;
                }
                for b in film_blocks[merged..end].iter_mut() {
                    film.merge(&b.take().expect("checked above"));
                }
                (merged, spp_done, pass) = (end, last, pass + 1);
                merged_items.store(merged, Ordering::Release);
            }
        }
    });
    // a cancel that came after the last tile changes nothing
    let interrupted = spp_done < spp;
    let branches = match &integrator {
        Integrator::Path(p) => Some(p.branches.count()),
        Integrator::Direct(_) => None,
    };
    Ok(RenderOutput {
        film,
        branches,
        pilot,
        spp: spp_done,
        spp_requested: spp,
        dropped_samples: dropped.load(Ordering::Relaxed),
        elapsed: start.elapsed(),
        interrupted,
    })
}

/// Where on the film a camera sample lands: its pixel plus the sampler's first 2-D draw, in
/// pixels (where the film splats it), and the same as a fraction of the film (`film_uv`, what
/// sensors take). The pilot (`branching.rs`) starts its samples here too.
#[inline]
pub(super) fn film_position(
    pixel: UVec2,
    s: &mut PixelSampler,
    width: u32,
    height: u32,
) -> (Vec2, Vec2) {
    let pos = pixel.as_vec2() + s.next_2d();
    (pos, pos / Vec2::new(width as f32, height as f32))
}

/// Irradiance on the surface seen through film position `film_uv`, on the camera's side.
fn surface_irradiance(
    scene: &Scene,
    sensor: &Sensor,
    film_uv: Vec2,
    s: &mut PixelSampler,
) -> Spectrum {
    let Some(ray): Option<Ray> = sensor.camera_ray(film_uv, s) else { return Spectrum::ZERO };
    let Some(si) = scene.intersect(&ray) else { return Spectrum::ZERO };
    let n = if si.n.dot(ray.d) < 0.0 { si.n } else { -si.n };
    estimate_irradiance(scene, &scene.integrator, si.p, n, s)
}
