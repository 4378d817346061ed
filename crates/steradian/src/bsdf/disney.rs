//! Burley's "Disney" lobes (*Physically Based Shading at Disney*, 2012; *Extending the Disney
//! BRDF to a BSDF with Integrated Subsurface Scattering*, 2015) in the form Mitsuba 3's
//! `principled` and `principledthin` evaluate them: Schlick's Fresnel weight, the roughness
//! remapping, the GTR1 clearcoat distribution, the retro-reflective diffuse term with its
//! fake-subsurface "flatness" blend, and sheen. All directions in the local shading frame.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::microfacet::{MicrofacetDistribution, MicrofacetKind};
use crate::spectrum::luminance;
use crate::Spectrum;

/// Schlick's weight (1 − cos)⁵, cos clamped to [0, 1].
#[inline]
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's approximation R0 + (1 − R0)(1 − cos)⁵ of a dielectric's reflectance for relative
/// IOR `eta`; seen from the denser side the weight takes the transmitted cosine (1 under
/// total internal reflection).
#[inline]
pub(super) fn schlick_fresnel(r0: Spectrum, cos_theta: f32, eta: f32) -> Spectrum {
    let (eta_it, eta_ti) = if cos_theta >= 0.0 { (eta, 1.0 / eta) } else { (1.0 / eta, eta) };
    let w = if eta_it > 1.0 {
        schlick_weight(cos_theta.abs())
    } else {
        let cos_t2 = 1.0 - (1.0 - cos_theta * cos_theta) * eta_ti * eta_ti;
        schlick_weight(cos_t2.max(0.0).sqrt())
    };
    r0 + (Spectrum::ONE - r0) * w
}

/// Normal-incidence reflectance ((η − 1)/(η + 1))² of relative IOR η.
#[inline]
pub(super) fn schlick_r0(eta: f32) -> f32 {
    ((eta - 1.0) / (eta + 1.0)).powi(2)
}

/// The base colour divided by its luminance (the hue alone), white for black.
#[inline]
pub(super) fn tint(base_color: Spectrum) -> Spectrum {
    let lum = luminance(base_color);
    if lum > 0.0 {
        base_color / lum
    } else {
        Spectrum::ONE
    }
}

/// The GGX lobe (visible normals sampled) of `roughness` r and `anisotropic` a: α = r²,
/// stretched by √(1 − 0.9 a) along u and shrunk along v, at least 0.001.
#[inline]
pub(super) fn ggx(roughness: f32, anisotropic: f32) -> MicrofacetDistribution {
    let r2 = roughness * roughness;
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    MicrofacetDistribution::new(
        MicrofacetKind::Ggx,
        (r2 / aspect).max(0.001),
        (r2 * aspect).max(0.001),
        true,
    )
}

/// Whether a microfacet normal `m` joins `wo` and `wi` as a reflection (both on the side of
/// `m` that `wo`'s hemisphere faces) or as a transmission (`wi` on the other side).
#[inline]
pub(super) fn faces_agree(m: Vec3, wo: Vec3, wi: Vec3, transmission: bool) -> bool {
    let m = if wo.z < 0.0 { -m } else { m };
    wo.dot(m) > 0.0 && if transmission { wi.dot(m) < 0.0 } else { wi.dot(m) > 0.0 }
}

/// Burley's GTR1 ("generalised Trowbridge–Reitz", γ = 1) normal distribution of the
/// clearcoat, isotropic, sampled by D·cos θ (not by visible normals).
#[derive(Clone, Copy, Debug)]
pub(super) struct Gtr1 {
    alpha: f32,
}

impl Gtr1 {
    /// The clearcoat of gloss g: α from 0.1 (g = 0) down to 0.001 (g = 1).
    #[inline]
    pub(super) fn clearcoat(gloss: f32) -> Self {
        Gtr1 { alpha: 0.1 * (1.0 - gloss) + 0.001 * gloss }
    }

    /// D(m) in 1/sr.
    #[inline]
    pub(super) fn d(&self, m: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        let r = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * m.z * m.z));
        if r * m.z > 1e-20 {
            r
        } else {
            0.0
        }
    }

    /// Density of [`sample`](Self::sample) per unit solid angle of m.
    #[inline]
    pub(super) fn pdf(&self, m: Vec3) -> f32 {
        if m.z < 0.0 {
            0.0
        } else {
            m.z * self.d(m)
        }
    }

    #[inline]
    pub(super) fn sample(&self, u: Vec2) -> Vec3 {
        let (sin_phi, cos_phi) = (2.0 * PI * u.x).sin_cos();
        let a2 = self.alpha * self.alpha;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin_theta = (1.0 - cos2).max(0.0).sqrt();
        Vec3::new(cos_phi * sin_theta, sin_phi * sin_theta, cos2.max(0.0).sqrt())
    }
}

/// The clearcoat's separable shadowing: Smith's GGX G1 with the fixed α 0.25 for each
/// direction (0 where a direction sees the back of the microfacet).
#[inline]
pub(super) fn clearcoat_g(wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
    smith_ggx1(wo, m, 0.25) * smith_ggx1(wi, m, 0.25)
}

#[inline]
fn smith_ggx1(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let c2 = v.z * v.z;
    let tan2 = (1.0 - c2) / c2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// The diffuse factor that multiplies base colour/π: Burley's retro-reflective diffuse
/// (1 − F_o/2)(1 − F_i/2) + R_r(F_o + F_i + F_o F_i (R_r − 1)), R_r = 2 r cos²θ_d, blended by
/// `flatness` towards the Hanrahan–Krueger-like 1.25 (F_ss (1/(cos θo + cos θi) − 0.5) + 0.5).
/// `cos_o`, `cos_i` are the absolute cosines, `cos_d` the cosine between wi and the half
/// vector.
#[inline]
pub(super) fn diffuse_factor(
    cos_o: f32,
    cos_i: f32,
    cos_d: f32,
    roughness: f32,
    flatness: f32,
) -> f32 {
    let (fo, fi) = (schlick_weight(cos_i), schlick_weight(cos_o));
    let f_diff = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    let fss90 = rr / 2.0;
    let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
    let f_ss = 1.25 * (fss * (1.0 / (cos_o + cos_i) - 0.5) + 0.5);
    (f_diff + f_retro) * (1.0 - flatness) + f_ss * flatness
}

/// The sheen colour: white tinted towards the base colour's hue by `sheen_tint`, times
/// Schlick's weight of cos θ_d.
#[inline]
pub(super) fn sheen(base_color: Spectrum, sheen_tint: f32, cos_d: f32) -> Spectrum {
    let c = Spectrum::ONE * (1.0 - sheen_tint) + tint(base_color) * sheen_tint;
    c * schlick_weight(cos_d.abs())
}

/// Lobe probabilities, normalised to sum 1 (all 0 when they sum to 0 or are not finite).
#[inline]
pub(super) fn normalised<const N: usize>(p: [f32; N]) -> [f32; N] {
    let total: f32 = p.iter().sum();
    if total > 0.0 && total.is_finite() {
        p.map(|x| x / total)
    } else {
        [0.0; N]
    }
}

/// Index of the lobe whose probability interval holds `u1` (the last one takes the rest).
#[inline]
pub(super) fn choose<const N: usize>(p: &[f32; N], u1: f32) -> usize {
    let mut acc = 0.0;
    for (k, &pk) in p.iter().enumerate().take(N - 1) {
        acc += pk;
        if u1 < acc {
            return k;
        }
    }
    N - 1
}
