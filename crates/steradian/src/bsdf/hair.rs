//! `hair`: scattering by a hair or fur fibre (Chiang et al., "A Practical and Controllable Hair
//! and Fur Model for Production Path Tracing", 2016), as Mitsuba 3's `hair` plugin.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `eumelanin`, `pheomelanin` | float | 1.3, 0.2 | pigment concentrations; σa = eumelanin·(0.419, 0.697, 1.37) + pheomelanin·(0.187, 0.4, 1.05) (d'Eon et al. 2011), per unit of fibre radius |
//! | `sigma_a` | spectrum/texture | (pigments) | absorption per unit of fibre radius, instead of the pigments (not both) |
//! | `scale` | float | 1 | factor on `sigma_a` |
//! | `int_ior`, `ext_ior` | float or name | `amber` (1.55), `air` | the fibre's and the surrounding IORs (must differ) |
//! | `longitudinal_roughness`, `azimuthal_roughness` | float | 0.3, 0.3 | β_m, β_n ∈ [0, 1] |
//! | `scale_tilt` | float | 2 | α, the tilt of the cuticle scales, degrees |
//!
//! **Frame.** The model reads directions in the shading frame of a curve (`linearcurve`,
//! `bsplinecurve`): z is the normal, y runs along the fibre, x around it. Like Mitsuba's, it
//! is meant for curves; on other shapes y is merely the surface's second tangent. An
//! interaction stands for the whole walk through the fibre: light leaves at the point where it
//! entered, on either side.
//!
//! **Model.** ρ(wo, wi)·|cos θ| = Σ_{p<3} M_p(θ) · A_p · N_p(φ) + M₃ · A₃ / 2π, with the
//! lobes R, TT, TRT and the rest: M_p the longitudinal scattering of d'Eon et al. (variances
//! v₀ = (0.726β_m + 0.812β_m² + 3.7β_m²⁰)², v₁ = v₀/4, v₂ = v₃ = 4v₀, the incident direction
//! tilted by −2α, α, 4α for p = 0, 1, 2), A_p the attenuation (dielectric Fresnel reflectance
//! f at the fibre's cross-section angle, transmittance T = exp(−σa·2cos γt / cos θt):
//! A₀ = f, A₁ = (1 − f)²T, A₂ = A₁Tf, A₃ = A₂fT/(1 − Tf)), N_p a logistic of scale
//! s = √(π/8)(0.265β_n + 1.194β_n² + 5.372β_n²²) about the ideal azimuth 2pγt − 2γi + pπ,
//! trimmed to [−π, π]; h = sin γi follows from the direction seen in the fibre's
//! cross-section. steradian returns that sum divided by |cos θ| (its BSDFs carry no cosine).
//!
//! **Sampling** (Mitsuba's): the lobe p by the luminance of A_p, then θ from M_p and φ from
//! N_p (uniform for p = 3); the density is the mixture over all lobes, which `pdf` returns.
//!
//! **Where steradian differs on purpose:** none in the model; `eumelanin`/`pheomelanin`
//! together with `sigma_a` is an error, as in Mitsuba; a negative `scale` or pigment
//! concentration is an error (Mitsuba renders it).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_dielectric;
use super::{BsdfSample, Lobe, ShadingPoint};
use crate::spectrum::luminance;
use crate::texture::Texture;
use crate::Spectrum;

/// Lobes modelled one by one (R, TT, TRT); the rest is one more term.
const P_MAX: usize = 3;

/// σa of eumelanin and pheomelanin per unit concentration and fibre radius (d'Eon et al.).
const EUMELANIN_SIGMA_A: [f32; 3] = [0.419, 0.697, 1.37];
const PHEOMELANIN_SIGMA_A: [f32; 3] = [0.187, 0.4, 1.05];

