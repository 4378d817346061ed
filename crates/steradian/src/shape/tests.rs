//! Tests of every shape: hand-computed intersections and Monte Carlo checks of sampling.

use std::f64::consts::PI as PI64;

use glam::{Vec2, Vec3};

use super::test_util::{check_sampling, close, trace};
use super::*;
use crate::geometry::{offset_ray_origin, Ray, Transform};

fn hit(shape: &Shape, ray: &Ray) -> Option<SurfaceInteraction> {
    let (t, prim) = trace(shape, ray)?;
    let (t2, uv) = shape.intersect_prim(prim, ray).unwrap();
    assert_eq!(t, t2);
    Some(shape.interaction(
        ray,
        &PreliminaryHit { t, uv, shape: 0, prim, instance: crate::geometry::NO_INSTANCE },
    ))
}

fn tr(v: Vec3) -> Transform {
    Transform::translate(v)
}

fn sc(v: Vec3) -> Transform {
    Transform::scale(v).unwrap()
}

fn assert_frame(si: &SurfaceInteraction) {
    let f = si.sh_frame;
    assert!((f.n.length() - 1.0).abs() < 1e-4 && (f.s.length() - 1.0).abs() < 1e-4);
    assert!(f.n.dot(f.s).abs() < 1e-4 && f.n.dot(f.t).abs() < 1e-4);
}

// ---------------------------------------------------------------- rectangle

#[test]
fn rectangle_intersections() {
    let m = sc(Vec3::new(2.0, 1.0, 1.0)).then(&tr(Vec3::Z));
    let s = Shape::Rectangle(Rectangle::new(&m, false));
    assert!((s.surface_area() - 8.0).abs() < 1e-5);
    let r = Ray::infinite(Vec3::new(1.0, 0.5, 3.0), -Vec3::Z);
    let si = hit(&s, &r).unwrap();
    assert!((si.t - 2.0).abs() < 1e-6);
    assert!(close(si.p, Vec3::new(1.0, 0.5, 1.0), 1e-6));
    assert!(close(si.n, Vec3::Z, 1e-6) && close(si.sh_frame.n, Vec3::Z, 1e-6));
    assert!((si.uv - Vec2::new(0.75, 0.75)).length() < 1e-6);
    assert_frame(&si);
    // from below: same normal (never flipped towards the ray)
    let si = hit(&s, &Ray::infinite(Vec3::new(1.0, 0.5, -3.0), Vec3::Z)).unwrap();
    assert!(close(si.n, Vec3::Z, 1e-6));
    // misses and t_max
    assert!(hit(&s, &Ray::infinite(Vec3::new(2.5, 0.0, 3.0), -Vec3::Z)).is_none());
    assert!(hit(&s, &Ray::new(Vec3::new(1.0, 0.5, 3.0), -Vec3::Z, 1.5)).is_none());
    assert!(hit(&s, &Ray::infinite(Vec3::new(1.0, 0.5, 3.0), Vec3::X)).is_none());
    // flip_normals
    let f = Shape::Rectangle(Rectangle::new(&m, true));
    assert!(close(hit(&f, &r).unwrap().n, -Vec3::Z, 1e-6));
    // rotated: +z → −y
    let rot = Transform::rotate(Vec3::X, 90.0).unwrap();
    let s = Shape::Rectangle(Rectangle::new(&rot, false));
    let si = hit(&s, &Ray::infinite(Vec3::new(0.0, -3.0, 0.0), Vec3::Y)).unwrap();
    assert!((si.t - 3.0).abs() < 1e-6 && close(si.n, -Vec3::Y, 1e-6));
    // shear/non-uniform: normal via the inverse transpose stays perpendicular to the plane
    let m = Transform::from_row_major(&[
        1.0, 0.0, 0.7, 0.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ])
    .unwrap();
    let s = Rectangle::new(&m, false);
    assert!(
        s.normal().dot(m.vector(Vec3::X)).abs() < 1e-6
            && s.normal().dot(m.vector(Vec3::Y)).abs() < 1e-6
    );
}

