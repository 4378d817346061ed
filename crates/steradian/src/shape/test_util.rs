//! Shared checks for the shape tests.

use glam::Vec3;

use super::Shape;
use crate::geometry::Ray;
use crate::sampling::Pcg32;
use crate::testkit::u2;

pub fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).length() <= tol
}

/// Closest hit over all primitives of `shape` (brute force).
pub fn trace(shape: &Shape, ray: &Ray) -> Option<(f32, u32)> {
    let mut best: Option<(f32, u32)> = None;
    let mut r = *ray;
    for p in 0..shape.prim_count() {
        if let Some((t, _)) = shape.intersect_prim(p, &r) {
            r.t_max = t;
            best = Some((t, p));
        }
    }
    best
}

/// Checks area and direction sampling of `shape`:
/// - sampled positions satisfy `on_surface`, have unit normals and E[1/pdf_area] = area;
/// - direction samples are consistent (`reference + wi·dist = p`), their pdf equals
///   `pdf_direction`, and tracing `wi` from `reference` hits the shape at `dist` (at the first
///   hit when `first_hit` is set: the sampled point is visible from the reference);
/// - E[1/pdf] over direction samples equals `solid_angle` (within 5 standard errors).
pub fn check_sampling(
    shape: &Shape,
    on_surface: impl Fn(Vec3) -> bool,
    reference: Vec3,
    solid_angle: f64,
    first_hit: bool,
    seed: u64,
) {
    let mut rng = Pcg32::new(seed, 11);
    let area = shape.surface_area() as f64;
    let n = 20_000;
    let mut acc = 0.0f64;
    for _ in 0..n {
        let ps = shape.sample_position(u2(&mut rng));
        assert!(on_surface(ps.p), "sampled point {} is not on the surface", ps.p);
        assert!((ps.n.length() - 1.0).abs() < 1e-4, "normal {}", ps.n);
        assert!(ps.pdf_area > 0.0 && ps.pdf_area.is_finite());
        acc += 1.0 / ps.pdf_area as f64;
    }
    let est = acc / n as f64;
    assert!((est - area).abs() <= 1e-4 * area, "E[1/pdf_area] = {est}, area = {area}");

    let n = 40_000;
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let Some(ds) = shape.sample_direction(reference, u2(&mut rng), super::UvRequest::Compute)
        else {
            continue;
        };
        assert!(ds.pdf > 0.0 && ds.pdf.is_finite());
        assert!((ds.wi.length() - 1.0).abs() < 1e-4);
        let scale = 1.0 + ds.p.abs().max_element().max(reference.abs().max_element());
        assert!(
            close(reference + ds.wi * ds.dist, ds.p, 2e-4 * scale),
            "{} vs {}",
            reference + ds.wi * ds.dist,
            ds.p
        );
        assert!(on_surface(ds.p), "direction-sampled point {} is not on the surface", ds.p);
        let pdf = shape
            .pdf_direction(reference, &super::SurfacePoint { p: ds.p, n: ds.n, prim: ds.prim });
        assert!((pdf - ds.pdf).abs() <= 1e-3 * ds.pdf, "pdf {} vs pdf_direction {}", ds.pdf, pdf);
        // brute-force visibility of the sampled point (skip grazing directions)
        if ds.wi.dot(ds.n).abs() > 1e-2 {
            let ray = Ray::new(reference, ds.wi, ds.dist * (1.0 + 1e-3) + 1e-4);
            let (t, _) = trace(shape, &ray)
                .unwrap_or_else(|| panic!("direction {} does not hit the shape", ds.wi));
            if first_hit {
                assert!(
                    (t - ds.dist).abs() <= 1e-3 * ds.dist + 1e-4,
                    "hit at {t}, sampled at {}",
                    ds.dist
                );
            } else {
                assert!(t <= ds.dist * (1.0 + 1e-3) + 1e-4);
            }
        }
        let w = 1.0 / ds.pdf as f64;
        sum += w;
        sum2 += w * w;
    }
    let mean = sum / n as f64;
    let var = (sum2 / n as f64 - mean * mean).max(0.0);
    let se = (var / n as f64).sqrt();
    assert!(
        (mean - solid_angle).abs() <= 5.0 * se + 1e-4 * solid_angle,
        "solid angle estimate {mean} ± {se}, expected {solid_angle}"
    );
}
