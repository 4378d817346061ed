//! Pearson's χ² goodness of fit of sampled directions against the density the sampling code
//! reports (pbrt-v4 / Mitsuba 3 style): the directions are binned on a (θ, φ) grid, each
//! cell's expected count is n·∫ pdf dω over the cell (midpoint rule), and cells with expected
//! counts below 5 are pooled.
//!
//! A test asserts `p > 0.01 / tests`: a correct sampler fails one run in a hundred over the
//! whole family of tests (Bonferroni), a density that is wrong by a few percent over a few
//! cells fails at the sample counts the tests use (10⁵ – 2·10⁵).

use std::f64::consts::PI;

use glam::Vec3;

/// A (θ, φ) grid over the cap θ ≤ `theta_max` around +z (the whole sphere for θmax = π).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapGrid {
    /// Polar extent of the grid, rad.
    pub theta_max: f64,
    /// Cells in θ.
    pub nt: usize,
    /// Cells in φ.
    pub np: usize,
    /// pdf evaluations per cell and axis for the expected counts: sharp densities (microfacet
    /// lobes with α ≲ 0.1) need more than 8 for the quadrature to be exact.
    pub sub: usize,
}

impl CapGrid {
    /// The whole sphere in 20 × 40 cells, 8² pdf evaluations per cell.
    pub const SPHERE: CapGrid = CapGrid { theta_max: PI, nt: 20, np: 40, sub: 8 };

    /// The grid with `sub`² pdf evaluations per cell.
    pub fn with_sub(self, sub: usize) -> CapGrid {
        CapGrid { sub, ..self }
    }

    /// The cell of direction `w`, `None` outside the cap.
    pub fn cell(&self, w: Vec3) -> Option<usize> {
        let t = (w.z.clamp(-1.0, 1.0) as f64).acos();
        if t > self.theta_max {
            return None;
        }
        let mut p = (w.y as f64).atan2(w.x as f64);
        if p < 0.0 {
            p += 2.0 * PI;
        }
        let it = ((t / self.theta_max * self.nt as f64) as usize).min(self.nt - 1);
        let ip = ((p / (2.0 * PI) * self.np as f64) as usize).min(self.np - 1);
        Some(it * self.np + ip)
    }

    /// `n`·∫ pdf dω over each cell (midpoint rule on `sub` × `sub` points per cell).
    pub fn expected(&self, n: usize, pdf: impl Fn(Vec3) -> f64) -> Vec<f64> {
        let (nt, np, sub) = (self.nt, self.np, self.sub);
        let mut expected = vec![0f64; nt * np];
        for it in 0..nt {
            for ip in 0..np {
                let mut acc = 0.0;
                for a in 0..sub {
                    for b in 0..sub {
                        let t0 = (it as f64 + (a as f64 + 0.5) / sub as f64) * self.theta_max
                            / nt as f64;
                        let p0 = (ip as f64 + (b as f64 + 0.5) / sub as f64) * 2.0 * PI / np as f64;
                        let w = Vec3::new(
                            (t0.sin() * p0.cos()) as f32,
                            (t0.sin() * p0.sin()) as f32,
                            t0.cos() as f32,
                        );
                        acc += pdf(w) * t0.sin();
                    }
                }
                let cell =
                    (self.theta_max / nt as f64) * (2.0 * PI / np as f64) / (sub * sub) as f64;
                expected[it * np + ip] = acc * cell * n as f64;
            }
        }
        expected
    }
}

/// The p-value of `n` draws of `sample` (a direction, or `None` for a rejected draw) against
/// the density `pdf` on `grid`. The density may integrate to less than 1: rejected draws form
/// one more cell, whose expected count is what the density leaves of `n`; it must not
/// integrate to more than 1 (+10⁻³ for the quadrature). Every direction drawn must lie in the
/// cap, and the density must vanish outside it.
pub fn directions_pvalue(
    grid: &CapGrid,
    n: usize,
    mut sample: impl FnMut() -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64,
) -> f64 {
    let mut observed = vec![0f64; grid.nt * grid.np];
    let mut rejected = 0.0;
    for _ in 0..n {
        match sample() {
            Some(w) => {
                let cell = grid.cell(w).unwrap_or_else(|| panic!("direction {w} outside the cap"));
                observed[cell] += 1.0;
            }
            None => rejected += 1.0,
        }
    }
    let mut expected = grid.expected(n, pdf);
    let accepted: f64 = expected.iter().sum();
    // A density scaled by 1 + ε changes each cell by ε only (χ² grows by ε²·n, nothing at
    // ε = 1 %), but moves the rejected cell by ε·n when the density integrates to less than 1;
    // above 1 it must fail here, with the quadrature's error allowed.
    assert!(
        accepted <= n as f64 * (1.0 + 1e-3),
        "the density integrates to {} > 1 over the cap",
        accepted / n as f64
    );
    let expected_rejected = (n as f64 - accepted).max(0.0);
    assert!(
        rejected == 0.0 || expected_rejected > 0.0,
        "{rejected} of {n} draws rejected, but the density integrates to {}",
        accepted / n as f64
    );
    observed.push(rejected);
    expected.push(expected_rejected);
    chi2_test(&observed, &expected)
}