#[test]
fn rectangle_sampling() {
    // 2a × 2b rectangle at height h below the reference, centred: Ω = 4 asin(ab / √((a²+h²)(b²+h²)))
    let (a, b, h) = (2.0f64, 1.0f64, 1.5f64);
    let m = sc(Vec3::new(a as f32, b as f32, 1.0)).then(&tr(Vec3::new(0.3, -0.2, 0.0)));
    let s = Shape::Rectangle(Rectangle::new(&m, false));
    let omega = |h: f64| 4.0 * (a * b / ((a * a + h * h) * (b * b + h * h)).sqrt()).asin();
    let on = |p: Vec3| {
        p.z.abs() < 1e-5 && (p.x - 0.3).abs() <= 2.0 + 1e-5 && (p.y + 0.2).abs() <= 1.0 + 1e-5
    };
    // near (area/d² = 3.6: spherical-rectangle sampling)
    check_sampling(&s, on, Vec3::new(0.3, -0.2, h as f32), omega(h), true, 1);
    // seen from below the front side: same solid angle (|cos|)
    check_sampling(&s, on, Vec3::new(0.3, -0.2, -h as f32), omega(h), true, 2);
    // far (area/d² = 0.5: area sampling)
    check_sampling(&s, on, Vec3::new(0.3, -0.2, 4.0), omega(4.0), true, 3);
}

// ---------------------------------------------------------------- disk

#[test]
fn disk_intersections() {
    let m = sc(Vec3::splat(2.0)).then(&tr(Vec3::Z));
    let s = Shape::Disk(Disk::new(&m, false));
    assert!((s.surface_area() - 4.0 * std::f32::consts::PI).abs() < 1e-5);
    let si = hit(&s, &Ray::infinite(Vec3::new(1.0, 1.0, 5.0), -Vec3::Z)).unwrap();
    assert!((si.t - 4.0).abs() < 1e-6);
    assert!(close(si.p, Vec3::new(1.0, 1.0, 1.0), 1e-5));
    assert!(close(si.n, Vec3::Z, 1e-6));
    assert!((si.uv - Vec2::new(0.5f32.sqrt(), 0.125)).length() < 1e-5, "{}", si.uv);
    assert_frame(&si);
    // φ in the lower half plane: v in (0.5, 1)
    let si = hit(&s, &Ray::infinite(Vec3::new(0.0, -1.0, 5.0), -Vec3::Z)).unwrap();
    assert!((si.uv - Vec2::new(0.5, 0.75)).length() < 1e-5, "{}", si.uv);
    assert!(hit(&s, &Ray::infinite(Vec3::new(1.5, 1.5, 5.0), -Vec3::Z)).is_none());
    assert!(hit(&s, &Ray::new(Vec3::new(1.0, 1.0, 5.0), -Vec3::Z, 3.9)).is_none());
    let f = Shape::Disk(Disk::new(&m, true));
    assert!(close(
        hit(&f, &Ray::infinite(Vec3::new(1.0, 1.0, 5.0), -Vec3::Z)).unwrap().n,
        -Vec3::Z,
        1e-6
    ));
}

#[test]
fn disk_sampling() {
    // on the axis at height h: Ω = 2π(1 − h/√(h² + r²))
    let (r, h) = (1.5f64, 2.0f64);
    let s = Shape::Disk(Disk::new(&sc(Vec3::splat(r as f32)), false));
    let omega = 2.0 * PI64 * (1.0 - h / (h * h + r * r).sqrt());
    let on = |p: Vec3| p.z.abs() < 1e-5 && p.truncate().length() <= 1.5 + 1e-5;
    check_sampling(&s, on, Vec3::new(0.0, 0.0, h as f32), omega, true, 3);
}

// ---------------------------------------------------------------- sphere

