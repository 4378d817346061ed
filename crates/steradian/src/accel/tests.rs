//! BVH tests against brute force.

use glam::{Vec2, Vec3};

use super::layout::{leaf_range, ANALYTIC, EMPTY_CHILD, LEAF, WIDTH};
use super::{Accel, Isa};
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
        shapes.push(Shape::Mesh(
            Mesh::new(pos, None, None, idx, &Transform::IDENTITY, false, false).unwrap(),
        ));
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
            2 => Shape::Cylinder(
                Cylinder::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 0.5, &t, false).unwrap(),
            ),
            _ => Shape::Mesh(cube(&t, false)),
        });
    }
    shapes
}

/// The kernel sets this CPU can run (scalar always; AVX2 where present).
fn isas() -> Vec<Isa> {
    [Isa::Scalar, Isa::Avx2].into_iter().filter(|i| i.is_supported()).collect()
}

/// Triangle leaves of one packet (tested 4 lanes wide) and of two or more (tested in pairs,
/// 8 lanes wide).
fn leaf_kinds(accel: &Accel) -> (usize, usize) {
    let leaves = accel
        .nodes
        .iter()
        .flat_map(|n| n.child)
        .filter(|&c| c & super::layout::LEAF != 0 && c & super::layout::ANALYTIC == 0);
    leaves.fold((0, 0), |(one, more), c| {
        if super::layout::leaf_range(c).len() == 1 {
            (one + 1, more)
        } else {
            (one, more + 1)
        }
    })
}

#[test]
fn closest_hit_and_occlusion_match_brute_force() {
    let shapes = scene(3);
    for isa in isas() {
        let accel = Accel::build_with_isa(&shapes, isa);
        assert_eq!(accel.isa(), isa);
        let (single, paired) = leaf_kinds(&accel);
        assert!(
            single > 0 && paired > 0,
            "both packet tests must run: {single} one-packet leaves, {paired} larger"
        );
        let b = accel.bounds();
        assert!(b.min.cmple(Vec3::splat(-10.0)).all() && b.max.cmpge(Vec3::splat(10.0)).all());
        let mut r = Pcg32::new(99, 5);
        let (mut hits, mut occl) = (0, 0);
        for i in 0..10_000 {
            let o = v3(&mut r) * 30.0 - Vec3::splat(15.0);
            let mut d = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                r.next_f32(),
                r.next_f32(),
            ));
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
                    // the same triangle test in SIMD and scalar: identical distance and barycentrics
                    assert_eq!(h.t, t, "{isa:?} ray {i}");
                    assert_eq!((h.shape, h.prim), (s, p), "{isa:?} ray {i}");
                    assert_eq!(
                        shapes[s as usize].intersect_prim(p, &ray).unwrap().1,
                        h.uv,
                        "{isa:?} ray {i}"
                    );
                }
                (g, w) => panic!("{isa:?} ray {i}: bvh {g:?}, brute force {w:?}"),
            }
            let occluded = accel.occluded(&shapes, &ray);
            assert_eq!(occluded, want.is_some(), "{isa:?} ray {i}");
            occl += occluded as u32;
            // a ray interval (t_min, t_max): the hit beyond t_min
            if let Some((t, _, _)) = want {
                let t_min = 0.5 * t;
                let far = accel
                    .intersect_from(&shapes, &ray, t_min)
                    .expect("the closest hit lies beyond t_min");
                assert_eq!(far.t, t, "{isa:?} ray {i}");
                assert!(accel.occluded_from(&shapes, &ray, t_min));
            }
        }
        // the test must exercise both outcomes
        assert!(hits > 1000 && hits < 9000, "{hits} hits");
        assert!(occl > 1000);
    }
}

/// Rays starting inside a closed triangle mesh (a box) with an interval that
/// excludes the near wall must find the far wall: tests t_min on triangles against brute force.
#[test]
fn intervals_on_a_closed_mesh() {
    let shapes = vec![Shape::Mesh(cube(&Transform::scale(Vec3::splat(2.0)).unwrap(), false))];
    let mut r = Pcg32::new(5, 7);
    for isa in isas() {
        let accel = Accel::build_with_isa(&shapes, isa);
        for _ in 0..1000 {
            let o = v3(&mut r) * 2.0 - Vec3::ONE;
            let d = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                r.next_f32(),
                r.next_f32(),
            ));
            let ray = Ray::infinite(o, d);
            let h = accel.intersect(&shapes, &ray).expect("inside a closed box");
            assert_eq!(h.t, brute_intersect(&shapes, &ray).unwrap().0);
            // beyond the exit point nothing is left
            assert!(accel.intersect_from(&shapes, &ray, h.t * 1.001).is_none());
            assert!(!accel.occluded_from(&shapes, &ray, h.t * 1.001));
        }
    }
}

