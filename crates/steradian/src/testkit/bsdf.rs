//! Checks every BSDF must pass: sampling matches the density (χ² test), a sample's weight is
//! eval·|cos|/pdf and its pdf is `pdf()`, sampled directions are unit vectors, and the
//! directional albedo (energy conservation); with the microfacet parameter grid the rough
//! BSDFs' tests share.

use glam::{Vec2, Vec3};

use super::chi2::{chi2_test, CapGrid};
use crate::bsdf::{Bsdf, MicrofacetDistribution, MicrofacetKind, ShadingPoint};
use crate::sampling::Pcg32;

/// The shading point the checks evaluate BSDFs at (a flat surface at uv (0.3, 0.6)).
pub fn sp() -> ShadingPoint {
    ShadingPoint::at_uv(Vec2::new(0.3, 0.6))
}

/// The unit direction at polar angle θ and azimuth φ (degrees) in the local frame.
pub fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (st, ct) = theta_deg.to_radians().sin_cos();
    let (sp, cp) = phi_deg.to_radians().sin_cos();
    Vec3::new(st * cp, st * sp, ct)
}

/// Microfacet distributions for every kind (Beckmann, GGX) × visible-normal sampling (on, off)
/// × roughness (α_u, α_v) of `alphas`, in that nesting order (tests derive seeds from the
/// index).
pub fn microfacet_grid(alphas: &[(f32, f32)]) -> Vec<MicrofacetDistribution> {
    let mut v = vec![];
    for kind in [MicrofacetKind::Beckmann, MicrofacetKind::Ggx] {
        for vis in [true, false] {
            for &(au, av) in alphas {
                v.push(MicrofacetDistribution::new(kind, au, av, vis));
            }
        }
    }
    v
}

/// The roughnesses of the rough conductor and dielectric tests: a sharp, a medium and a wide
/// isotropic lobe, and an anisotropic one.
pub const ALPHAS: [(f32, f32); 4] = [(0.05, 0.05), (0.3, 0.3), (0.7, 0.7), (0.1, 0.4)];

/// pdf evaluations per χ² cell and axis for a microfacet lobe: sharp lobes (α < 0.1) need a
/// finer quadrature for the expected counts to be exact.
pub fn chi2_sub(d: &MicrofacetDistribution) -> usize {
    if d.alpha_u.min(d.alpha_v) < 0.1 {
        40
    } else {
        12
    }
}

/// Asserts the χ² fit ([`chi2_pvalue_sub`], 2·10⁵ samples) of `bsdf(d)` for every `d` of
/// `grid` seen from each polar angle of `thetas` (degrees, azimuth 35°), at the 1 % level over
/// the whole family (Bonferroni); test `j` of distribution `i` has seed 10·i + j.
#[track_caller]
pub fn assert_chi2_over_grid(
    grid: &[MicrofacetDistribution],
    thetas: &[f32],
    bsdf: impl Fn(MicrofacetDistribution) -> Bsdf,
) {
    let tests = grid.len() * thetas.len();
    for (i, &d) in grid.iter().enumerate() {
        for (j, &theta) in thetas.iter().enumerate() {
            let seed = (i * 10 + j) as u64;
            let p = chi2_pvalue_sub(&bsdf(d), dir(theta, 35.0), 200_000, seed, chi2_sub(&d));
            assert!(p > 0.01 / tests as f64, "{d:?} θ={theta}: p-value {p}");
        }
    }
}

/// Pearson χ² goodness-of-fit of `sample` against `pdf` on a (θ, φ) grid over the sphere
/// ([`CapGrid::SPHERE`]). Returns the p-value.
pub fn chi2_pvalue(bsdf: &Bsdf, wo: Vec3, n: usize, seed: u64) -> f64 {
    chi2_pvalue_sub(bsdf, wo, n, seed, 8)
}

/// [`chi2_pvalue`] with `sub`² pdf evaluations per cell for the expected counts (see
/// [`chi2_sub`]).
pub fn chi2_pvalue_sub(bsdf: &Bsdf, wo: Vec3, n: usize, seed: u64, sub: usize) -> f64 {
    chi2_pvalue_impl(bsdf, wo, n, seed, sub, false)
}

/// [`chi2_pvalue`] for BSDFs that also have delta lobes (e.g. `mask`'s pass-through):
/// delta samples are left out of the histogram, whose expected counts come from `pdf()`
/// (the smooth part's density, which integrates to the probability of a smooth sample).
pub fn chi2_pvalue_with_delta(bsdf: &Bsdf, wo: Vec3, n: usize, seed: u64) -> f64 {
    chi2_pvalue_impl(bsdf, wo, n, seed, 8, true)
}

fn chi2_pvalue_impl(
    bsdf: &Bsdf,
    wo: Vec3,
    n: usize,
    seed: u64,
    sub: usize,
    allow_delta: bool,
) -> f64 {
    let grid = CapGrid::SPHERE.with_sub(sub);
    let mut observed = vec![0f64; grid.nt * grid.np];
    let mut rng = Pcg32::new(seed, 11);
    let sp = sp();
    let mut delta = 0usize;
    for _ in 0..n {
        let u1 = rng.next_f32();
        let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = bsdf.sample(&sp, wo, u1, u2) {
            assert_unit(s.wi);
            if s.lobe.is_delta() {
                delta += 1;
                continue;
            }
            observed[grid.cell(s.wi).expect("the grid covers the sphere")] += 1.0;
        }
    }
    assert!(allow_delta || delta == 0, "chi2 test covers smooth lobes only");
    let expected = grid.expected(n, |w| bsdf.pdf(&sp, wo, w) as f64);
    chi2_test(&observed, &expected)
}

