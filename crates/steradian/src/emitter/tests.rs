//! Light sampling matches the density the emitters report: for each kind of area light (the
//! sphere from outside and inside, a near and a far rectangle, disk, cylinder, triangle mesh)
//! and the constant environment, the directions `sample_direction` draws from a point are
//! binned and compared with `pdf_direction` summed over every point of the light along each
//! direction (χ² test of the shared harness, 10⁵ draws each; draws rejected for facing away
//! form one more cell). Delta lights have no density; the spot light's flux factor is checked
//! against a quadrature of its falloff instead.

use glam::{Vec2, Vec3};

use super::{AreaLight, ConstantEnvironment, Emitter, SpotLight};
use crate::geometry::{Frame, PreliminaryHit, Ray, Transform};
use crate::sampling::Pcg32;
use crate::shape::{Cylinder, Disk, Mesh, Rectangle, Shape, Sphere};
use crate::testkit::chi2::{directions_pvalue, CapGrid};
use crate::texture::Texture;
use crate::Spectrum;

/// Every point where the ray from `o` along `w` meets `shape` (all primitives, all roots),
/// as the density query takes it.
fn points_along(shape: &Shape, o: Vec3, w: Vec3) -> Vec<crate::geometry::SurfaceInteraction> {
    let mut points = vec![];
    for prim in 0..shape.prim_count() {
        let mut origin = o;
        for _ in 0..4 {
            let ray = Ray::infinite(origin, w);
            let Some((t, uv)) = shape.intersect_prim(prim, &ray) else { break };
            let si = shape.interaction(
                &ray,
                &PreliminaryHit { t, uv, shape: 0, prim, instance: crate::geometry::NO_INSTANCE },
            );
            // the next root: restart just past this one
            origin = si.p + w * 1e-4 * (1.0 + si.p.abs().max_element());
            points.push(si);
        }
    }
    points
}

/// The p-value of the directions the area light on `shape` draws from `reference`, on a grid
/// over the cap of half-angle `theta_max` around the direction to `target` (the light lies
/// inside that cap).
fn area_light_pvalue(
    shape: Shape,
    reference: Vec3,
    target: Vec3,
    theta_max: f64,
    seed: u64,
) -> f64 {
    let shapes = [shape];
    let light = Emitter::Area(AreaLight::new(0, Texture::Constant(Spectrum::ONE)));
    let frame = Frame::from_normal((target - reference).normalize());
    let grid = CapGrid { theta_max, ..CapGrid::SPHERE }.with_sub(48);
    let mut rng = Pcg32::new(seed, 13);
    directions_pvalue(
        &grid,
        100_000,
        || {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            light.sample_direction(&shapes, reference, u).map(|es| frame.to_local(es.wi))
        },
        |local| {
            let w = frame.to_world(local);
            points_along(&shapes[0], reference, w)
                .iter()
                .map(|si| light.pdf_direction(&shapes, reference, w, &si.surface_point()) as f64)
                .sum()
        },
    )
}

/// The half-angle of the smallest cap around `axis` (seen from `reference`) that holds every
/// point of `points`, widened by 5 % so the light's edge falls inside the grid.
fn cap_around(reference: Vec3, axis: Vec3, points: impl IntoIterator<Item = Vec3>) -> f64 {
    let axis = (axis - reference).normalize();
    let widest = points
        .into_iter()
        .map(|p| ((p - reference).normalize().dot(axis).clamp(-1.0, 1.0) as f64).acos())
        .fold(0.0, f64::max);
    (widest * 1.05).min(std::f64::consts::PI)
}

/// Family-wide significance (Bonferroni over the χ² tests of this file).
const TESTS: f64 = 8.0;

#[track_caller]
fn assert_fits(p: f64, what: &str) {
    assert!(p > 0.01 / TESTS, "{what}: p-value {p}");
}

#[test]
fn sphere_light_sampling_matches_its_density() {
    // seen from outside: the cone it subtends
    let (c, r, reference) = (Vec3::new(0.2, 0.1, 3.0), 1.0, Vec3::new(0.3, -0.2, 0.0));
    let sphere = Shape::Sphere(Sphere::new(c, r, &Transform::IDENTITY, false));
    let theta = ((r / (c - reference).length()) as f64).asin() * 1.05;
    assert_fits(area_light_pvalue(sphere, reference, c, theta, 1), "sphere from outside");
    // from inside (normals inwards): by area, over the whole sphere of directions
    let sphere = Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0, &Transform::IDENTITY, true));
    let reference = Vec3::new(0.3, -0.5, 0.2);
    let p = area_light_pvalue(sphere, reference, Vec3::Z, std::f64::consts::PI, 2);
    assert_fits(p, "sphere from inside");
}

