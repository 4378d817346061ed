//! `heterogeneous`: a medium whose coefficients vary over space, read from volumes.
//!
//! | parameter         | type              | default   | meaning |
//! |-------------------|-------------------|-----------|---------|
//! | `sigma_t`         | volume or spectrum | 1        | extinction coefficient σ_t, 1/m (scene units), before `scale` |
//! | `albedo`          | volume or spectrum | 0.75     | single-scattering albedo σ_s/σ_t, in [0, 1] |
//! | `scale`           | float             | 1         | factor on σ_t |
//! | `sample_emitters` | bool              | true      | whether scattering in the medium samples the lights |
//! | (nested)          | phase             | isotropic | the phase function |
//!
//! Volumes (`texture/volume.rs`) are `gridvolume` or `constvolume`, each looked up in its own unit
//! cube. As in Mitsuba 3, the medium fills the world-space bounding box of the `sigma_t`
//! volume (outside it light flies freely), and its majorant is one number for all channels,
//! μ̄ = `scale` × the largest value of `sigma_t`.
//!
//! **Free flights** by delta tracking: tentative collisions at rate μ̄ (the same density in
//! every channel); at each, with σ_n = μ̄ − σ_t, the collision is real with probability
//! σ_t,c/μ̄ in the path's channel c (f = σ_s, pdf_j = σ_t,j) and null otherwise (f = pdf_j =
//! σ_n,j), as in Mitsuba 3; the integrator weights the path by spectral MIS over the channels
//! (`medium/mod.rs`). For a grey medium the weights are the albedo and 1. **Transmittance**
//! by ratio tracking: the product of σ_n/μ̄ over the tentative collisions before the end of
//! the segment.

use glam::Vec3;

use super::{FlightWeight, FreeFlight};
use crate::geometry::Ray;
use crate::param::ParamError;
use crate::phase::PhaseFunction;
use crate::sampling::PixelSampler;
use crate::texture::Volume;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Heterogeneous {
    sigma_t: Volume,
    albedo: Volume,
    scale: f32,
    /// μ̄ = scale × max σ_t, 1/m.
    majorant: f32,
    pub phase: PhaseFunction,
    pub sample_emitters: bool,
}

impl Heterogeneous {
    /// Defaults (Mitsuba 3's).
    pub const DEFAULT_SIGMA_T: f32 = 1.0;
    pub const DEFAULT_ALBEDO: f32 = 0.75;
    pub const DEFAULT_SCALE: f32 = 1.0;
    pub const DEFAULT_SAMPLE_EMITTERS: bool = true;

    pub fn new(
        sigma_t: Volume,
        albedo: Volume,
        scale: f32,
        phase: PhaseFunction,
        sample_emitters: bool,
    ) -> Result<Heterogeneous, ParamError> {
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(ParamError::new(
                "scale",
                format!("scale must be finite and non-negative, got {scale}"),
            ));
        }
        if sigma_t.min() < 0.0 {
            return Err(ParamError::new(
                "sigma_t",
                format!("sigma_t must be non-negative, its smallest value is {}", sigma_t.min()),
            ));
        }
        if albedo.min() < 0.0 || albedo.max() > 1.0 {
            return Err(ParamError::new(
                "albedo",
                format!(
                    "albedo must lie in [0, 1], its values span [{}, {}]",
                    albedo.min(),
                    albedo.max()
                ),
            ));
        }
        let majorant = scale * sigma_t.max();
        Ok(Heterogeneous { sigma_t, albedo, scale, majorant, phase, sample_emitters })
    }

    /// μ̄, 1/m.
    pub fn majorant(&self) -> f32 {
        self.majorant
    }

    /// σ_t at world position `p`, 1/m.
    #[inline]
    pub fn sigma_t_at(&self, p: Vec3) -> Spectrum {
        self.sigma_t.eval(p) * self.scale
    }

    /// The stretch [t0, t1] of the ray (up to `t_max`) inside the medium's box, if any.
    #[inline]
    fn segment(&self, ray: &Ray, t_max: f32) -> Option<(f32, f32)> {
        if self.majorant <= 0.0 {
            return None;
        }
        let clipped = Ray::new(ray.o, ray.d, t_max);
        self.sigma_t.bounds().intersect(&clipped, ray.d.recip())
    }

    /// A free flight along `ray` up to the surface at `t_max`, real and null collisions decided
    /// in `channel` (module docs).
    pub fn sample_free_flight(
        &self,
        ray: &Ray,
        t_max: f32,
        channel: usize,
        sampler: &mut PixelSampler,
    ) -> FreeFlight {
        let Some((mut t, t1)) = self.segment(ray, t_max) else {
            return FreeFlight::Pass { weight: FlightWeight::ONE };
        };
        let mu = self.majorant;
        let mut weight = FlightWeight::ONE;
        loop {
            t -= (-sampler.next_1d()).ln_1p() / mu;
            let u = sampler.next_1d();
            if t >= t1 {
                return FreeFlight::Pass { weight };
            }
            let p = ray.at(t);
            let sigma_t = self.sigma_t_at(p).min(Spectrum::splat(mu));
            if u * mu < sigma_t[channel] {
                // real: f = σ_s, pdf_j = σ_t,j (both over μ̄, which cancels), over the largest
                let top = sigma_t.max_element();
                weight.f *= sigma_t * self.albedo.eval(p) / top;
                weight.pdf *= sigma_t / top;
                return FreeFlight::Scatter { t, weight };
            }
            // null: f = pdf_j = σ_n,j (σ_n in `channel` is positive, or it was not chosen)
            let sigma_n = Spectrum::splat(mu) - sigma_t;
            let top = sigma_n.max_element();
            weight.f *= sigma_n / top;
            weight.pdf *= sigma_n / top;
        }
    }

    /// Ratio-tracking estimate of the transmittance along `ray` over [0, t] (module docs).
    pub fn transmittance(&self, ray: &Ray, t: f32, sampler: &mut PixelSampler) -> Spectrum {
        let Some((mut s, t1)) = self.segment(ray, t) else { return Spectrum::ONE };
        let mu = self.majorant;
        let mut tr = Spectrum::ONE;
        loop {
            s -= (-sampler.next_1d()).ln_1p() / mu;
            if s >= t1 {
                return tr;
            }
            let sigma_n = (Spectrum::splat(mu) - self.sigma_t_at(ray.at(s))).max(Spectrum::ZERO);
            tr *= sigma_n / mu;
            if tr == Spectrum::ZERO {
                return tr;
            }
        }
    }
}