/// What absorbs light inside the fibre.
#[derive(Clone, Debug, PartialEq)]
pub enum HairAbsorption {
    /// Pigment concentrations (eumelanin, pheomelanin).
    Pigments { eumelanin: f32, pheomelanin: f32 },
    /// σa given directly, times `scale`.
    SigmaA { sigma_a: Texture, scale: f32 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Hair {
    absorption: HairAbsorption,
    /// Relative IOR int_ior / ext_ior.
    eta: f32,
    /// Longitudinal variances per lobe.
    v: [f32; P_MAX + 1],
    /// Logistic scale of the azimuthal lobes.
    s: f32,
    /// sin and cos of 2ᵏα, k = 0, 1, 2.
    sin_2k_alpha: [f32; 3],
    cos_2k_alpha: [f32; 3],
}

impl Hair {
    pub const DEFAULT_EUMELANIN: f32 = 1.3;
    pub const DEFAULT_PHEOMELANIN: f32 = 0.2;
    pub const DEFAULT_SCALE: f32 = 1.0;
    pub const DEFAULT_LONGITUDINAL_ROUGHNESS: f32 = 0.3;
    pub const DEFAULT_AZIMUTHAL_ROUGHNESS: f32 = 0.3;
    /// Degrees.
    pub const DEFAULT_SCALE_TILT: f32 = 2.0;
    pub const DEFAULT_INT_IOR: &'static str = "amber";
    pub const DEFAULT_EXT_IOR: &'static str = "air";

    /// The fibre (see the module docs); the roughnesses must lie in [0, 1] and η ≠ 1.
    pub fn new(
        absorption: HairAbsorption,
        eta: f32,
        longitudinal_roughness: f32,
        azimuthal_roughness: f32,
        scale_tilt_deg: f32,
    ) -> Result<Hair, String> {
        for (name, r) in [
            ("longitudinal_roughness", longitudinal_roughness),
            ("azimuthal_roughness", azimuthal_roughness),
        ] {
            if !(0.0..=1.0).contains(&r) {
                return Err(format!("hair: {name} must lie in [0, 1], got {r}"));
            }
        }
        if !(eta.is_finite() && eta > 0.0 && eta != 1.0) {
            return Err(format!("hair: the interior and exterior IORs must differ (η = {eta})"));
        }
        if !scale_tilt_deg.is_finite() {
            return Err("hair: scale_tilt must be finite".into());
        }
        match &absorption {
            HairAbsorption::Pigments { eumelanin, pheomelanin } => {
                let valid = |c: f32| c.is_finite() && c >= 0.0;
                if !(valid(*eumelanin) && valid(*pheomelanin)) {
                    return Err("hair: pigment concentrations must be finite and ≥ 0".into());
                }
            }
            HairAbsorption::SigmaA { scale, .. } => {
                if !(scale.is_finite() && *scale >= 0.0) {
                    return Err(format!("hair: scale must be finite and ≥ 0, got {scale}"));
                }
            }
        }
        let mut sin_2k_alpha = [0.0; 3];
        let mut cos_2k_alpha = [0.0; 3];
        sin_2k_alpha[0] = scale_tilt_deg.to_radians().sin();
        cos_2k_alpha[0] = (1.0 - sin_2k_alpha[0] * sin_2k_alpha[0]).max(0.0).sqrt();
        for i in 1..3 {
            sin_2k_alpha[i] = 2.0 * cos_2k_alpha[i - 1] * sin_2k_alpha[i - 1];
            cos_2k_alpha[i] = cos_2k_alpha[i - 1] * cos_2k_alpha[i - 1]
                - sin_2k_alpha[i - 1] * sin_2k_alpha[i - 1];
        }
        let bn = azimuthal_roughness;
        let s = (PI / 8.0).sqrt() * (0.265 * bn + 1.194 * bn * bn + 5.372 * bn.powi(22));
        let bm = longitudinal_roughness;
        let v0 = (0.726 * bm + 0.812 * bm * bm + 3.7 * bm.powi(20)).powi(2);
        let v = [v0, 0.25 * v0, 4.0 * v0, 4.0 * v0];
        Ok(Hair { absorption, eta, v, s, sin_2k_alpha, cos_2k_alpha })
    }

    /// σa at the shading point, per unit of fibre radius.
    fn sigma_a(&self, sp: &ShadingPoint) -> Spectrum {
        match &self.absorption {
            HairAbsorption::Pigments { eumelanin, pheomelanin } => {
                Spectrum::from(EUMELANIN_SIGMA_A) * *eumelanin
                    + Spectrum::from(PHEOMELANIN_SIGMA_A) * *pheomelanin
            }
            HairAbsorption::SigmaA { sigma_a, scale } => sigma_a.eval(sp.tex()) * *scale,
        }
    }

    /// The incident direction tilted by the cuticle scales for lobe `p`: (sin θ, |cos θ|).
    fn reframe(&self, sin_theta: f32, cos_theta: f32, p: usize) -> (f32, f32) {
        let (sa, ca) = (self.sin_2k_alpha, self.cos_2k_alpha);
        let (s, c) = match p {
            0 => (sin_theta * ca[1] - cos_theta * sa[1], cos_theta * ca[1] + sin_theta * sa[1]),
            1 => (sin_theta * ca[0] + cos_theta * sa[0], cos_theta * ca[0] - sin_theta * sa[0]),
            2 => (sin_theta * ca[2] + cos_theta * sa[2], cos_theta * ca[2] - sin_theta * sa[2]),
            _ => (sin_theta, cos_theta),
        };
        (s, c.abs())
    }

    /// What eval, pdf and sample share about the direction towards the viewer `wo`.
    fn incident(&self, sp: &ShadingPoint, wo: Vec3) -> Incident {
        let gamma_i = gamma(wo);
        let h = gamma_i.sin();
        let sin_theta = wo.y;
        let cos_theta = (1.0 - sin_theta * sin_theta).max(0.0).sqrt();
        let phi = wo.z.atan2(wo.x);
        let sin_theta_t = sin_theta / self.eta;
        let cos_theta_t = (1.0 - sin_theta_t * sin_theta_t).max(0.0).sqrt();
        let eta_p = (self.eta * self.eta - sin_theta * sin_theta).max(0.0).sqrt() / cos_theta;
        let sin_gamma_t = h / eta_p;
        let cos_gamma_t = (1.0 - sin_gamma_t * sin_gamma_t).max(0.0).sqrt();
        let gamma_t = sin_gamma_t.clamp(-1.0, 1.0).asin();
        let transmittance = (-self.sigma_a(sp) * (2.0 * cos_gamma_t / cos_theta_t)).exp();
        // attenuation per lobe
        let f = fresnel_dielectric(cos_theta * (1.0 - h * h).max(0.0).sqrt(), self.eta).r;
        let mut a = [Spectrum::ZERO; P_MAX + 1];
        a[0] = Spectrum::splat(f);
        a[1] = transmittance * ((1.0 - f) * (1.0 - f));
        for p in 2..P_MAX {
            a[p] = a[p - 1] * transmittance * f;
        }
        a[P_MAX] = a[P_MAX - 1] * transmittance * f / (Spectrum::ONE - transmittance * f);
        let lum = a.map(luminance);
        let total: f32 = lum.iter().sum();
        let a_pdf = lum.map(|l| l / total);
        Incident { gamma_i, gamma_t, sin_theta, cos_theta, phi, a, a_pdf }
    }

    /// Σ over lobes of M_p·2π·w_p·N_p (+ M₃·w₃) for the outgoing `wi`, with per-lobe
    /// weights `w` (A_p for the value, their sampling probabilities for the density).
    fn lobes<T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>>(
        &self,
        inc: &Incident,
        wi: Vec3,
        w: [T; P_MAX + 1],
        zero: T,
    ) -> T {
        let dphi = wi.z.atan2(wi.x) - inc.phi;
        let (sin_phi_i, cos_phi_i) = inc.phi.sin_cos();
        let mut sum = zero;
        for (p, &wp) in w.iter().enumerate().take(P_MAX) {
            let (s, c) = self.reframe(inc.sin_theta, inc.cos_theta, p);
            let wi_p = Vec3::new(c * cos_phi_i, s, c * sin_phi_i);
            let m = longitudinal(wi_p, wi, self.v[p]);
            let n = azimuthal(dphi, p, self.s, inc.gamma_i, inc.gamma_t);
            sum = sum + wp * (m * 2.0 * PI * n);
        }
        let wo_dir = Vec3::new(inc.cos_theta * cos_phi_i, inc.sin_theta, inc.cos_theta * sin_phi_i);
        sum + w[P_MAX] * longitudinal(wo_dir, wi, self.v[P_MAX])
    }

    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        let cos = wi.z.abs();
        if cos == 0.0 {
            return Spectrum::ZERO;
        }
        let inc = self.incident(sp, wo);
        let value = self.lobes(&inc, wi, inc.a, Spectrum::ZERO);
        if value.is_finite() {
            value / cos
        } else {
            Spectrum::ZERO
        }
    }

    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        let inc = self.incident(sp, wo);
        let pdf = self.lobes(&inc, wi, inc.a_pdf, 0.0);
        if pdf.is_finite() {
            pdf
        } else {
            0.0
        }
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let inc = self.incident(sp, wo);
        // the lobe, and u1 rescaled within its share
        let (mut u, mut p) = (u1, 0);
        while p < P_MAX && u >= inc.a_pdf[p] {
            u -= inc.a_pdf[p];
            p += 1;
        }
        let u_phi = if inc.a_pdf[p] > 0.0 { (u / inc.a_pdf[p]).clamp(0.0, 1.0) } else { 0.5 };
        let (sin_theta_ip, cos_theta_ip) = self.reframe(inc.sin_theta, inc.cos_theta, p);
        // longitudinal: cos θ about the tilted direction from M_p
        let v = self.v[p];
        let cos_theta = 1.0 + v * (u2.x + (1.0 - u2.x) * (-2.0 / v).exp()).ln();
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let cos_phi = (2.0 * PI * u2.y).cos();
        let sin_theta_o = -cos_theta * sin_theta_ip + sin_theta * cos_phi * cos_theta_ip;
        let cos_theta_o = (1.0 - sin_theta_o * sin_theta_o).max(0.0).sqrt();
        // azimuthal: about the ideal azimuth of the lobe, uniform for the rest
        let dphi = if p < P_MAX {
            2.0 * p as f32 * inc.gamma_t - 2.0 * inc.gamma_i
                + p as f32 * PI
                + trimmed_logistic_sample(u_phi, self.s)
        } else {
            2.0 * PI * u_phi
        };
        let (sin_phi_o, cos_phi_o) = (inc.phi + dphi).sin_cos();
        let wi = Vec3::new(cos_theta_o * cos_phi_o, sin_theta_o, cos_theta_o * sin_phi_o)
            .normalize_or_zero();
        let pdf = self.lobes(&inc, wi, inc.a_pdf, 0.0);
        if !(pdf.is_finite() && pdf > 0.0) || wi == Vec3::ZERO {
            return None;
        }
        let value = self.lobes(&inc, wi, inc.a, Spectrum::ZERO);
        if !value.is_finite() {
            return None;
        }
        Some(BsdfSample { wi, pdf, weight: value / pdf, lobe: Lobe::Smooth, eta: 1.0 })
    }
}