/// The path tracer takes sampled directions as they come, without renormalising.
#[track_caller]
fn assert_unit(wi: Vec3) {
    assert!(
        (wi.length() - 1.0).abs() < 1e-5,
        "sampled direction {wi} is not a unit vector (|wi| = {})",
        wi.length()
    );
}

/// Helmholtz reciprocity, ρ(a, c) = ρ(c, a) to `rel` of ρ, for each pair of directions.
pub fn assert_reciprocal(bsdf: &Bsdf, pairs: &[(Vec3, Vec3)], rel: f32) {
    let s = sp();
    for &(a, c) in pairs {
        let (x, y) = (bsdf.eval(&s, a, c), bsdf.eval(&s, c, a));
        assert!((x - y).abs().max_element() <= rel * x.max_element(), "{x:?} vs {y:?}");
    }
}

/// Checks that a sample's weight equals eval·|cos|/pdf and its pdf equals `pdf()`.
pub fn check_sample_consistency(bsdf: &Bsdf, wo: Vec3, seed: u64) {
    let mut rng = Pcg32::new(seed, 5);
    let sp = sp();
    for _ in 0..2000 {
        let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(s) = bsdf.sample(&sp, wo, rng.next_f32(), u2) else { continue };
        if s.lobe.is_delta() {
            continue;
        }
        let pdf = bsdf.pdf(&sp, wo, s.wi);
        assert!((pdf - s.pdf).abs() <= 1e-3 * pdf.max(1e-3), "pdf {pdf} vs sample {}", s.pdf);
        let expect = bsdf.eval(&sp, wo, s.wi) * s.wi.z.abs() / s.pdf;
        assert!(
            (expect - s.weight).abs().max_element() <= 1e-3 * expect.max_element().max(1e-3),
            "weight {:?} vs {:?}",
            s.weight,
            expect
        );
    }
}

/// Directional albedo ∫ρ cos dωi by sampling, with its standard error, per channel.
pub fn albedo(bsdf: &Bsdf, wo: Vec3, n: usize, seed: u64) -> ([f64; 3], [f64; 3]) {
    let mut rng = Pcg32::new(seed, 17);
    let sp = sp();
    let (mut s1, mut s2) = ([0f64; 3], [0f64; 3]);
    for _ in 0..n {
        let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = bsdf.sample(&sp, wo, rng.next_f32(), u2) {
            assert_unit(s.wi);
            for c in 0..3 {
                let v = s.weight[c] as f64;
                s1[c] += v;
                s2[c] += v * v;
            }
        }
    }
    let nf = n as f64;
    let mean = s1.map(|x| x / nf);
    let se = [0, 1, 2].map(|c| ((s2[c] / nf - mean[c] * mean[c]).max(0.0) / (nf - 1.0)).sqrt());
    (mean, se)
}

/// Compares `bsdfs[config]` with a table of Mitsuba 3's `eval` and `pdf` written by
/// `scripts/bsdf_table.py` (columns: config, Mitsuba's wi (our wo), Mitsuba's wo (our wi),
/// its eval, which includes |cos θ| of the sampled direction, and its pdf). Both must agree
/// to 2e-3 relative (f32 arithmetic in a different order) above a floor of 1e-4 of the
/// table's largest value.
pub fn compare_with_mitsuba_table(bsdfs: &[Bsdf], table: &str) {
    let s = sp();
    let rows: Vec<Vec<f64>> = table
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse::<f64>().expect("a number")).collect())
        .collect();
    assert!(rows.len() >= 8 * bsdfs.len(), "the table has {} rows", rows.len());
    let peak = rows.iter().map(|r| r[7].max(r[8]).max(r[9]).max(r[10])).fold(0.0, f64::max);
    let floor = 1e-4 * peak;
    let v3 = |r: &[f64]| Vec3::new(r[0] as f32, r[1] as f32, r[2] as f32);
    let mut nonzero = 0;
    for r in &rows {
        let b = &bsdfs[r[0] as usize];
        let (wo, wi) = (v3(&r[1..4]), v3(&r[4..7]));
        let f = b.eval(&s, wo, wi) * wi.z.abs();
        let pdf = b.pdf(&s, wo, wi);
        let ours = [f.x as f64, f.y as f64, f.z as f64, pdf as f64];
        for (k, (&a, &m)) in ours.iter().zip(&r[7..11]).enumerate() {
            assert!(
                (a - m).abs() <= 2e-3 * m.abs() + floor,
                "config {} wo {wo} wi {wi}: {} ours {a} vs Mitsuba {m}",
                r[0],
                ["f.r", "f.g", "f.b", "pdf"][k]
            );
        }
        nonzero += (r[7] > 0.0) as usize;
    }
    // the table must exercise the lobes, not only zeros
    assert!(nonzero * 2 >= rows.len(), "{nonzero} of {} values are non-zero", rows.len());
}