#[test]
fn sphere_intersections() {
    let s = Shape::Sphere(Sphere::new(Vec3::new(1.0, 0.0, 0.0), 2.0, &tr(Vec3::Z), false));
    if let Shape::Sphere(sp) = &s {
        assert!(
            close(sp.center(), Vec3::new(1.0, 0.0, 1.0), 1e-6) && (sp.radius() - 2.0).abs() < 1e-6
        );
    }
    let r = Ray::infinite(Vec3::new(1.0, 0.0, -5.0), Vec3::Z);
    let si = hit(&s, &r).unwrap();
    assert!((si.t - 4.0).abs() < 1e-5);
    assert!(close(si.p, Vec3::new(1.0, 0.0, -1.0), 1e-5));
    assert!(close(si.n, -Vec3::Z, 1e-5));
    assert!((si.uv.y - 1.0).abs() < 1e-4, "{}", si.uv); // south pole: θ = π
                                                        // equator hit: local point (0, 1, 0) → φ = π/2, θ = π/2
    let si = hit(&s, &Ray::infinite(Vec3::new(1.0, 5.0, 1.0), -Vec3::Y)).unwrap();
    assert!((si.t - 3.0).abs() < 1e-5 && close(si.n, Vec3::Y, 1e-5));
    assert!((si.uv - Vec2::new(0.25, 0.5)).length() < 1e-5, "{}", si.uv);
    assert_frame(&si);
    // from inside: the far side
    let si = hit(&s, &Ray::infinite(Vec3::new(1.0, 0.0, 1.0), Vec3::X)).unwrap();
    assert!((si.t - 2.0).abs() < 1e-5 && close(si.n, Vec3::X, 1e-5));
    // misses and t_max
    assert!(hit(&s, &Ray::infinite(Vec3::new(1.0, 2.1, -5.0), Vec3::Z)).is_none());
    assert!(hit(&s, &Ray::new(Vec3::new(1.0, 0.0, -5.0), Vec3::Z, 3.9)).is_none());
    assert!(hit(&s, &Ray::infinite(Vec3::new(1.0, 0.0, -5.0), -Vec3::Z)).is_none());
    // leaving the surface outwards from an offset origin: no self-hit
    let si = hit(&s, &r).unwrap();
    let out = si.spawn_ray(-Vec3::Z);
    assert!(hit(&s, &out).is_none());
    // going inwards from the surface: the far side at distance 4
    let inward = Ray::infinite(offset_ray_origin(si.p, si.n, Vec3::Z), Vec3::Z);
    let far = hit(&s, &inward).unwrap();
    assert!((far.t - 4.0).abs() < 1e-3 && close(far.n, Vec3::Z, 1e-4));
    // flip_normals and negative scale both point the normals inwards
    let f = Shape::Sphere(Sphere::new(Vec3::new(1.0, 0.0, 0.0), 2.0, &tr(Vec3::Z), true));
    assert!(close(hit(&f, &r).unwrap().n, Vec3::Z, 1e-5));
    let neg = Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0, &sc(Vec3::new(-1.0, 1.0, 1.0)), false));
    assert!(close(
        hit(&neg, &Ray::infinite(Vec3::new(0.0, 0.0, -5.0), Vec3::Z)).unwrap().n,
        Vec3::Z,
        1e-5
    ));
    // to_world applies after centre and radius: centre (1,0,0) scaled by 2 → (2,0,0), radius 2
    let s2 = Sphere::new(Vec3::X, 1.0, &sc(Vec3::splat(2.0)), false);
    assert!(close(s2.center(), Vec3::new(2.0, 0.0, 0.0), 1e-6) && (s2.radius() - 2.0).abs() < 1e-6);
}

#[test]
fn sphere_far_and_grazing_rays_are_accurate() {
    // A small sphere far away: the stable quadratic keeps the hit on the surface.
    let s =
        Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 1000.0), 0.01, &Transform::IDENTITY, false));
    let si = hit(&s, &Ray::infinite(Vec3::ZERO, Vec3::Z)).unwrap();
    assert!((si.t - 999.99).abs() < 1e-3, "{}", si.t);
    let d = Vec3::new(0.0099, 0.0, 1000.0).normalize();
    assert!(hit(&s, &Ray::infinite(Vec3::ZERO, d)).is_some());
    let d = Vec3::new(0.0101, 0.0, 1000.0).normalize();
    assert!(hit(&s, &Ray::infinite(Vec3::ZERO, d)).is_none());
}

/// The intersection runs in single precision: rays leaving a sphere's surface (from the
/// offset origin every path vertex uses) must not find the surface again, and rays going
/// in must find the far side where double precision puts it, for unit and large spheres far
/// from and near the origin (random points and directions, fixed seed).
#[test]
fn sphere_rays_from_the_surface_in_single_precision() {
    let mut rng = crate::sampling::Pcg32::new(11, 5);
    for (c, r) in [
        (Vec3::new(0.0, 0.0, 1000.0), 5.0f32),
        (Vec3::new(0.3, -0.2, 0.1), 1.0),
        (Vec3::new(-50.0, 20.0, 400.0), 3.0),
        (Vec3::new(0.0, -1000.0, 0.0), 999.0),
    ] {
        let s = Shape::Sphere(Sphere::new(c, r, &Transform::IDENTITY, false));
        for _ in 0..2000 {
            let n = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                rng.next_f32(),
                rng.next_f32(),
            ));
            let d = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                rng.next_f32(),
                rng.next_f32(),
            ));
            let p = c + n * r;
            let cos = d.dot(n);
            if cos.abs() < 0.05 {
                continue; // grazing: no chord to speak of
            }
            let ray = Ray::infinite(offset_ray_origin(p, n, d), d);
            match hit(&s, &ray) {
                Some(si) if cos > 0.0 => {
                    panic!("r = {r}: self-hit at t = {} leaving the surface", si.t)
                }
                None if cos < 0.0 => panic!("r = {r}: no far side going in"),
                Some(si) => {
                    // the far root from the ray's actual origin, in double precision
                    let (o, d, c) = (ray.o.as_dvec3(), ray.d.as_dvec3(), c.as_dvec3());
                    let oc = o - c;
                    let b = oc.dot(d);
                    let far = -b + (b * b - oc.dot(oc) + (r as f64).powi(2)).sqrt();
                    assert!(
                        (si.t as f64 - far).abs() <= 1e-5 * (1.0 + far + c.abs().max_element()),
                        "r = {r}: t {} vs {far}",
                        si.t
                    );
                }
                None => {}
            }
        }
    }
}