/// The incident direction's parameters and the lobes' attenuations and probabilities.
struct Incident {
    gamma_i: f32,
    gamma_t: f32,
    sin_theta: f32,
    cos_theta: f32,
    phi: f32,
    a: [Spectrum; P_MAX + 1],
    a_pdf: [f32; P_MAX + 1],
}

/// The angle between the normal and `w` seen in the fibre's cross-section (x, z), signed as
/// Mitsuba signs it.
fn gamma(w: Vec3) -> f32 {
    let proj = (w.x * w.x + w.z * w.z).sqrt();
    if proj == 0.0 {
        return 0.0;
    }
    let g = (w.z / proj).clamp(-1.0, 1.0).acos();
    if w.x < 0.0 {
        g
    } else {
        -g
    }
}

/// d'Eon et al.'s longitudinal scattering M(θi, θo) with variance `v`, over 2π (Mitsuba's
/// `square_to_rough_fiber_pdf` with κ = 1/v): y is the fibre axis.
fn longitudinal(wi: Vec3, wo: Vec3, v: f32) -> f32 {
    let kappa = 1.0 / v;
    let (ci, co) = (wi.y, wo.y);
    let si = (1.0 - ci * ci).max(0.0).sqrt();
    let so = (1.0 - co * co).max(0.0).sqrt();
    let c = ci * co * kappa;
    let s = si * so * kappa;
    let m = if kappa > 10.0 {
        (-c + log_i0(s) - kappa + std::f32::consts::LN_2 + (kappa / 2.0).ln()).exp()
    } else {
        (-c).exp() * i0(s) * kappa / (2.0 * kappa.sinh())
    };
    m / (2.0 * PI)
}

