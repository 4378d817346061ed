//! Phase-function tests: normalisation, reciprocity, exact sampling (χ² against the density,
//! p/pdf = 1), and the moments that define them (HG's mean cosine is g; Rayleigh's mean
//! cos² θ is 2/5).

use glam::{Vec2, Vec3};

use super::*;
use crate::sampling::Pcg32;
use crate::testkit::chi2::{directions_pvalue, CapGrid};

/// The phase functions under test.
fn family() -> Vec<PhaseFunction> {
    let hg = |g: f32| PhaseFunction::HenyeyGreenstein(HenyeyGreenstein::new(g).unwrap());
    vec![
        PhaseFunction::Isotropic(Isotropic),
        hg(0.0),
        hg(0.3),
        hg(-0.6),
        hg(0.9),
        hg(2e-4),
        PhaseFunction::Rayleigh(Rayleigh),
        // a forward peak, a dip and a backward lobe; two nodes (linear in cos θ); a zero
        PhaseFunction::Tabulated(
            TabulatedPhase::new(&[0.6, 0.3, 0.1, 0.2, 0.5, 1.5, 6.0]).unwrap(),
        ),
        PhaseFunction::Tabulated(TabulatedPhase::new(&[0.2, 1.0]).unwrap()),
        PhaseFunction::Tabulated(TabulatedPhase::new(&[0.0, 1.0, 0.0, 2.0]).unwrap()),
        PhaseFunction::Blend(Box::new(
            BlendPhase::new(0.3, PhaseFunction::Isotropic(Isotropic), hg(0.8)).unwrap(),
        )),
        PhaseFunction::Blend(Box::new(
            BlendPhase::new(0.6, hg(-0.4), PhaseFunction::Rayleigh(Rayleigh)).unwrap(),
        )),
    ]
}

fn wo() -> Vec3 {
    Vec3::new(0.3, -0.5, 0.8).normalize()
}

/// 2π ∫ p dμ over the scattering angle's cosine by a fine midpoint rule (p depends on μ only).
#[test]
fn every_phase_function_integrates_to_one() {
    let wo = wo();
    let frame = crate::geometry::Frame::from_normal(-wo);
    for p in family() {
        let n = 200_000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let mu = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            let s = (1.0 - mu * mu).sqrt();
            let wi = frame.to_world(Vec3::new(s as f32, 0.0, mu as f32));
            sum += p.eval(wo, wi) as f64 * 2.0 / n as f64;
        }
        let total = 2.0 * std::f64::consts::PI * sum;
        assert!((total - 1.0).abs() < 1e-4, "{p:?}: {total}");
    }
}

#[test]
fn phase_functions_are_reciprocal_and_sample_exactly() {
    let mut r = Pcg32::new(3, 5);
    for p in family() {
        for _ in 0..200 {
            let a = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                r.next_f32(),
                r.next_f32(),
            ));
            let b = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(
                r.next_f32(),
                r.next_f32(),
            ));
            assert!((p.eval(a, b) - p.eval(b, a)).abs() <= 1e-6 * p.eval(a, b), "{p:?}");
            let s = p.sample(a, r.next_f32(), Vec2::new(r.next_f32(), r.next_f32()));
            assert!((s.wi.length() - 1.0).abs() < 1e-5, "{p:?}: {}", s.wi);
            assert_eq!(s.weight, 1.0);
            let pdf = p.pdf(a, s.wi);
            assert!((s.pdf - pdf).abs() <= 1e-5 * pdf, "{p:?}: {} vs {pdf}", s.pdf);
        }
    }
}

/// Pearson's χ² of 2·10⁵ samples against ∫ p dω per cell (20 × 40 cells on the sphere, more
/// quadrature points for the sharp HG lobe), p > 0.01 / tests.
#[test]
fn sampled_directions_follow_the_density() {
    let family = family();
    let wo = wo();
    for (k, p) in family.iter().enumerate() {
        let mut r = Pcg32::new(17, k as u64);
        let pv = directions_pvalue(
            &CapGrid::SPHERE.with_sub(24),
            200_000,
            || Some(p.sample(wo, r.next_f32(), Vec2::new(r.next_f32(), r.next_f32())).wi),
            |wi| p.eval(wo, wi) as f64,
        );
        assert!(pv > 0.01 / family.len() as f64, "{p:?}: p = {pv}");
    }
}

/// g is the mean cosine of the scattering angle; Rayleigh's mean cos² θ is 2/5. Within four
/// standard errors of 2·10⁵ samples.
#[test]
fn moments_of_the_scattering_angle() {
    let wo = wo();
    let moment = |p: &PhaseFunction, f: fn(f64) -> f64| {
        let mut r = Pcg32::new(9, 1);
        let n = 200_000;
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let wi = p.sample(wo, r.next_f32(), Vec2::new(r.next_f32(), r.next_f32())).wi;
            let v = f(-(wo.dot(wi)) as f64);
            s += v;
            s2 += v * v;
        }
        let mean = s / n as f64;
        (mean, ((s2 / n as f64 - mean * mean) / n as f64).sqrt())
    };
    for g in [-0.6f32, 0.3, 0.9] {
        let p = PhaseFunction::HenyeyGreenstein(HenyeyGreenstein::new(g).unwrap());
        let (m, se) = moment(&p, |mu| mu);
        assert!((m - g as f64).abs() <= 4.0 * se, "g = {g}: mean cosine {m} ± {se}");
    }
    let (m, se) = moment(&PhaseFunction::Rayleigh(Rayleigh), |mu| mu * mu);
    assert!((m - 0.4).abs() <= 4.0 * se, "Rayleigh: mean cos² {m} ± {se}");
    let (m, se) = moment(&PhaseFunction::Rayleigh(Rayleigh), |mu| mu);
    assert!(m.abs() <= 4.0 * se, "Rayleigh is symmetric: mean cosine {m} ± {se}");
}

#[test]
fn parameters_out_of_range_are_errors() {
    for g in [-1.0f32, 1.0, 1.5, f32::NAN] {
        assert!(HenyeyGreenstein::new(g).is_err(), "g = {g}");
    }
    let iso = || PhaseFunction::Isotropic(Isotropic);
    for w in [-0.1f32, 1.1, f32::NAN] {
        assert!(BlendPhase::new(w, iso(), iso()).is_err(), "weight = {w}");
    }
    assert!(BlendPhase::new(1.0, iso(), iso()).is_ok());
    for values in [&[1.0f32][..], &[0.0, 0.0, 0.0], &[1.0, -0.1, 1.0], &[1.0, f32::NAN]] {
        assert!(TabulatedPhase::new(values).is_err(), "values = {values:?}");
    }
}