#[test]
fn sphere_sampling() {
    let (r, d) = (1.3f64, 3.0f64);
    let c = Vec3::new(0.5, -0.25, 0.75);
    let s = Shape::Sphere(Sphere::new(c, r as f32, &Transform::IDENTITY, false));
    let on = |p: Vec3| ((p - c).length() - 1.3).abs() < 1e-4;
    // outside: the cone, Ω = 2π(1 − √(1 − r²/d²))
    let omega = 2.0 * PI64 * (1.0 - (1.0 - r * r / (d * d)).sqrt());
    check_sampling(&s, on, c + Vec3::new(0.0, d as f32, 0.0), omega, true, 4);
    // far away (tiny cone)
    let d = 200.0f64;
    let omega = 2.0 * PI64 * (r * r / (d * d)) / (1.0 + (1.0 - r * r / (d * d)).sqrt());
    check_sampling(&s, on, c + Vec3::new(0.0, 0.0, d as f32), omega, true, 5);
    // inside: area sampling, every direction hits once → 4π
    check_sampling(&s, on, c + Vec3::new(0.3, 0.2, -0.4), 4.0 * PI64, true, 6);
    // flipped normals do not change the densities
    let f = Shape::Sphere(Sphere::new(c, r as f32, &Transform::IDENTITY, true));
    check_sampling(&f, on, c + Vec3::new(0.3, 0.2, -0.4), 4.0 * PI64, true, 7);
}

/// Regression: the cone sample's distance is solved in single precision; near the silhouette
/// of a small far sphere (veach's r = 0.0333 light seen from 15 m) the textbook radicand
/// r² − dc²·sin² θ cancels. The sampled point must lie on the sphere, along `wi` at `dist`,
/// and `dist` must match the double-precision distance of the same sample.
#[test]
fn sphere_cone_samples_stay_on_the_surface_at_the_silhouette() {
    let c = Vec3::new(-3.75, 0.0, 0.0);
    let r = 0.03333f32;
    let s = Shape::Sphere(Sphere::new(c, r, &Transform::IDENTITY, false));
    let reference = Vec3::new(2.0, -4.0, 14.0);
    let mut rng = crate::sampling::Pcg32::new(7, 0);
    let mut worst = 0.0f32;
    for i in 0..20_000 {
        // half the samples within 1e-3 of the cone's rim
        let uy = if i % 2 == 0 { rng.next_f32() } else { 1.0 - 1e-3 * rng.next_f32() };
        let u = Vec2::new(rng.next_f32(), uy.min(1.0 - f32::EPSILON));
        let ds = s.sample_direction(reference, u, UvRequest::Skip).expect("outside the sphere");
        assert!(
            ((ds.p - c).length() - r).abs() < 1e-6,
            "off the sphere by {}",
            (ds.p - c).length() - r
        );
        assert!((ds.wi.length() - 1.0).abs() < 1e-6);
        let along = reference + ds.wi * ds.dist;
        assert!((along - ds.p).length() < 2e-3 * r, "{} from the point", (along - ds.p).length());
        assert!(
            close(ds.n, (ds.p - c) / r, 1e-5) && ds.n.dot(ds.wi) <= 1e-4,
            "the sampled side faces the reference"
        );
        // the distance of the intended sample, in double precision
        let dc = (c.as_dvec3() - reference.as_dvec3()).length();
        let (r64, uy64) = (r as f64, u.y as f64);
        let sin2_max = r64 * r64 / (dc * dc);
        let cos_t = 1.0 - uy64 * (1.0 - (1.0 - sin2_max).sqrt());
        let exact = dc * cos_t - (r64 * r64 - dc * dc * (1.0 - cos_t * cos_t)).max(0.0).sqrt();
        worst = worst.max(((ds.dist as f64 - exact).abs() / r64) as f32);
    }
    // single precision cancels to 1.8e-4·r here; the factored radicand keeps 4.5e-5·r
    assert!(worst < 1e-4, "distance off by {worst}·r");
}

