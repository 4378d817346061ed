//! Ray-casting throughput of steradian's BVH on the mesh and ray sets exported by the Embree 3
//! benchmark (`benches/embree/bench.cpp --export PREFIX`; formats in `benches/README.md`),
//! single rays (closest hit or occlusion) as a path tracer casts them, on 1 and 2 threads.
//!
//!     cargo run --release --example raycast -- --data PREFIX [--reference PREFIX.embree]
//!         [--threads 1,2] [--sets primary,diffuse,bounce,shadow] [--isa avx2|scalar] [--repeat 3]
//!
//! Reads `PREFIX.mesh` and `PREFIX.<set>.rays`; with `--reference`, compares every ray's result
//! with Embree's `--dump-hits` file `REF.<set>.hits` (f32 distance, ∞ = miss; or 1/0 occluded).
//! Timing covers what Embree's timing covers: reading each stored ray, the traversal, and
//! writing the hit distance and primitive index; the best of `--repeat` runs is printed.

use std::time::Instant;

use steradian::accel::{Accel, Isa};
use steradian::geometry::{Ray, Transform};
use steradian::shape::{Mesh, Shape};
use steradian::Vec3;

const CHUNK: usize = 4096;

#[derive(Clone, Copy)]
#[repr(C)]
struct Ray32 {
    o: [f32; 3],
    t_near: f32,
    d: [f32; 3],
    t_far: f32,
}

fn die(msg: String) -> ! {
    eprintln!("raycast: error: {msg}");
    std::process::exit(1)
}

fn read(path: &str) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| die(format!("{path}: {e}")))
}

fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes(b[i..i + 4].try_into().unwrap())
}

fn f32_at(b: &[u8], i: usize) -> f32 {
    f32::from_le_bytes(b[i..i + 4].try_into().unwrap())
}

fn load_mesh(path: &str) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let b = read(path);
    if b.len() < 16 || &b[..8] != b"SMESH001" {
        die(format!("{path}: not a SMESH001 file"));
    }
    let (nv, nt) = (u32_at(&b, 8) as usize, u32_at(&b, 12) as usize);
    if b.len() != 16 + 12 * nv + 12 * nt {
        die(format!(
            "{path}: expected {} bytes for {nv} vertices and {nt} triangles",
            16 + 12 * nv + 12 * nt
        ));
    }
    let v = (0..nv)
        .map(|i| Vec3::from_array(std::array::from_fn(|k| f32_at(&b, 16 + 12 * i + 4 * k))))
        .collect();
    let base = 16 + 12 * nv;
    let t = (0..nt).map(|i| std::array::from_fn(|k| u32_at(&b, base + 12 * i + 4 * k))).collect();
    (v, t)
}

/// Rays and kind (false closest hit, true occlusion); `None` when the file does not exist.
fn load_rays(path: &str) -> Option<(Vec<Ray32>, bool)> {
    if !std::path::Path::new(path).exists() {
        return None;
    }
    let b = read(path);
    if b.len() < 16 || &b[..8] != b"SRAYS001" {
        die(format!("{path}: not a SRAYS001 file"));
    }
    let (n, kind) = (u32_at(&b, 8) as usize, u32_at(&b, 12));
    if b.len() != 16 + 32 * n {
        die(format!("{path}: expected {n} rays"));
    }
    let rays = (0..n)
        .map(|i| {
            let f = |k: usize| f32_at(&b, 16 + 32 * i + 4 * k);
            Ray32 { o: [f(0), f(1), f(2)], t_near: f(3), d: [f(4), f(5), f(6)], t_far: f(7) }
        })
        .collect();
    Some((rays, kind == 1))
}

/// CPU seconds used by this process so far (user + system, from /proc; 0 where unavailable):
/// with the wall time it tells whether the tracing threads had their cores on a shared machine.
fn process_cpu_s() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else { return 0.0 };
    // fields after the parenthesised command name; utime and stime are the 12th and 13th
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}

/// Traces all rays on `pool`; returns seconds. `t[i]`: distance (∞ miss) or 1/0 occluded.
fn trace(
    pool: &rayon::ThreadPool,
    accel: &Accel,
    shapes: &[Shape],
    rays: &[Ray32],
    occlusion: bool,
    t: &mut [f32],
    prim: &mut [u32],
) -> f64 {
    use rayon::prelude::*;
    let start = Instant::now();
    pool.install(|| {
        rays.par_chunks(CHUNK)
            .zip(t.par_chunks_mut(CHUNK))
            .zip(prim.par_chunks_mut(CHUNK))
            .for_each(|((rays, t), prim)| {
                for ((r, t), p) in rays.iter().zip(t).zip(prim) {
                    let ray = Ray::new(Vec3::from_array(r.o), Vec3::from_array(r.d), r.t_far);
                    if occlusion {
                        *t = accel.occluded_from(shapes, &ray, r.t_near) as u32 as f32;
                    } else {
                        match accel.intersect_from(shapes, &ray, r.t_near) {
                            Some(h) => {
                                *t = h.t;
                                *p = h.prim;
                            }
                            None => {
                                *t = f32::INFINITY;
                                *p = u32::MAX;
                            }
                        }
                    }
                }
            })
    });
    start.elapsed().as_secs_f64()
}

