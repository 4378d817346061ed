//! `tabphase`: a phase function given as a table over the scattering angle's cosine.
//!
//! | parameter | type   | default    | meaning |
//! |-----------|--------|------------|---------|
//! | `values`  | string | (required) | the phase function at N ≥ 2 cosines spaced evenly from −1 (back) to 1 (forward), separated by commas or spaces; any positive scale |
//!
//! As Mitsuba 3's: the table is interpolated linearly in cos θ (cos θ = −wo·wi, 1 forward) and
//! normalised, p(θ) = f(cos θ) / (2π ∫₋₁¹ f), the integral by the trapezoid rule, which is
//! exact for the interpolant. Sampling inverts the interpolant's cumulative distribution
//! exactly (a quadratic within each interval), so a sample's weight p/pdf is 1.
//!
//! **Where steradian differs on purpose:** a negative, non-finite or all-zero table is an error
//! (Mitsuba's distribution refuses negative entries and an empty integral too).

use glam::{Vec2, Vec3};

use super::{scattered, PhaseSample};
use crate::param::ParamError;

#[derive(Clone, Debug, PartialEq)]
pub struct TabulatedPhase {
    /// The table, normalised to a density in cos θ over [−1, 1] (∫ = 1).
    density: Vec<f32>,
    /// The cumulative distribution at each node (0 at −1, 1 at 1).
    cdf: Vec<f32>,
}

impl TabulatedPhase {
    pub fn new(values: &[f32]) -> Result<TabulatedPhase, ParamError> {
        let err = |m: String| ParamError::new("values", m);
        if values.len() < 2 {
            return Err(err(format!("needs at least two values, got {}", values.len())));
        }
        if let Some(v) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
            return Err(err(format!("values must be finite and non-negative, got {v}")));
        }
        let dx = 2.0 / (values.len() - 1) as f64;
        let areas: Vec<f64> =
            values.windows(2).map(|w| 0.5 * (w[0] as f64 + w[1] as f64) * dx).collect();
        let total: f64 = areas.iter().sum();
        if total.is_nan() || total <= 0.0 {
            return Err(err("the values are all zero".into()));
        }
        let density = values.iter().map(|&v| (v as f64 / total) as f32).collect();
        let mut cdf = Vec::with_capacity(values.len());
        let mut acc = 0.0;
        cdf.push(0.0);
        for a in &areas {
            acc += a / total;
            cdf.push(acc as f32);
        }
        *cdf.last_mut().expect("two values or more") = 1.0;
        Ok(TabulatedPhase { density, cdf })
    }

    /// The interval width in cos θ.
    fn dx(&self) -> f32 {
        2.0 / (self.density.len() - 1) as f32
    }

    /// The density in cos θ at `mu`, linearly interpolated.
    fn density_at(&self, mu: f32) -> f32 {
        let n = self.density.len();
        let x = ((mu.clamp(-1.0, 1.0) + 1.0) / self.dx()).min((n - 1) as f32);
        let i = (x as usize).min(n - 2);
        let t = x - i as f32;
        self.density[i] * (1.0 - t) + self.density[i + 1] * t
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.density_at(-wo.dot(wi)) * (0.5 * std::f32::consts::FRAC_1_PI)
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> PhaseSample {
        let n = self.density.len();
        // the interval holding u.x, then the point of the linear density within it
        let i = self.cdf.partition_point(|&c| c <= u.x).clamp(1, n - 1) - 1;
        let dx = self.dx();
        let (f0, f1) = (self.density[i], self.density[i + 1]);
        let c = (u.x - self.cdf[i]).max(0.0) / dx;
        // s in [0, 1] with f0·s + (f1 − f0)·s²/2 = c, in the form that stays exact as f1 → f0
        let root = (f0 * f0 + 2.0 * (f1 - f0) * c).max(0.0).sqrt();
        let s = if f0 + root > 0.0 { (2.0 * c / (f0 + root)).clamp(0.0, 1.0) } else { 0.5 };
        let mu = (-1.0 + (i as f32 + s) * dx).clamp(-1.0, 1.0);
        let wi = scattered(wo, mu, u.y);
        PhaseSample { wi, pdf: self.eval(wo, wi), weight: 1.0 }
    }
}