// ---------------------------------------------------------------- cylinder

#[test]
fn cylinder_intersections() {
    let s = Shape::Cylinder(
        Cylinder::new(Vec3::ZERO, Vec3::Z, 1.0, &Transform::IDENTITY, false).unwrap(),
    );
    assert!((s.surface_area() - 2.0 * std::f32::consts::PI).abs() < 1e-5);
    let si = hit(&s, &Ray::infinite(Vec3::new(3.0, 0.0, 0.5), -Vec3::X)).unwrap();
    assert!(
        (si.t - 2.0).abs() < 1e-5
            && close(si.p, Vec3::new(1.0, 0.0, 0.5), 1e-5)
            && close(si.n, Vec3::X, 1e-5)
    );
    assert!(
        (si.uv - Vec2::new(0.0, 0.5)).length() < 1e-5
            || (si.uv - Vec2::new(1.0, 0.5)).length() < 1e-5,
        "{}",
        si.uv
    );
    assert_frame(&si);
    // from inside: the wall ahead, normal still outward
    let si = hit(&s, &Ray::infinite(Vec3::new(0.0, 0.0, 0.5), Vec3::Y)).unwrap();
    assert!((si.t - 1.0).abs() < 1e-5 && close(si.n, Vec3::Y, 1e-5));
    assert!((si.uv - Vec2::new(0.25, 0.5)).length() < 1e-5, "{}", si.uv);
    // above the z range: miss; through the open top onto the far wall
    assert!(hit(&s, &Ray::infinite(Vec3::new(3.0, 0.0, 1.5), -Vec3::X)).is_none());
    let d = Vec3::new(-4.0, 0.0, -1.0).normalize();
    let si = hit(&s, &Ray::infinite(Vec3::new(3.0, 0.0, 1.6), d)).unwrap();
    assert!(
        (si.t - 17f32.sqrt()).abs() < 1e-4
            && close(si.p, Vec3::new(-1.0, 0.0, 0.6), 1e-4)
            && close(si.n, -Vec3::X, 1e-4)
    );
    // along the axis: miss; t_max
    assert!(hit(&s, &Ray::infinite(Vec3::new(0.0, 0.0, -1.0), Vec3::Z)).is_none());
    assert!(hit(&s, &Ray::new(Vec3::new(3.0, 0.0, 0.5), -Vec3::X, 1.9)).is_none());
    // flip_normals
    let f = Shape::Cylinder(
        Cylinder::new(Vec3::ZERO, Vec3::Z, 1.0, &Transform::IDENTITY, true).unwrap(),
    );
    assert!(close(
        hit(&f, &Ray::infinite(Vec3::new(3.0, 0.0, 0.5), -Vec3::X)).unwrap().n,
        -Vec3::X,
        1e-5
    ));
    // p0/p1/radius and to_world: axis along x from 0 to 2, radius 0.5, moved by (0, 1, 0)
    let s = Shape::Cylinder(
        Cylinder::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), 0.5, &tr(Vec3::Y), false).unwrap(),
    );
    let si = hit(&s, &Ray::infinite(Vec3::new(1.0, 1.0, 3.0), -Vec3::Z)).unwrap();
    assert!(
        (si.t - 2.5).abs() < 1e-5
            && close(si.p, Vec3::new(1.0, 1.0, 0.5), 1e-5)
            && close(si.n, Vec3::Z, 1e-5)
    );
    assert!((si.uv.y - 0.5).abs() < 1e-5);
    assert!(hit(&s, &Ray::infinite(Vec3::new(2.1, 1.0, 3.0), -Vec3::Z)).is_none());
    assert!((s.surface_area() - 2.0 * std::f32::consts::PI).abs() < 1e-5);
    assert!(Cylinder::new(Vec3::ZERO, Vec3::ZERO, 1.0, &Transform::IDENTITY, false).is_err());
}

#[test]
fn cylinder_sampling() {
    // radius r, length 2L, reference at the centre of the axis:
    // Ω = 4π L / √(L² + r²)
    let (r, l) = (0.8f64, 1.1f64);
    let s = Shape::Cylinder(
        Cylinder::new(
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 2.0 * l as f32),
            r as f32,
            &Transform::IDENTITY,
            false,
        )
        .unwrap(),
    );
    let on =
        |p: Vec3| (p.truncate().length() - 0.8).abs() < 1e-4 && p.z >= -1e-5 && p.z <= 2.2 + 1e-5;
    let omega = 4.0 * PI64 * l / (l * l + r * r).sqrt();
    check_sampling(&s, on, Vec3::new(0.0, 0.0, l as f32), omega, true, 8);
}

