//! `homogeneous`: a medium with the same coefficients everywhere.
//!
//! | parameter         | type     | default   | meaning |
//! |-------------------|----------|-----------|---------|
//! | `sigma_t`         | spectrum | 1         | extinction coefficient σ_t, 1/m (scene units) |
//! | `albedo`          | spectrum | 0.75      | single-scattering albedo σ_s/σ_t, in [0, 1] |
//! | `scale`           | float    | 1         | factor on σ_t (and so on σ_s and σ_a) |
//! | `sample_emitters` | bool     | true      | whether scattering in the medium samples the lights |
//! | (nested)          | phase    | isotropic | the phase function |
//!
//! Transmittance over a distance d: T(d) = exp(−σ_t d) per channel. Free-flight distances are
//! drawn in one channel c (the integrator picks it) with density σ_t,c exp(−σ_t,c t):
//! t = −ln(1 − ξ)/σ_t,c; [`Homogeneous::free_flight_pdf`] gives every channel's density of a
//! distance, for the spectral MIS of `volpathmis`, and [`Homogeneous::transmittance`] the
//! probability of flying past d.

use super::{FlightWeight, FreeFlight};
use crate::param::ParamError;
use crate::phase::PhaseFunction;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Homogeneous {
    /// σ_t × `scale`, 1/m.
    sigma_t: Spectrum,
    albedo: Spectrum,
    pub phase: PhaseFunction,
    pub sample_emitters: bool,
}

impl Homogeneous {
    /// Defaults (Mitsuba 3's).
    pub const DEFAULT_SIGMA_T: f32 = 1.0;
    pub const DEFAULT_ALBEDO: f32 = 0.75;
    pub const DEFAULT_SCALE: f32 = 1.0;
    pub const DEFAULT_SAMPLE_EMITTERS: bool = true;

    pub fn new(
        sigma_t: Spectrum,
        albedo: Spectrum,
        scale: f32,
        phase: PhaseFunction,
        sample_emitters: bool,
    ) -> Result<Homogeneous, ParamError> {
        if !(sigma_t.is_finite() && sigma_t.min_element() >= 0.0) {
            return Err(ParamError::new(
                "sigma_t",
                format!("sigma_t must be finite and non-negative, got {sigma_t}"),
            ));
        }
        if !(albedo.is_finite() && albedo.min_element() >= 0.0 && albedo.max_element() <= 1.0) {
            return Err(ParamError::new(
                "albedo",
                format!("albedo must lie in [0, 1], got {albedo}"),
            ));
        }
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(ParamError::new(
                "scale",
                format!("scale must be finite and non-negative, got {scale}"),
            ));
        }
        Ok(Homogeneous { sigma_t: sigma_t * scale, albedo, phase, sample_emitters })
    }

    /// σ_t, 1/m.
    pub fn sigma_t(&self) -> Spectrum {
        self.sigma_t
    }

    /// σ_s = α σ_t, 1/m.
    pub fn sigma_s(&self) -> Spectrum {
        self.albedo * self.sigma_t
    }

    /// σ_a = (1 − α) σ_t, 1/m.
    pub fn sigma_a(&self) -> Spectrum {
        (Spectrum::ONE - self.albedo) * self.sigma_t
    }

    /// T(d) = exp(−σ_t d), the fraction of light that crosses distance `d` (m; infinite: 0
    /// where σ_t > 0, 1 where the channel is clear).
    #[inline]
    pub fn transmittance(&self, d: f32) -> Spectrum {
        Spectrum::from_array(self.sigma_t.to_array().map(|s| {
            if s > 0.0 {
                (-s * d).exp()
            } else {
                1.0
            }
        }))
    }

    /// Whether σ_t differs between channels (Mitsuba's `has_spectral_extinction`, decided by
    /// the values): a grey medium needs no spectral MIS.
    #[inline]
    pub fn is_chromatic(&self) -> bool {
        self.sigma_t.min_element() != self.sigma_t.max_element()
    }

    /// A free flight along a ray whose surface lies at `t_max` (m), its distance drawn in
    /// `channel` by `u_t` (`medium/mod.rs`). The densities are compared in logarithms,
    /// ln p_j = ln σ_t,j − σ_t,j t, so that no ratio overflows over long flights.
    #[inline]
    pub fn sample_free_flight(&self, t_max: f32, channel: usize, u_t: f32) -> FreeFlight {
        let chromatic = self.is_chromatic();
        let t = self.sample_distance(u_t, channel);
        if t < t_max {
            if !chromatic {
                return FreeFlight::Scatter {
                    t,
                    weight: FlightWeight { f: self.albedo, pdf: Spectrum::ONE },
                };
            }
            let log_pdf = self.sigma_t.to_array().map(|s| {
                if s > 0.0 {
                    s.ln() - s * t
                } else {
                    f32::NEG_INFINITY
                }
            });
            let pdf = relative_to_largest(log_pdf);
            FreeFlight::Scatter { t, weight: FlightWeight { f: self.albedo * pdf, pdf } }
        } else {
            if !chromatic {
                return FreeFlight::Pass { weight: FlightWeight::ONE };
            }
            let log_pdf = self.sigma_t.to_array().map(|s| if s > 0.0 { -s * t_max } else { 0.0 });
            let pdf = relative_to_largest(log_pdf);
            FreeFlight::Pass { weight: FlightWeight { f: pdf, pdf } }
        }
    }
    /// A free-flight distance drawn in `channel` (0, 1, 2) from ξ ∈ [0, 1): density
    /// σ_t,c exp(−σ_t,c t); infinite where σ_t,c = 0 (the light flies on).
    #[inline]
    pub fn sample_distance(&self, xi: f32, channel: usize) -> f32 {
        let s = self.sigma_t[channel];
        if s > 0.0 {
            -(-xi).ln_1p() / s
        } else {
            f32::INFINITY
        }
    }

    /// The density of free-flight distance `t` in each channel, σ_t exp(−σ_t t), 1/m.
    pub fn free_flight_pdf(&self, t: f32) -> Spectrum {
        self.sigma_t * self.transmittance(t)
    }
}