#[test]
fn rectangle_light_sampling_matches_its_density() {
    // rectangles tilted by 30°, facing down: one near enough (area > distance²) to be sampled
    // by solid angle as a spherical rectangle, one sampled by area
    for (k, (scale, height, what)) in [
        (Vec3::new(1.5, 1.0, 1.0), 1.2, "near rectangle"),
        (Vec3::new(0.8, 0.5, 1.0), 2.0, "far rectangle"),
    ]
    .into_iter()
    .enumerate()
    {
        let to_world = Transform::translate(Vec3::new(0.4, 0.2, height))
            .then_after(&Transform::rotate(Vec3::X, 30.0).unwrap())
            .then_after(&Transform::scale(scale).unwrap());
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(x, y)| to_world.point(Vec3::new(x, y, 0.0)));
        let centre = to_world.point(Vec3::ZERO);
        let reference = Vec3::new(-0.3, 0.1, 0.0);
        let rect = Shape::Rectangle(Rectangle::new(&to_world, true));
        let cap = cap_around(reference, centre, corners);
        assert_fits(area_light_pvalue(rect, reference, centre, cap, 3 + 10 * k as u64), what);
    }
}

#[test]
fn disk_light_sampling_matches_its_density() {
    // a disk of radius 0.7 at z = 1.5, facing down and tilted (area sampling)
    let to_world = Transform::translate(Vec3::new(0.2, -0.3, 1.5))
        .then_after(&Transform::rotate(Vec3::Y, 25.0).unwrap())
        .then_after(&Transform::scale(Vec3::splat(0.7)).unwrap());
    let rim = (0..360).map(|k| {
        let a = (k as f32).to_radians();
        to_world.point(Vec3::new(a.cos(), a.sin(), 0.0))
    });
    let centre = to_world.point(Vec3::ZERO);
    let reference = Vec3::new(0.1, 0.2, 0.0);
    let disk = Shape::Disk(Disk::new(&to_world, true));
    let cap = cap_around(reference, centre, rim);
    assert_fits(area_light_pvalue(disk, reference, centre, cap, 4), "disk");
}

#[test]
fn cylinder_light_sampling_matches_its_density() {
    // an open tube seen from outside: area samples on its far side face away and are
    // rejected, which the density's missing mass must account for
    let cyl = Cylinder::new(
        Vec3::new(-0.5, 0.0, 2.0),
        Vec3::new(0.7, 0.3, 2.4),
        0.4,
        &Transform::IDENTITY,
        false,
    )
    .unwrap();
    let reference = Vec3::new(0.0, -0.3, 0.0);
    let p = area_light_pvalue(Shape::Cylinder(cyl), reference, Vec3::Z, std::f64::consts::PI, 5);
    assert_fits(p, "cylinder");
}

#[test]
fn mesh_light_sampling_matches_its_density() {
    // three triangles of different sizes and tilts (each chosen by area, then sampled by
    // solid angle as a spherical triangle), facing down
    let positions = vec![
        Vec3::new(-1.0, -0.5, 2.0),
        Vec3::new(0.2, -0.6, 2.2),
        Vec3::new(-0.4, 0.6, 1.8),
        Vec3::new(0.9, 0.4, 2.5),
        Vec3::new(0.3, 1.2, 1.6),
    ];
    let indices = vec![[0, 2, 1], [1, 2, 3], [2, 4, 3]];
    let mesh = Mesh::new(positions.clone(), None, None, indices, &Transform::IDENTITY, false, true)
        .unwrap();
    let reference = Vec3::new(0.1, 0.2, 0.0);
    let centre = positions.iter().sum::<Vec3>() / positions.len() as f32;
    let cap = cap_around(reference, centre, positions);
    assert_fits(area_light_pvalue(Shape::Mesh(mesh), reference, centre, cap, 6), "mesh");
}

#[test]
fn environment_sampling_matches_its_density() {
    let env = ConstantEnvironment::new(Spectrum::ONE);
    let mut rng = Pcg32::new(7, 13);
    let p = directions_pvalue(
        &CapGrid::SPHERE,
        100_000,
        || {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            env.sample_direction(Vec3::ZERO, u).map(|es| es.wi)
        },
        |w| env.pdf_direction(w) as f64,
    );
    assert_fits(p, "constant environment");
}

/// A spot light's flux is I·∫falloff dω: its flux factor matches a quadrature of the falloff
/// over the sphere (the χ² grid's, 20 × 40 cells of 32² points; the cutoff crosses cells, so
/// to 10⁻³).
#[test]
fn spot_flux_factor_is_the_integral_of_its_falloff() {
    for (cutoff, beam) in [(20.0f32, 15.0f32), (60.0, 10.0), (120.0, 90.0)] {
        let to_world = Transform::rotate(Vec3::new(1.0, 1.0, 0.0), 40.0).unwrap();
        let spot = SpotLight::new(&to_world, Spectrum::ONE, cutoff.to_radians(), beam.to_radians())
            .unwrap();
        let grid = CapGrid::SPHERE.with_sub(32);
        let integral: f64 = grid.expected(1, |w| spot.falloff(w) as f64).iter().sum();
        let factor = spot.solid_angle_factor() as f64;
        assert!(
            (integral - factor).abs() <= 1e-3 * factor,
            "cutoff {cutoff}°, beam {beam}°: ∫falloff dω = {integral}, flux factor {factor}"
        );
    }
}
