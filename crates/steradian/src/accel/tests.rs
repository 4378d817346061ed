//! BVH tests against brute force.

use glam::{Vec2, Vec3};

use super::Accel;
use crate::geometry::{Ray, Transform};
use crate::sampling::Pcg32;
use crate::shape::{cube, Cylinder, Disk, Mesh, Rectangle, Shape, Sphere};

fn v3(r: &mut Pcg32) -> Vec3 {
    Vec3::new(r.next_f32(), r.next_f32(), r.next_f32())
}

fn brute_intersect(shapes: &[Shape], ray: &Ray) -> Option<(f32, u32, u32)> {
    let mut best = None;
    let mut r = *ray;
    for (s, shape) in shapes.iter().enumerate() {
        for p in 0..shape.prim_count() {
            if let Some((t, _)) = shape.intersect_prim(p, &r) {
                r.t_max = t;
                best = Some((t, s as u32, p));
            }
        }
    }
    best
}

fn scene(seed: u64) -> Vec<Shape> {
    let mut r = Pcg32::new(seed, 1);
    let mut shapes = Vec::new();
    // a soup of random triangles (two meshes), with some degenerate ones
    for _ in 0..2 {
        let mut pos = Vec::new();
        let mut idx = Vec::new();
        for i in 0..1500u32 {
            let c = v3(&mut r) * 20.0 - Vec3::splat(10.0);
            let size = 0.2 + 2.0 * r.next_f32();
            for _ in 0..3 {
                pos.push(c + (v3(&mut r) - Vec3::splat(0.5)) * size);
            }
            if i % 97 == 0 {
                pos[3 * i as usize + 2] = pos[3 * i as usize + 1];
            }
            idx.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        shapes.push(Shape::Mesh(Mesh::new(pos, None, None, idx, &Transform::IDENTITY, false, false).unwrap()));
    }
    for _ in 0..60 {
        let c = v3(&mut r) * 20.0 - Vec3::splat(10.0);
        shapes.push(Shape::Sphere(Sphere::new(c, 0.1 + r.next_f32(), &Transform::IDENTITY, false)));
    }
    for i in 0..20 {
        let t = Transform::rotate(v3(&mut r) - Vec3::splat(0.5), 360.0 * r.next_f32())
            .unwrap()
            .then(&Transform::translate(v3(&mut r) * 20.0 - Vec3::splat(10.0)));
        shapes.push(match i % 4 {
            0 => Shape::Rectangle(Rectangle::new(&t, false)),
            1 => Shape::Disk(Disk::new(&t, true)),
            2 => Shape::Cylinder(Cylinder::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 0.5, &t, false).unwrap()),
            _ => Shape::Mesh(cube(&t, false)),
        });
    }
    shapes
}

#[test]
fn closest_hit_and_occlusion_match_brute_force() {
    let shapes = scene(3);
    let accel = Accel::build(&shapes);
    let b = accel.bounds();
    assert!(b.min.cmple(Vec3::splat(-10.0)).all() && b.max.cmpge(Vec3::splat(10.0)).all());
    let mut r = Pcg32::new(99, 5);
    let (mut hits, mut occl) = (0, 0);
    for i in 0..10_000 {
        let o = v3(&mut r) * 30.0 - Vec3::splat(15.0);
        let mut d = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(r.next_f32(), r.next_f32()));
        if i % 10 == 0 {
            // axis-aligned directions exercise the slab test's infinities
            d = [Vec3::X, -Vec3::Y, Vec3::Z][i % 3];
        }
        let t_max = if i % 3 == 0 { f32::INFINITY } else { 30.0 * r.next_f32() };
        let ray = Ray::new(o, d, t_max);
        let got = accel.intersect(&shapes, &ray);
        let want = brute_intersect(&shapes, &ray);
        match (got, want) {
            (None, None) => {}
            (Some(h), Some((t, s, p))) => {
                hits += 1;
                assert!((h.t - t).abs() <= 1e-5 * t, "ray {i}: t {} vs {t}", h.t);
                assert_eq!((h.shape, h.prim), (s, p), "ray {i}");
                assert_eq!(shapes[s as usize].intersect_prim(p, &ray).unwrap().1, h.uv);
            }
            (g, w) => panic!("ray {i}: bvh {g:?}, brute force {w:?}"),
        }
        let occluded = accel.occluded(&shapes, &ray);
        assert_eq!(occluded, want.is_some(), "ray {i}");
        occl += occluded as u32;
    }
    // the test must exercise both outcomes
    assert!(hits > 1000 && hits < 9000, "{hits} hits");
    assert!(occl > 1000);
}

#[test]
fn layout_is_compact_and_complete() {
    let shapes = scene(4);
    let accel = Accel::build(&shapes);
    let total: u32 = shapes.iter().map(|s| s.prim_count()).sum();
    // all non-degenerate primitives are referenced exactly once
    let mut seen = std::collections::HashSet::new();
    for p in &accel.prims {
        assert!(seen.insert((p.shape, p.prim)));
    }
    assert!(accel.prims.len() as u32 <= total && accel.prims.len() as u32 >= total - 40);
    // leaves cover every primitive once, children are adjacent and inside their parent
    let mut covered = vec![0u8; accel.prims.len()];
    for n in &accel.nodes {
        if n.count > 0 {
            for c in &mut covered[n.offset as usize..(n.offset + n.count) as usize] {
                *c += 1;
            }
        } else {
            for c in [n.offset as usize, n.offset as usize + 1] {
                let ch = &accel.nodes[c];
                for a in 0..3 {
                    assert!(ch.min[a] >= n.min[a] && ch.max[a] <= n.max[a]);
                }
            }
        }
    }
    assert!(covered.iter().all(|&c| c == 1));
}

#[test]
fn empty_scenes_and_single_shapes() {
    let accel = Accel::build(&[]);
    let ray = Ray::infinite(Vec3::ZERO, Vec3::Z);
    assert!(accel.intersect(&[], &ray).is_none());
    assert!(!accel.occluded(&[], &ray));
    assert!(accel.bounds().is_empty());
    let shapes = vec![Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 5.0), 1.0, &Transform::IDENTITY, false))];
    let accel = Accel::build(&shapes);
    let h = accel.intersect(&shapes, &ray).unwrap();
    assert!((h.t - 4.0).abs() < 1e-5 && h.shape == 0 && h.prim == 0);
    assert!(accel.occluded(&shapes, &ray));
    assert!(!accel.occluded(&shapes, &Ray::new(Vec3::ZERO, Vec3::Z, 3.9)));
    // many identical triangles (coincident centroids) still build and trace
    let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let idx = vec![[0, 1, 2]; 100];
    let shapes = vec![Shape::Mesh(Mesh::new(pos, None, None, idx, &Transform::IDENTITY, false, false).unwrap())];
    let accel = Accel::build(&shapes);
    let h = accel.intersect(&shapes, &Ray::infinite(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z)).unwrap();
    assert!((h.t - 1.0).abs() < 1e-6);
}
