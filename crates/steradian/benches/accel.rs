//! BVH benchmarks (criterion): build throughput in triangles/s and single-ray throughput in
//! rays/s (closest hit and occlusion, incoherent rays) for each kernel set this CPU runs.
//!
//!     cargo bench -p steradian --bench accel
//!
//! The mesh is a cube-sphere (each cube face an n × n grid pushed onto the unit sphere) as in
//! the Embree comparison (`benches/embree/run.sh`), which traces Embree's own ray files.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use steradian::accel::{Accel, Isa};
use steradian::geometry::{Ray, Transform};
use steradian::sampling::Pcg32;
use steradian::shape::{Mesh, Shape};
use steradian::Vec3;

/// A unit cube-sphere of 12 n² triangles.
fn cube_sphere(n: u32) -> Shape {
    let mut pos = Vec::new();
    let mut idx = Vec::new();
    for face in 0..6 {
        let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
        let base = pos.len() as u32;
        for j in 0..=n {
            for i in 0..=n {
                let mut c = [0.0f32; 3];
                c[axis] = sign;
                c[(axis + 1) % 3] = -1.0 + 2.0 * i as f32 / n as f32;
                c[(axis + 2) % 3] = -1.0 + 2.0 * j as f32 / n as f32;
                pos.push(Vec3::from_array(c).normalize());
            }
        }
        for j in 0..n {
            for i in 0..n {
                let a = base + j * (n + 1) + i;
                idx.push([a, a + 1, a + n + 2]);
                idx.push([a, a + n + 2, a + n + 1]);
            }
        }
    }
    Shape::Mesh(
        Mesh::new(pos, None, None, idx, &Transform::IDENTITY, false, true).expect("valid mesh"),
    )
}

fn uniform_sphere(rng: &mut Pcg32) -> Vec3 {
    let z = 1.0 - 2.0 * rng.next_f32();
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * rng.next_f32();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Incoherent rays: from points just inside and outside the sphere, uniform directions;
/// segments between two surface points for occlusion.
fn rays(count: usize) -> (Vec<Ray>, Vec<Ray>) {
    let mut rng = Pcg32::new(1, 2);
    let closest = (0..count)
        .map(|i| {
            let o = uniform_sphere(&mut rng) * if i % 2 == 0 { 0.999 } else { 1.001 };
            Ray::infinite(o, uniform_sphere(&mut rng))
        })
        .collect();
    let shadow = (0..count)
        .map(|_| {
            let (p, q) = (uniform_sphere(&mut rng) * 0.999, uniform_sphere(&mut rng) * 1.5);
            let d = q - p;
            Ray::new(p, d.normalize(), d.length())
        })
        .collect();
    (closest, shadow)
}

fn isas() -> Vec<Isa> {
    [Isa::Avx2, Isa::Scalar].into_iter().filter(|i| i.is_supported()).collect()
}

fn build(c: &mut Criterion) {
    let mut g = c.benchmark_group("bvh_build");
    g.sample_size(10);
    for n in [29u32, 91] {
        let shapes = vec![cube_sphere(n)];
        let tris = 12 * n as u64 * n as u64;
        g.throughput(Throughput::Elements(tris));
        g.bench_function(format!("sphere_{tris}_tris"), |b| b.iter(|| Accel::build(&shapes)));
    }
    g.finish();
}

fn trace(c: &mut Criterion) {
    let shapes = vec![cube_sphere(91)];
    let (closest, shadow) = rays(1 << 16);
    let mut g = c.benchmark_group("ray_throughput");
    g.throughput(Throughput::Elements(closest.len() as u64));
    for isa in isas() {
        let accel = Accel::build_with_isa(&shapes, isa);
        g.bench_function(format!("closest_{isa:?}"), |b| {
            b.iter(|| closest.iter().filter(|r| accel.intersect(&shapes, r).is_some()).count())
        });
        g.bench_function(format!("occluded_{isa:?}"), |b| {
            b.iter(|| shadow.iter().filter(|r| accel.occluded(&shapes, r)).count())
        });
    }
    g.finish();
}

criterion_group!(benches, build, trace);
criterion_main!(benches);