/// The modified Bessel function I₀ by its series (ten terms).
fn i0(x: f32) -> f32 {
    let (mut sum, x2) = (1.0f32, x * x);
    let (mut xi, mut denom) = (x2, 4.0f32);
    for i in 1..=10 {
        sum += xi / denom;
        xi *= x2;
        let f = (i + 1) as f32;
        denom *= 4.0 * f * f;
    }
    sum
}

/// ln I₀(x), asymptotic above 12.
fn log_i0(x: f32) -> f32 {
    if x > 12.0 {
        x + 0.5 * ((1.0 / (2.0 * PI * x)).ln() + 1.0 / (8.0 * x))
    } else {
        i0(x).ln()
    }
}

fn logistic(x: f32, s: f32) -> f32 {
    let e = (-x.abs() / s).exp();
    e / (s * (1.0 + e) * (1.0 + e))
}

fn logistic_cdf(x: f32, s: f32) -> f32 {
    1.0 / (1.0 + (-x / s).exp())
}

/// A logistic sample of scale `s` trimmed to [−π, π].
fn trimmed_logistic_sample(u: f32, s: f32) -> f32 {
    let k = logistic_cdf(PI, s) - logistic_cdf(-PI, s);
    let x = -s * (1.0 / (u * k + logistic_cdf(-PI, s)) - 1.0).ln();
    x.clamp(-PI, PI)
}