/// χ² test with pooling of cells whose expected count is below 5; returns the p-value.
pub fn chi2_test(observed: &[f64], expected: &[f64]) -> f64 {
    let mut idx: Vec<usize> = (0..observed.len()).collect();
    idx.sort_by(|&a, &b| expected[a].partial_cmp(&expected[b]).unwrap());
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    let mut chsq = 0.0;
    let mut dof = 0i64;
    for &i in &idx {
        if expected[i] == 0.0 {
            assert!(
                observed[i] == 0.0,
                "sample in a cell of zero density (cell {i}, {} samples)",
                observed[i]
            );
            continue;
        }
        if expected[i] < 5.0 {
            pool_o += observed[i];
            pool_e += expected[i];
        } else {
            chsq += (observed[i] - expected[i]).powi(2) / expected[i];
            dof += 1;
        }
    }
    if pool_e > 0.0 {
        chsq += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    dof -= 1;
    if dof <= 0 {
        return 1.0;
    }
    chi2_survival(chsq, dof as f64)
}

/// Upper tail of the χ² distribution, Q(k/2, x/2), via the regularised incomplete gamma.
pub fn chi2_survival(x: f64, k: f64) -> f64 {
    1.0 - reg_lower_gamma(k / 2.0, x / 2.0)
}

fn reg_lower_gamma(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x < a + 1.0 {
        // series
        let mut sum = 1.0 / a;
        let mut term = sum;
        let mut n = a;
        for _ in 0..1000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        sum * (-x + a * x.ln() - ln_gamma(a)).exp()
    } else {
        // continued fraction for the upper tail (Lentz)
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / 1e-300;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < 1e-300 {
                d = 1e-300;
            }
            c = b + an / c;
            if c.abs() < 1e-300 {
                c = 1e-300;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        1.0 - (-x + a * x.ln() - ln_gamma(a)).exp() * h
    }
}

fn ln_gamma(x: f64) -> f64 {
    // Lanczos approximation (g = 7, n = 9)
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Known quantiles of the χ² distribution (tables): Q(3.841, 1) = 0.05,
    /// Q(18.307, 10) = 0.05, Q(63.691, 40) = 0.01, Q(2, 2) = e⁻¹.
    #[test]
    fn survival_matches_tables() {
        for (x, k, q) in
            [(3.841_458_8, 1.0, 0.05), (18.307_038, 10.0, 0.05), (63.690_740, 40.0, 0.01)]
        {
            let p = chi2_survival(x, k);
            assert!((p - q).abs() < 1e-6, "Q({x}, {k}) = {p}, tables {q}");
        }
        assert!((chi2_survival(2.0, 2.0) - (-1.0f64).exp()).abs() < 1e-12);
    }

    /// The harness itself: uniform directions pass against the uniform density and fail
    /// against a density tilted by 20 % towards +z (the same draws; at 10⁵ draws a 5 % tilt
    /// is not seen), and the rejected-draw cell catches a sampler that drops 3 % of its draws
    /// where its density accounts for 1 %.
    #[test]
    fn harness_accepts_the_right_density_and_rejects_a_wrong_one() {
        use crate::sampling::{warp, Pcg32};
        let draw = |seed, drop: f32| {
            let mut rng = Pcg32::new(seed, 1);
            move || {
                let w =
                    warp::square_to_uniform_sphere(glam::Vec2::new(rng.next_f32(), rng.next_f32()));
                (rng.next_f32() >= drop).then_some(w)
            }
        };
        let uniform = |_: Vec3| 1.0 / (4.0 * PI);
        let tilted = |w: Vec3| (1.0 + 0.2 * w.z as f64) / (4.0 * PI);
        let kept = |_: Vec3| 0.99 / (4.0 * PI);
        let n = 100_000;
        let grid = CapGrid::SPHERE;
        let p = directions_pvalue(&grid, n, draw(3, 0.0), uniform);
        assert!(p > 0.01, "uniform: p-value {p}");
        let p = directions_pvalue(&grid, n, draw(3, 0.0), tilted);
        assert!(p < 1e-6, "tilted: p-value {p}");
        let p = directions_pvalue(&grid, n, draw(3, 0.01), kept);
        assert!(p > 0.01, "1 % dropped: p-value {p}");
        let p = directions_pvalue(&grid, n, draw(3, 0.03), kept);
        assert!(p < 1e-6, "3 % dropped: p-value {p}");
    }
}