#[test]
fn layout_is_compact_and_complete() {
    let shapes = scene(4);
    let accel = Accel::build(&shapes);
    let total: u32 = shapes.iter().map(|s| s.prim_count()).sum();
    // every leaf is reached from the root once; every non-degenerate primitive is referenced
    // exactly once; children lie inside their parent's box
    let mut seen = std::collections::HashSet::new();
    let mut visited_nodes = 0;
    let mut todo = vec![(accel.root, accel.bounds())];
    while let Some((code, parent)) = todo.pop() {
        if code & LEAF == 0 {
            visited_nodes += 1;
            let n = &accel.nodes[code as usize];
            for lane in 0..WIDTH {
                if n.child[lane] == EMPTY_CHILD {
                    assert!(
                        n.bounds[0][lane] > n.bounds[3][lane],
                        "unused lanes hold the empty box"
                    );
                    continue;
                }
                let b = n.child_bounds(lane);
                assert!(b.min.cmpge(parent.min).all() && b.max.cmple(parent.max).all());
                todo.push((n.child[lane], b));
            }
        } else if code & ANALYTIC == 0 {
            let packets = &accel.tris[leaf_range(code)];
            assert!(!packets.is_empty() && packets.len() <= 2);
            for (p, ids) in packets.iter().zip(&accel.tri_ids[leaf_range(code)]) {
                for lane in 0..4 {
                    if ids.shape[lane] == u32::MAX {
                        assert!(
                            p.v.iter().flatten().all(|axis| axis[lane].is_nan()),
                            "empty lanes never hit"
                        );
                        continue;
                    }
                    assert!(seen.insert((ids.shape[lane], ids.prim[lane])));
                    // the packet holds the triangle's vertices, inside the leaf box
                    let tri = shapes[ids.shape[lane] as usize]
                        .triangle(ids.prim[lane])
                        .expect("triangle of a curved shape");
                    for (k, v) in tri.iter().enumerate() {
                        assert_eq!(
                            [p.v[k][0][lane], p.v[k][1][lane], p.v[k][2][lane]],
                            v.to_array()
                        );
                        assert!(v.cmpge(parent.min).all() && v.cmple(parent.max).all());
                    }
                }
            }
        } else {
            for r in &accel.others[leaf_range(code)] {
                assert!(
                    shapes[r.shape as usize].triangle(r.prim).is_none(),
                    "a triangle among the curved shapes"
                );
                assert!(seen.insert((r.shape, r.prim)));
            }
        }
    }
    assert_eq!(visited_nodes, accel.nodes.len());
    assert!(seen.len() as u32 <= total && seen.len() as u32 >= total - 40);
    let stats = accel.stats();
    assert_eq!(stats.triangles + stats.analytic_prims, seen.len());
    // packets are mostly full
    assert!(stats.triangles as f32 / (4 * stats.triangle_packets) as f32 > 0.6, "{stats:?}");
}

#[test]
fn empty_scenes_and_single_shapes() {
    for isa in isas() {
        let accel = Accel::build_with_isa(&[], isa);
        let ray = Ray::infinite(Vec3::ZERO, Vec3::Z);
        assert!(accel.intersect(&[], &ray).is_none());
        assert!(!accel.occluded(&[], &ray));
        assert!(accel.bounds().is_empty());
        let shapes = vec![Shape::Sphere(Sphere::new(
            Vec3::new(0.0, 0.0, 5.0),
            1.0,
            &Transform::IDENTITY,
            false,
        ))];
        let accel = Accel::build_with_isa(&shapes, isa);
        let h = accel.intersect(&shapes, &ray).unwrap();
        assert!((h.t - 4.0).abs() < 1e-5 && h.shape == 0 && h.prim == 0);
        assert!(accel.occluded(&shapes, &ray));
        assert!(!accel.occluded(&shapes, &Ray::new(Vec3::ZERO, Vec3::Z, 3.9)));
        // many identical triangles (coincident centroids) still build and trace
        let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        let idx = vec![[0, 1, 2]; 100];
        let shapes = vec![Shape::Mesh(
            Mesh::new(pos, None, None, idx, &Transform::IDENTITY, false, false).unwrap(),
        )];
        let accel = Accel::build_with_isa(&shapes, isa);
        let h =
            accel.intersect(&shapes, &Ray::infinite(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z)).unwrap();
        assert!((h.t - 1.0).abs() < 1e-6);
        // many instances of analytic shapes: a 20 × 20 × 5 grid of spheres
        let shapes: Vec<Shape> = (0..2000)
            .map(|i| {
                Shape::Sphere(Sphere::new(
                    Vec3::new((i % 20) as f32, (i / 20 % 20) as f32, (i / 400) as f32 * 3.0),
                    0.3,
                    &Transform::IDENTITY,
                    false,
                ))
            })
            .collect();
        let accel = Accel::build_with_isa(&shapes, isa);
        assert_eq!(accel.stats().analytic_prims, 2000);
        let h =
            accel.intersect(&shapes, &Ray::infinite(Vec3::new(7.0, 4.0, -10.0), Vec3::Z)).unwrap();
        assert_eq!(h.shape, 7 + 4 * 20);
        assert!((h.t - 9.7).abs() < 1e-4);
    }
}