// ---------------------------------------------------------------- meshes

fn triangle_mesh(to_world: &Transform) -> Mesh {
    Mesh::new(
        vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)],
        None,
        Some(vec![Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)]),
        vec![[0, 1, 2]],
        to_world,
        false,
        false,
    )
    .unwrap()
}

#[test]
fn mesh_intersections() {
    let m = Shape::Mesh(triangle_mesh(&tr(Vec3::new(0.0, 0.0, 1.0))));
    let si = hit(&m, &Ray::infinite(Vec3::new(0.5, 1.0, 4.0), -Vec3::Z)).unwrap();
    assert!(
        (si.t - 3.0).abs() < 1e-6
            && close(si.p, Vec3::new(0.5, 1.0, 1.0), 1e-6)
            && close(si.n, Vec3::Z, 1e-6)
    );
    assert!((si.uv - Vec2::new(0.25, 0.5)).length() < 1e-6);
    assert!(close(si.sh_frame.s, Vec3::X, 1e-6)); // dp/du from the uvs
    assert!(hit(&m, &Ray::infinite(Vec3::new(1.5, 1.5, 4.0), -Vec3::Z)).is_none());
    assert!(hit(&m, &Ray::new(Vec3::new(0.5, 1.0, 4.0), -Vec3::Z, 2.9)).is_none());
    // cube: top face
    let c = Shape::Mesh(cube(&sc(Vec3::splat(0.5)), false));
    assert_eq!(c.prim_count(), 12);
    assert!((c.surface_area() - 6.0).abs() < 1e-5);
    for (o, n) in [
        (Vec3::Z, Vec3::Z),
        (-Vec3::Z, -Vec3::Z),
        (Vec3::X, Vec3::X),
        (-Vec3::X, -Vec3::X),
        (Vec3::Y, Vec3::Y),
        (-Vec3::Y, -Vec3::Y),
    ] {
        let r = Ray::infinite(o * 3.0 + (Vec3::ONE - n.abs()) * 0.1, -o);
        let si = hit(&c, &r).unwrap();
        assert!((si.t - 2.5).abs() < 1e-5, "{}", si.t);
        assert!(close(si.n, n, 1e-6) && close(si.sh_frame.n, n, 1e-6));
        assert!(si.uv.cmpge(Vec2::ZERO).all() && si.uv.cmple(Vec2::ONE).all());
        // from inside, the same face with the same (outward) normal
        let si = hit(&c, &Ray::infinite(Vec3::ZERO, o)).unwrap();
        assert!((si.t - 0.5).abs() < 1e-5 && close(si.n, n, 1e-6));
    }
    let f = Shape::Mesh(cube(&Transform::IDENTITY, true));
    let si = hit(&f, &Ray::infinite(Vec3::new(0.1, 0.2, 3.0), -Vec3::Z)).unwrap();
    assert!(close(si.n, -Vec3::Z, 1e-6) && close(si.sh_frame.n, -Vec3::Z, 1e-6));
    // rotated cube: face normals rotate
    let rot = Transform::rotate(Vec3::Z, 45.0).unwrap();
    let c = Shape::Mesh(cube(&rot, false));
    let si = hit(&c, &Ray::infinite(Vec3::new(5.0, 0.0, 0.0), -Vec3::X)).unwrap();
    assert!((si.t - (5.0 - 2f32.sqrt())).abs() < 1e-4);
    assert!(
        close(si.n, Vec3::new(1.0, 1.0, 0.0).normalize(), 1e-4)
            || close(si.n, Vec3::new(1.0, -1.0, 0.0).normalize(), 1e-4)
    );
}

#[test]
fn mesh_without_uvs_uses_barycentrics() {
    let m = Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        None,
        None,
        vec![[0, 1, 2]],
        &Transform::IDENTITY,
        false,
        true,
    )
    .unwrap();
    let s = Shape::Mesh(m);
    let si = hit(&s, &Ray::infinite(Vec3::new(0.2, 0.3, 1.0), -Vec3::Z)).unwrap();
    assert!((si.uv - Vec2::new(0.2, 0.3)).length() < 1e-6);
}