fn main() {
    let mut data = None;
    let mut reference = None;
    let mut threads = vec![1usize, 2];
    let mut sets: Vec<String> =
        ["primary", "diffuse", "bounce", "shadow"].map(String::from).to_vec();
    let mut isa = Isa::detect();
    let mut repeat = 1usize;
    let mut name = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut val = || args.next().unwrap_or_else(|| die(format!("missing value after {a}")));
        match a.as_str() {
            "--data" => data = Some(val()),
            "--reference" => reference = Some(val()),
            "--name" => name = Some(val()),
            "--threads" => {
                threads = val()
                    .split(',')
                    .map(|s| s.parse().unwrap_or_else(|_| die(format!("bad thread count '{s}'"))))
                    .collect()
            }
            "--sets" => sets = val().split(',').map(String::from).collect(),
            "--repeat" => repeat = val().parse().unwrap_or_else(|_| die("bad --repeat".into())),
            "--isa" => {
                isa = match val().as_str() {
                    "avx2" => Isa::Avx2,
                    "scalar" => Isa::Scalar,
                    other => die(format!("unknown --isa '{other}' (avx2 or scalar)")),
                }
            }
            "-h" | "--help" => {
                println!("usage: raycast --data PREFIX [--reference PREFIX] [--name NAME] [--threads 1,2] [--sets LIST] [--isa avx2|scalar] [--repeat N]");
                return;
            }
            _ => die(format!("unknown argument '{a}' (see --help)")),
        }
    }
    let data = data.unwrap_or_else(|| die("--data PREFIX is required".into()));
    let name = name.unwrap_or_else(|| data.rsplit('/').next().unwrap_or(&data).to_string());

    let (positions, indices) = load_mesh(&format!("{data}.mesh"));
    let (nv, nt) = (positions.len(), indices.len());
    let mesh = Mesh::new(positions, None, None, indices, &Transform::IDENTITY, false, true)
        .unwrap_or_else(|e| die(format!("{data}.mesh: {e}")));
    let shapes = vec![Shape::Mesh(mesh)];
    // build once untimed (page faults, thread-pool start), then time the best of 3
    let mut accel = Accel::build_with_isa(&shapes, isa);
    let mut build_s = f64::INFINITY;
    for _ in 0..3 {
        let start = Instant::now();
        accel = Accel::build_with_isa(&shapes, isa);
        build_s = build_s.min(start.elapsed().as_secs_f64());
    }
    let stats = accel.stats();
    let mesh_bytes = 12 * nv + 12 * nt;
    println!(
        "BUILD lib=steradian isa={:?} mesh={name} tris={nt} build_threads={} sec={build_s:.4} mtris_per_s={:.3} bvh_mb={:.1} \
         nodes={} packets={} packet_fill={:.3} bytes_per_tri_bvh={:.1} bytes_per_tri_mesh={:.1} bytes_per_tri_total={:.1} sah_cost={:.2}",
        accel.isa(),
        rayon::current_num_threads(),
        nt as f64 / build_s / 1e6,
        stats.bytes as f64 / (1024.0 * 1024.0),
        stats.nodes,
        stats.triangle_packets,
        stats.triangles as f64 / (4 * stats.triangle_packets) as f64,
        stats.bytes as f64 / nt as f64,
        mesh_bytes as f64 / nt as f64,
        (stats.bytes + mesh_bytes) as f64 / nt as f64,
        accel.sah_cost(),
    );

    for set in &sets {
        let Some((rays, occlusion)) = load_rays(&format!("{data}.{set}.rays")) else { continue };
        let mut t = vec![0.0f32; rays.len()];
        let mut prim = vec![0u32; rays.len()];
        for &th in &threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(th)
                .build()
                .unwrap_or_else(|e| die(format!("thread pool: {e}")));
            let (mut sec, mut cpu_util) = (f64::INFINITY, 0.0);
            for _ in 0..repeat.max(1) {
                let cpu0 = process_cpu_s();
                let s = trace(&pool, &accel, &shapes, &rays, occlusion, &mut t, &mut prim);
                if s < sec {
                    sec = s;
                    cpu_util = (process_cpu_s() - cpu0) / (s * th as f64);
                }
            }
            let (mut hits, mut tsum) = (0usize, 0.0f64);
            for &x in &t {
                if occlusion {
                    hits += (x > 0.5) as usize;
                } else if x.is_finite() {
                    hits += 1;
                    tsum += x as f64;
                }
            }
            let mut line = format!(
                "TRACE lib=steradian mesh={name} set={set} mode={} threads={th} rays={} sec={sec:.4} mrays_per_s={:.3} hit_frac={:.6} mean_t={:.6} cpu_util={cpu_util:.3}",
                if occlusion { "occluded1" } else { "intersect1" },
                rays.len(),
                rays.len() as f64 / sec / 1e6,
                hits as f64 / rays.len() as f64,
                if hits > 0 && !occlusion { tsum / hits as f64 } else { 0.0 },
            );
            if let Some(r) = &reference {
                let path = format!("{r}.{set}.hits");
                let b = read(&path);
                if b.len() != 4 * rays.len() {
                    die(format!("{path}: expected {} results", rays.len()));
                }
                // per ray: same hit/miss (or occlusion) decision, and the same distance to 1e-4
                let (mut differ, mut dist_differ) = (0usize, 0usize);
                for (i, &x) in t.iter().enumerate() {
                    let e = f32_at(&b, 4 * i);
                    if occlusion {
                        differ += ((x > 0.5) != (e > 0.5)) as usize;
                    } else if x.is_finite() != e.is_finite() {
                        differ += 1;
                    } else if x.is_finite() && (x - e).abs() > 1e-4 * e.abs().max(1e-3) {
                        dist_differ += 1;
                    }
                }
                line += &format!(
                    " vs_embree_decision_differs={differ} vs_embree_distance_differs={dist_differ}"
                );
            }
            println!("{line}");
        }
    }
}