/// Two spheres side by side must not share one leaf where the root node has child slots to
/// spare: the SAH prices their split at a node visit and keeps them together, so every ray
/// that reached either would test both. Leaves of several shapes split into free slots.
#[test]
fn separate_shapes_take_free_child_slots() {
    let floor = Transform::scale(Vec3::splat(8.0))
        .unwrap()
        .then(&Transform::rotate(Vec3::X, -90.0).unwrap());
    let shapes = vec![
        Shape::Rectangle(Rectangle::new(&floor, false)),
        Shape::Sphere(Sphere::new(Vec3::new(-0.7, 0.65, 0.0), 0.65, &Transform::IDENTITY, false)),
        Shape::Sphere(Sphere::new(Vec3::new(0.7, 0.65, 0.0), 0.65, &Transform::IDENTITY, false)),
    ];
    for isa in isas() {
        let accel = Accel::build_with_isa(&shapes, isa);
        assert_eq!(accel.nodes.len(), 1, "{isa:?}: three shapes fit one node");
        let analytic: Vec<usize> = accel.nodes[0]
            .child
            .iter()
            .filter(|&&c| c != EMPTY_CHILD && c & LEAF != 0 && c & ANALYTIC != 0)
            .map(|&c| leaf_range(c).len())
            .collect();
        assert_eq!(analytic, vec![1, 1], "{isa:?}: each sphere in a leaf of its own");
        // and the hits are still those of brute force
        let mut r = Pcg32::new(3, 1);
        for _ in 0..2000 {
            let o = Vec3::new(0.0, 3.0, 4.0) + (v3(&mut r) - Vec3::splat(0.5));
            let d = (Vec3::new(4.0 * r.next_f32() - 2.0, 0.0, 2.0 * r.next_f32() - 1.0) - o)
                .normalize();
            let ray = Ray::new(o, d, f32::INFINITY);
            let want = brute_intersect(&shapes, &ray).map(|(_, s, p)| (s, p));
            let got = accel.intersect(&shapes, &ray).map(|h| (h.shape, h.prim));
            assert_eq!(got, want, "{isa:?}: ray {ray:?}");
        }
    }
}

/// Instances of two groups (a box, a rectangle and a sphere; a box and a rectangle) under
/// rotations, scales (non-uniform for the group without the sphere) and translations find what
/// the same shapes built in world space find: the same member, distances within 1e-4 relative,
/// the same points and normals; occlusion agrees with the closest hits.
#[test]
fn instances_match_their_flattened_copies() {
    use std::sync::Arc;

    use super::{Instance, ShapeGroup};
    use crate::geometry::NO_INSTANCE;

    let local_box = Transform::scale(Vec3::new(0.6, 0.4, 0.5)).unwrap();
    let members = |t: &Transform, sphere: bool| {
        let mut m = vec![
            Shape::Mesh(cube(&local_box.then(t), false)),
            Shape::Rectangle(Rectangle::new(&Transform::translate(-Vec3::Z).then(t), false)),
        ];
        if sphere {
            m.push(Shape::Sphere(Sphere::new(Vec3::new(0.0, 1.0, 0.0), 0.5, t, false)));
        }
        m
    };
    let groups = [false, true]
        .map(|sphere| Arc::new(ShapeGroup::new(members(&Transform::IDENTITY, sphere))));
    let mut r = Pcg32::new(5, 3);
    let (mut instances, mut flat, mut first) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..40 {
        let sphere = i % 2 == 0;
        // spheres stay spheres under uniform scales only
        let s = if sphere {
            Vec3::splat(0.5 + r.next_f32())
        } else {
            Vec3::new(0.5 + r.next_f32(), 0.5 + r.next_f32(), 0.5 + r.next_f32())
        };
        let t = Transform::scale(s)
            .unwrap()
            .then(&Transform::rotate(v3(&mut r) - Vec3::splat(0.5), 360.0 * r.next_f32()).unwrap())
            .then(&Transform::translate(v3(&mut r) * 16.0 - Vec3::splat(8.0)));
        first.push(flat.len() as u32);
        flat.extend(members(&t, sphere));
        instances.push(Instance::new(groups[sphere as usize].clone(), t));
    }
    let accel = Accel::build_with_instances(&[], instances.clone(), Isa::detect());
    let flat_accel = Accel::build(&flat);
    let (mut hits, mut mismatches) = (0, 0);
    for i in 0..40_000 {
        let o = v3(&mut r) * 24.0 - Vec3::splat(12.0);
        let d =
            crate::sampling::warp::square_to_uniform_sphere(Vec2::new(r.next_f32(), r.next_f32()));
        let ray = Ray::new(o, d, if i % 3 == 0 { f32::INFINITY } else { 20.0 * r.next_f32() });
        let got = accel.intersect(&[], &ray);
        assert_eq!(accel.occluded(&[], &ray), got.is_some(), "ray {i}");
        let want = flat_accel.intersect(&flat, &ray);
        match (got, want) {
            (None, None) => {}
            (Some(h), Some(w)) => {
                hits += 1;
                assert_ne!(h.instance, NO_INSTANCE);
                assert_eq!(w.instance, NO_INSTANCE);
                if (first[h.instance as usize] + h.shape, h.prim) != (w.shape, w.prim) {
                    mismatches += 1;
                    continue;
                }
                assert!((h.t - w.t).abs() <= 1e-4 * w.t.max(1.0), "ray {i}: {} vs {}", h.t, w.t);
                let si = instances[h.instance as usize].interaction(&ray, &h);
                let sw = flat[w.shape as usize].interaction(&ray, &w);
                assert!((si.p - sw.p).length() < 1e-3 * (1.0 + sw.p.length()), "ray {i}");
                assert!(si.n.dot(sw.n) > 0.9999, "ray {i}: {} vs {}", si.n, sw.n);
                assert!(si.sh_frame.n.dot(sw.sh_frame.n) > 0.999, "ray {i}");
            }
            // an edge or a grazing ray can go either way in two floating-point paths
            _ => mismatches += 1,
        }
    }
    assert!(hits > 2000, "{hits} hits");
    assert!(mismatches * 1000 < hits, "{mismatches} mismatches in {hits} hits");
    assert_eq!((accel.stats().instances, accel.stats().triangles), (40, 0));
}