#[test]
fn smooth_normals_are_angle_weighted() {
    // Vertex 0 is shared by a face in z = 0 (normal +z, angle 90° at the vertex) and a face in
    // x = 0 (normal −x, angle 45°): Mitsuba's normal is normalize(π/2·ẑ − π/4·x̂) = (−1, 0, 2)/√5.
    // (Area weighting or plain averaging would give (−1, 0, 1)/√2.)
    let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(0.0, 1.0, 1.0)];
    let idx = vec![[0, 1, 2], [0, 3, 4]];
    let m = Mesh::new(pos.clone(), None, None, idx.clone(), &Transform::IDENTITY, false, false)
        .unwrap();
    let n0 = m.normals.as_ref().unwrap()[0];
    assert!(close(n0, Vec3::new(-1.0, 0.0, 2.0).normalize(), 1e-5), "{n0}");
    // interpolated at a hit near vertex 0 on face 0
    let s = Shape::Mesh(m);
    let r = Ray::infinite(Vec3::new(1e-4, 1e-4, 1.0), -Vec3::Z);
    let si = hit(&s, &r).unwrap();
    assert!(close(si.sh_frame.n, n0, 1e-3) && close(si.n, Vec3::Z, 1e-6));
    // flat shading
    let flat = Shape::Mesh(
        Mesh::new(pos.clone(), None, None, idx.clone(), &Transform::IDENTITY, false, true).unwrap(),
    );
    let si = hit(&flat, &r).unwrap();
    assert!(close(si.sh_frame.n, Vec3::Z, 1e-6));
    // flip_normals flips both
    let fl =
        Shape::Mesh(Mesh::new(pos, None, None, idx, &Transform::IDENTITY, true, false).unwrap());
    let si = hit(&fl, &r).unwrap();
    assert!(close(si.sh_frame.n, -n0, 1e-3) && close(si.n, -Vec3::Z, 1e-6));
    // octahedron: by symmetry the vertex normals are the vertex directions
    let v = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    let mut faces = Vec::new();
    for (a, b) in [(0u32, 2u32), (2, 1), (1, 3), (3, 0)] {
        faces.push([a, b, 4]);
        faces.push([b, a, 5]);
    }
    let m = Mesh::new(v.to_vec(), None, None, faces, &sc(Vec3::splat(2.0)), false, false).unwrap();
    for (i, n) in m.normals.as_ref().unwrap().iter().enumerate() {
        assert!(close(*n, v[i], 1e-5), "vertex {i}: {n}");
    }
    // outward geometric normals
    for f in 0..8 {
        let [a, b, c] = m.triangle(f);
        assert!((b - a).cross(c - a).dot(a + b + c) > 0.0);
    }
}

#[test]
fn mesh_validation_and_degenerate_triangles() {
    let id = Transform::IDENTITY;
    assert!(Mesh::new(vec![Vec3::ZERO, Vec3::X], None, None, vec![[0, 1, 2]], &id, false, false)
        .is_err());
    assert!(Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::new(f32::NAN, 0.0, 0.0)],
        None,
        None,
        vec![[0, 1, 2]],
        &id,
        false,
        false
    )
    .is_err());
    assert!(Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        Some(vec![Vec3::Z]),
        None,
        vec![[0, 1, 2]],
        &id,
        false,
        false
    )
    .is_err());
    // degenerate triangles (first, middle, last) are never sampled
    let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(2.0, 0.0, 0.0)];
    let idx = vec![[0, 1, 3], [0, 1, 2], [1, 1, 1], [0, 2, 1], [2, 2, 0]];
    let m = Mesh::new(pos, None, None, idx, &id, false, false).unwrap();
    assert!((m.surface_area() - 1.0).abs() < 1e-6);
    assert!(m.normals.as_ref().unwrap().iter().all(|n| n.is_finite()));
    let mut rng = crate::sampling::Pcg32::new(1, 2);
    for i in 0..10_000 {
        let u = if i < 4 {
            Vec2::new([0.0, 0.5, 0.999_999_9, 1.0 - f32::EPSILON][i], 0.3)
        } else {
            crate::testkit::u2(&mut rng)
        };
        let ps = m.sample_position(u);
        assert!(
            ps.p.is_finite() && ps.n.is_finite() && (ps.n.length() - 1.0).abs() < 1e-5,
            "{ps:?}"
        );
        assert!(ps.p.z == 0.0 && ps.p.x + ps.p.y <= 1.0 + 1e-6 && ps.p.x >= 0.0 && ps.p.y >= 0.0);
    }
    // a mesh with no area cannot be sampled
    let z = Shape::Mesh(
        Mesh::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::X],
            None,
            None,
            vec![[0, 1, 2]],
            &id,
            false,
            false,
        )
        .unwrap(),
    );
    assert_eq!(z.surface_area(), 0.0);
    assert!(z.sample_direction(Vec3::Z, Vec2::splat(0.5), super::UvRequest::Compute).is_none());
    assert_eq!(
        z.pdf_direction(Vec3::Z, &super::SurfacePoint { p: Vec3::ZERO, n: Vec3::Z, prim: 0 }),
        0.0
    );
}

