//! The path tracer on scenes built in code whose radiance is known in closed form: a furnace
//! (L = Le/(1 − ρ), and the partial sums for bounded depths) and a plane under a point light
//! (L = ρ/π·I·cos θ/r²). Monte Carlo estimates must lie within 5 standard errors.

use glam::Vec3;

use super::{Branches, EmitterVisibility, LastVertex, PathTracer};
use crate::geometry::Ray;
use crate::render::Job;
use crate::sampling::{warp, Pcg32};
use crate::testkit::scenes::{furnace, furnace_radiance, lit_plane, lit_plane_radiance, radiance};
use crate::testkit::MeanError;
use crate::Spectrum;

/// Emitted radiance and reflectance of the furnace tests: each channel its own case.
const LE: Spectrum = Spectrum::new(1.0, 0.5, 2.0);
const RHO: Spectrum = Spectrum::new(0.2, 0.5, 0.8);

/// The radiance estimate of `n` rays from a point inside the furnace, in directions spread
/// over the sphere (every direction has the same expectation there).
fn furnace_estimate(scene: &Job, n: u32, seed: u64) -> [MeanError; 3] {
    let mut dirs = Pcg32::new(seed, 3);
    let mut acc = [MeanError::default(); 3];
    for i in 0..n {
        let d = warp::square_to_uniform_sphere(glam::Vec2::new(dirs.next_f32(), dirs.next_f32()));
        let ray = Ray::infinite(Vec3::new(0.3, -0.2, 0.4), d);
        let [r, g, b] = radiance(scene, &ray, 1, seed ^ (i as u64) << 20);
        for (a, m) in acc.iter_mut().zip([r, g, b]) {
            a.push(m.mean());
        }
    }
    acc
}

/// The furnace estimate's bias from ray offsets, relative to the furnace's radiance: a bounce's ray leaves from
/// 10⁻⁴·(1 + |p|) off the surface (`RAY_EPSILON`), while the MIS weight of the point it hits
/// is computed from the surface point, so grazing BSDF samples and light samples of the same
/// point get weights that do not add up to 1. In the unit furnace this loses 6–8·10⁻⁵ of the
/// radiance (1.249904 for 1.25 at 20 000 rays; with RAY_EPSILON = 10⁻⁶ the loss vanishes),
/// more than 5 standard errors of an estimator this quiet.
const OFFSET_BIAS: f64 = 2e-4;

#[track_caller]
fn assert_radiance(est: &[MeanError; 3], expected: Spectrum, what: &str) {
    for (c, e) in est.iter().enumerate() {
        let slack = OFFSET_BIAS * furnace_radiance(LE, RHO, None)[c] as f64;
        e.assert_near(expected[c] as f64, 5.0, slack, &format!("{what}, channel {c}"));
    }
}

#[test]
fn furnace_radiance_is_le_over_one_minus_rho() {
    for branches in [Branches::Fixed(1), Branches::Auto] {
        let tracer = PathTracer { branches, ..Default::default() };
        let scene = furnace(LE, RHO, tracer);
        let est = furnace_estimate(&scene, 20_000, 1);
        assert_radiance(&est, furnace_radiance(LE, RHO, None), &format!("{branches:?}"));
    }
}

/// `max_depth` counts segments: 1 sees the emitter, each further one adds a bounce, with both
/// estimators at the last vertex (light sampling alone where it suffices, and MIS).
#[test]
fn furnace_depths_give_the_partial_sums() {
    for last_vertex in [LastVertex::LightOnlyWhereBounded, LastVertex::Mis] {
        for depth in [0, 1, 2, 3, 6] {
            let tracer = PathTracer {
                max_depth: Some(depth),
                branches: Branches::Fixed(1),
                last_vertex,
                ..Default::default()
            };
            let scene = furnace(LE, RHO, tracer);
            let est = furnace_estimate(&scene, 10_000, 2 + depth as u64);
            let want = furnace_radiance(LE, RHO, Some(depth));
            assert_radiance(&est, want, &format!("max_depth {depth}, {last_vertex:?}"));
        }
    }
}

/// Hidden emitters let camera rays through (Mitsuba 3.9.1's `hide_emitters`): inside the
/// furnace, whose wall emits, the camera sees past the wall to nothing, where it sees
/// Le/(1 − ρ) with the emitters shown.
#[test]
fn hidden_emitters_let_camera_rays_through() {
    let tracer = PathTracer { emitters: EmitterVisibility::Hidden, ..Default::default() };
    let scene = furnace(LE, RHO, tracer);
    let est = furnace_estimate(&scene, 2_000, 9);
    assert_radiance(&est, Spectrum::ZERO, "hidden emitters");
    assert!(est.iter().all(|e| e.mean() == 0.0), "{est:?}");
}

/// A point light's reflection is estimated exactly (next-event estimation of a delta light
/// has no variance, and the plane sees nothing else), at every depth that includes it.
#[test]
fn lit_plane_reflects_rho_over_pi_times_the_irradiance() {
    let (rho, intensity) = (Spectrum::new(0.3, 0.6, 0.9), Spectrum::new(2.0, 5.0, 1.0));
    let light = Vec3::new(0.5, 0.2, 1.0);
    for max_depth in [Some(2), Some(5), None] {
        let tracer = PathTracer { max_depth, ..Default::default() };
        let scene = lit_plane(rho, intensity, light, 4.0, tracer);
        for q in [Vec3::ZERO, Vec3::new(0.5, 0.2, 0.0), Vec3::new(-2.0, 3.0, 0.0)] {
            let eye = q + Vec3::new(-0.4, 0.3, 2.0);
            let ray = Ray::infinite(eye, (q - eye).normalize());
            let est = radiance(&scene, &ray, 64, 5);
            let want = lit_plane_radiance(rho, intensity, light, q);
            for c in 0..3 {
                let (m, w) = (est[c].mean(), want[c] as f64);
                assert!(
                    (m - w).abs() <= 1e-4 * w,
                    "max_depth {max_depth:?}, q {q}, channel {c}: {m} vs {w}"
                );
            }
        }
    }
    // the plane is one-sided: a light below it lights nothing that faces the camera
    let scene = lit_plane(rho, intensity, -light, 4.0, PathTracer::default());
    let eye = Vec3::new(0.1, 0.2, 1.0);
    let est = radiance(&scene, &Ray::infinite(eye, -eye.normalize()), 16, 6);
    assert!(est.iter().all(|e| e.mean() == 0.0), "lit from below: {:?}", est.map(|e| e.mean()));
}