/// A grid of `n × n` quads (2 n² triangles) on a wavy surface: a mesh large enough for the
/// builder's parallel paths (ranges above 4096 primitives split over threads, above 65536 bin
/// over threads).
fn wavy_grid(n: u32) -> Shape {
    let (pos, idx) = crate::testkit::scenes::grid_mesh(n, |i, j| {
        let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
        Vec3::new(x, y, 0.1 * (9.0 * x).sin() * (7.0 * y).cos())
    });
    Shape::Mesh(Mesh::new(pos, None, None, idx, &Transform::IDENTITY, false, true).unwrap())
}

/// The hierarchy is the same on any number of threads, bit for bit: every decision depends on
/// the primitives only, and the parallel chunks are laid out in a fixed order.
#[test]
fn builds_are_the_same_on_any_thread_count() {
    let mut shapes = scene(9);
    shapes.push(wavy_grid(200)); // 80,000 triangles
    let build = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| Accel::build_with_isa(&shapes, Isa::Scalar))
    };
    let one = build(1);
    for threads in [2, 3] {
        let other = build(threads);
        assert_eq!(one.root, other.root);
        assert_eq!(one.nodes.len(), other.nodes.len());
        for (a, b) in one.nodes.iter().zip(&other.nodes) {
            assert_eq!(a.child, b.child);
            assert_eq!(
                a.bounds.map(|p| p.map(f32::to_bits)),
                b.bounds.map(|p| p.map(f32::to_bits))
            );
        }
        assert_eq!(one.tris.len(), other.tris.len());
        for (a, b) in one.tris.iter().zip(&other.tris) {
            assert_eq!(
                a.v.map(|k| k.map(|x| x.map(f32::to_bits))),
                b.v.map(|k| k.map(|x| x.map(f32::to_bits)))
            );
        }
        for (a, b) in one.tri_ids.iter().zip(&other.tri_ids) {
            assert_eq!((a.shape, a.prim), (b.shape, b.prim));
        }
        let refs = |acc: &Accel| acc.others.iter().map(|r| (r.shape, r.prim)).collect::<Vec<_>>();
        assert_eq!(refs(&one), refs(&other));
    }
    // and the large mesh traces as brute force does
    let mut r = Pcg32::new(11, 3);
    for _ in 0..300 {
        let o = Vec3::new(r.next_f32(), r.next_f32(), 1.0);
        let d = (Vec3::new(r.next_f32(), r.next_f32(), -1.0) - o).normalize();
        let ray = Ray::infinite(o, d);
        let want = brute_intersect(&shapes, &ray).map(|(_, s, p)| (s, p));
        let got = one.intersect(&shapes, &ray).map(|h| (h.shape, h.prim));
        assert_eq!(got, want, "{ray:?}");
    }
}