#[test]
fn mesh_sampling() {
    // one triangle: Ω from the Van Oosterom–Strackee formula
    let m = Shape::Mesh(triangle_mesh(&Transform::IDENTITY));
    let solid_angle = |refp: Vec3| {
        let [a, b, c] = [Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)]
            .map(|v| (v - refp).as_dvec3());
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let num = a.dot(b.cross(c)).abs();
        let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        let omega = 2.0 * num.atan2(den);
        if omega < 0.0 {
            omega + 2.0 * PI64
        } else {
            omega
        }
    };
    let on = |p: Vec3| p.z.abs() < 1e-6 && p.x >= -1e-6 && p.y >= -1e-6 && p.x + p.y <= 2.0 + 1e-5;
    // near (spherical-triangle sampling, density 1/Ω: the estimate of Ω has no variance) and
    // far (Ω < 3·10⁻⁴ sr: area sampling)
    for (k, refp) in
        [Vec3::new(0.3, 0.4, 1.2), Vec3::new(-0.5, 0.2, -0.8), Vec3::new(40.0, 70.0, 150.0)]
            .into_iter()
            .enumerate()
    {
        check_sampling(&m, on, refp, solid_angle(refp), true, 9 + 20 * k as u64);
    }
    assert!(solid_angle(Vec3::new(40.0, 70.0, 150.0)) < 3e-4);
    // a cube from inside: 4π; uneven triangle sizes exercise the area CDF
    let t = sc(Vec3::new(1.0, 2.0, 0.5))
        .then(&Transform::rotate(Vec3::new(1.0, 1.0, 0.0), 30.0).unwrap());
    let c = Shape::Mesh(cube(&t, false));
    let inv = t.inverse();
    let on = |p: Vec3| {
        let l = inv.point(p);
        l.abs().max_element() <= 1.0 + 1e-4 && l.abs().max_element() >= 1.0 - 1e-4
    };
    assert!((c.surface_area() - 8.0 * (2.0 + 0.5 + 1.0)).abs() < 1e-4);
    check_sampling(&c, on, t.point(Vec3::new(0.2, -0.5, 0.1)), 4.0 * PI64, true, 10);
}

/// Smooth vertex normals are Mitsuba's angle-weighted sums (each face's unit normal times its
/// angle at the vertex, the angle from acos of the normalised edges, here in f64) to 1e-5, and
/// the same bits on any number of threads.
#[test]
fn smooth_normals_are_angle_weighted_on_any_thread_count() {
    let mut r = crate::sampling::Pcg32::new(5, 2);
    let n = 160u32; // 51,200 triangles: more vertices than one thread's share
    let (pos, idx) = crate::testkit::scenes::grid_mesh(n, |i, j| {
        let jitter = Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 0.3;
        Vec3::new(i as f32, j as f32, 0.0) + jitter + Vec3::Z * (i as f32 * 0.2).sin()
    });
    let mut want = vec![glam::DVec3::ZERO; pos.len()];
    for tri in &idx {
        let v = tri.map(|i| pos[i as usize].as_dvec3());
        let nf = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        for k in 0..3 {
            let d0 = (v[(k + 1) % 3] - v[k]).normalize();
            let d1 = (v[(k + 2) % 3] - v[k]).normalize();
            want[tri[k] as usize] += nf * d0.dot(d1).clamp(-1.0, 1.0).acos();
        }
    }
    let build = |threads: usize| {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| {
            Mesh::new(pos.clone(), None, None, idx.clone(), &Transform::IDENTITY, false, false)
                .unwrap()
        })
    };
    let one = build(1);
    let normals = one.normals.as_ref().unwrap();
    for (got, want) in normals.iter().zip(&want) {
        assert!((got.as_dvec3() - want.normalize()).length() < 1e-5, "{got} vs {want}");
    }
    for threads in [2, 3] {
        let other = build(threads);
        let bits = |m: &Mesh| {
            m.normals
                .as_ref()
                .unwrap()
                .iter()
                .map(|n| n.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&one), bits(&other), "{threads} threads");
    }
}