/// exp(ln p_j − max ln p): densities over the largest (which is finite: the sampled channel's).
#[inline]
fn relative_to_largest(log_pdf: [f32; 3]) -> Spectrum {
    let top = log_pdf.into_iter().fold(f32::NEG_INFINITY, f32::max);
    Spectrum::from_array(log_pdf.map(|l| (l - top).exp()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::phase::Isotropic;
    use crate::radiometry;
    use crate::sampling::Pcg32;

    fn medium() -> Homogeneous {
        let phase = PhaseFunction::Isotropic(Isotropic);
        Homogeneous::new(
            Spectrum::new(0.5, 1.0, 2.0),
            Spectrum::new(0.2, 0.5, 0.9),
            3.0,
            phase,
            true,
        )
        .unwrap()
    }

    #[test]
    fn coefficients_and_beer_lambert() {
        let m = medium();
        assert_eq!(m.sigma_t(), Spectrum::new(1.5, 3.0, 6.0));
        assert!((m.sigma_s() + m.sigma_a() - m.sigma_t()).abs().max_element() < 1e-6);
        for d in [0.0f32, 0.1, 0.7, 2.5] {
            let t = m.transmittance(d);
            for c in 0..3 {
                let want = radiometry::beer_lambert(m.sigma_t()[c] as f64, d as f64);
                assert!((t[c] as f64 - want).abs() <= 1e-6 * want.max(1e-30), "{d} {c}");
            }
        }
    }

    /// Distances drawn in each channel are exponential: their mean is 1/σ_t within four
    /// standard errors, the fraction beyond d is T(d) within four binomial standard errors,
    /// and the density integrates over [0, d] to 1 − T(d).
    #[test]
    fn free_flights_follow_the_exponential() {
        let m = medium();
        let n = 100_000;
        for c in 0..3 {
            let mut r = Pcg32::new(5, c as u64);
            let s = m.sigma_t()[c] as f64;
            let d = 0.4 / s;
            let (mut sum, mut beyond) = (0.0f64, 0usize);
            for _ in 0..n {
                let t = m.sample_distance(r.next_f32(), c) as f64;
                sum += t;
                beyond += (t > d) as usize;
            }
            let mean = sum / n as f64;
            let se = (1.0 / s) / (n as f64).sqrt(); // an exponential's sd is its mean
            assert!((mean - 1.0 / s).abs() <= 4.0 * se, "channel {c}: mean {mean} vs {}", 1.0 / s);
            let p = radiometry::beer_lambert(s, d);
            let frac = beyond as f64 / n as f64;
            let se = (p * (1.0 - p) / n as f64).sqrt();
            assert!((frac - p).abs() <= 4.0 * se, "channel {c}: beyond {frac} vs {p}");
            // ∫₀^d pdf dt by the midpoint rule
            let k = 10_000;
            let integral: f64 = (0..k)
                .map(|i| m.free_flight_pdf((d * (i as f64 + 0.5) / k as f64) as f32)[c] as f64)
                .sum::<f64>()
                * d
                / k as f64;
            assert!((integral - (1.0 - p)).abs() < 1e-5, "channel {c}: {integral}");
        }
        // a channel without extinction never stops the flight
        let clear =
            Homogeneous::new(Spectrum::ZERO, Spectrum::ONE, 1.0, m.phase.clone(), true).unwrap();
        assert_eq!(clear.sample_distance(0.99, 1), f32::INFINITY);
        assert_eq!(clear.transmittance(100.0), Spectrum::ONE);
    }

    #[test]
    fn bad_coefficients_are_errors() {
        let iso = || PhaseFunction::Isotropic(Isotropic);
        assert!(Homogeneous::new(Spectrum::splat(-1.0), Spectrum::ONE, 1.0, iso(), true).is_err());
        assert!(Homogeneous::new(Spectrum::ONE, Spectrum::splat(1.5), 1.0, iso(), true).is_err());
        assert!(Homogeneous::new(Spectrum::ONE, Spectrum::ONE, f32::NAN, iso(), true).is_err());
        assert!(Homogeneous::new(Spectrum::splat(f32::INFINITY), Spectrum::ONE, 1.0, iso(), true)
            .is_err());
    }
}