/// N_p: the trimmed logistic about lobe `p`'s ideal azimuth.
fn azimuthal(dphi: f32, p: usize, s: f32, gamma_i: f32, gamma_t: f32) -> f32 {
    let ideal = 2.0 * p as f32 * gamma_t - 2.0 * gamma_i + p as f32 * PI;
    let mut phi = (dphi - ideal) % (2.0 * PI);
    if phi > PI {
        phi -= 2.0 * PI;
    } else if phi < -PI {
        phi += 2.0 * PI;
    }
    logistic(phi, s) / (logistic_cdf(PI, s) - logistic_cdf(-PI, s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::Bsdf;
    use crate::testkit::bsdf::{albedo, chi2_pvalue, compare_with_mitsuba_table, dir};

    fn pigments(eumelanin: f32, pheomelanin: f32) -> HairAbsorption {
        HairAbsorption::Pigments { eumelanin, pheomelanin }
    }

    /// The configurations of `scripts/bsdf_table.py hair`.
    fn configs() -> Vec<Bsdf> {
        let h = |a, eta: f32, bm, bn, tilt| Bsdf::Hair(Hair::new(a, eta, bm, bn, tilt).unwrap());
        let amber = 1.55 / 1.000277;
        vec![
            h(pigments(1.3, 0.2), amber, 0.3, 0.3, 2.0),
            h(pigments(0.2, 0.4), amber, 0.3, 0.3, 2.0),
            h(
                HairAbsorption::SigmaA {
                    sigma_a: Spectrum::new(0.2, 0.25, 0.7).into(),
                    scale: 2.0,
                },
                amber,
                0.15,
                0.6,
                2.0,
            ),
            h(pigments(0.05, 0.05), 1.4 / 1.000277, 0.5, 0.2, 6.0),
        ]
    }

    #[test]
    fn eval_and_pdf_match_mitsuba() {
        compare_with_mitsuba_table(&configs(), include_str!("testdata/hair.csv"));
    }

    /// Sampling follows the density `pdf` returns, over the whole sphere.
    #[test]
    fn sampling_matches_pdf_chi2() {
        let mut k = 0;
        for b in configs() {
            for wo in [dir(30.0, 70.0), dir(80.0, 200.0), dir(120.0, 10.0)] {
                let p = chi2_pvalue(&b, wo, 200_000, 40 + k);
                k += 1;
                assert!(p > 0.01 / 12.0, "config {b:?} wo {wo}: p-value {p}");
            }
        }
    }

    /// With no absorption the fibre returns nearly all light (Fresnel losses only through the
    /// truncated sum): Mitsuba's mean sample weight for σa = 0.01 at this direction is 0.980.
    #[test]
    fn an_unpigmented_fibre_returns_the_light() {
        let b = Bsdf::Hair(
            Hair::new(
                HairAbsorption::SigmaA { sigma_a: Spectrum::splat(0.01).into(), scale: 1.0 },
                1.55 / 1.000277,
                0.3,
                0.3,
                2.0,
            )
            .unwrap(),
        );
        let wo = Vec3::new(0.3, 0.4, (1.0f32 - 0.25).sqrt());
        let (mean, se) = albedo(&b, wo, 200_000, 3);
        assert!((mean[0] - 0.9799).abs() < 4.0 * se[0] + 2e-3, "{mean:?} ± {se:?}");
    }
}
