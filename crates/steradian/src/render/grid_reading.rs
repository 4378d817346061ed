//! A `workplane` sensor's reading: a value per cell with its standard error, in lux (or W/m²),
//! and the statistics a lighting engineer reports: average, minimum, maximum, uniformity
//! U₀ = E_min/E_avg and E_min/E_max, each with its standard error.
//!
//! - Illuminance E = 683 lm/W × Y(RGB irradiance). Its standard error is taken as
//!   683 × Σ w_c σ_c (w the luminance weights): exact when the channels' errors are perfectly
//!   correlated, as in grey scenes, where each sample's channels are proportional; an upper
//!   bound otherwise (the film keeps no cross-channel moments).
//! - σ(avg) = √(Σ σᵢ²)/N (the cells are independent estimates); min and max carry the
//!   standard error of the cell that holds them; the ratios' errors follow by first-order
//!   propagation, ignoring the covariance of a cell with the average it is part of (1/N of it).

use super::RenderOutput;
use crate::emitter::LUMENS_PER_WATT;
use crate::sensor::WorkplaneUnit;
use crate::spectrum::luminance_f64;

/// A value and its standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    pub value: f64,
    pub stderr: f64,
}

/// The statistics of a grid of readings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridStats {
    pub avg: Estimate,
    pub min: Estimate,
    pub max: Estimate,
    /// E_min / E_avg.
    pub u0: Estimate,
    /// E_min / E_max.
    pub min_max: Estimate,
}

/// A grid sensor's reading.
#[derive(Clone, Debug, PartialEq)]
pub struct GridReading {
    pub nx: usize,
    pub ny: usize,
    /// "lx" or "W/m^2".
    pub unit: &'static str,
    /// ny rows of nx values, row 0 first (the plan's top row).
    pub values: Vec<f64>,
    pub stderr: Vec<f64>,
    pub stats: GridStats,
}

/// a/b with its first-order standard error.
fn ratio(a: Estimate, b: Estimate) -> Estimate {
    if b.value == 0.0 {
        return Estimate { value: f64::NAN, stderr: f64::NAN };
    }
    let value = a.value / b.value;
    let stderr =
        ((a.stderr / b.value).powi(2) + (a.value * b.stderr / (b.value * b.value)).powi(2)).sqrt();
    Estimate { value, stderr }
}

impl GridReading {
    /// The reading of a finished work-plane render in `unit`.
    pub fn from_render(out: &RenderOutput, unit: WorkplaneUnit) -> GridReading {
        let (value, error) = (out.film().develop(), out.film().develop_stderr());
        let (nx, ny) = (value.width as usize, value.height as usize);
        let (values, stderr): (Vec<f64>, Vec<f64>) = value
            .data
            .chunks_exact(3)
            .zip(error.data.chunks_exact(3))
            .map(|(v, e)| match unit {
                WorkplaneUnit::Illuminance => {
                    let k = LUMENS_PER_WATT as f64;
                    (k * luminance_f64(v), k * luminance_f64(e))
                }
                WorkplaneUnit::DaylightFactor { outdoor_lux } => {
                    let k = 100.0 * LUMENS_PER_WATT as f64 / outdoor_lux;
                    (k * luminance_f64(v), k * luminance_f64(e))
                }
                // the channels' mean, as `measure` reports a grey irradiance
                WorkplaneUnit::Irradiance => {
                    let mean = |x: &[f32]| x.iter().map(|&a| a as f64).sum::<f64>() / 3.0;
                    (mean(v), mean(e))
                }
            })
            .unzip();
        let n = values.len().max(1) as f64;
        let avg = Estimate {
            value: values.iter().sum::<f64>() / n,
            stderr: stderr.iter().map(|s| s * s).sum::<f64>().sqrt() / n,
        };
        let pick = |better: fn(f64, f64) -> bool| {
            let mut best = 0;
            for i in 1..values.len() {
                if better(values[i], values[best]) {
                    best = i;
                }
            }
            Estimate { value: values[best], stderr: stderr[best] }
        };
        let (min, max) = (pick(|a, b| a < b), pick(|a, b| a > b));
        let stats = GridStats { avg, min, max, u0: ratio(min, avg), min_max: ratio(min, max) };
        let unit = match unit {
            WorkplaneUnit::Illuminance => "lx",
            WorkplaneUnit::Irradiance => "W/m^2",
            WorkplaneUnit::DaylightFactor { .. } => "%",
        };
        GridReading { nx, ny, unit, values, stderr, stats }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_propagate_their_errors() {
        let a = Estimate { value: 2.0, stderr: 0.1 };
        let b = Estimate { value: 4.0, stderr: 0.2 };
        let r = ratio(a, b);
        assert_eq!(r.value, 0.5);
        // (0.1/4)² + (2·0.2/16)² = 6.25e-4 + 6.25e-4
        assert!((r.stderr - (1.25e-3f64).sqrt()).abs() < 1e-12);
        assert!(ratio(a, Estimate { value: 0.0, stderr: 0.0 }).value.is_nan());
    }
}
