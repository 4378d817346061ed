//! Fresnel equations and mirror/refraction helpers (local frame, +z = normal).
//!
//! Dielectric and conductor reflectances are the exact unpolarised ones (mean of the s- and
//! p-polarised power reflectances), as in Mitsuba 3's `fresnel.h`. Directions follow the
//! crate convention: they point away from the surface.

use glam::Vec3;

use crate::Spectrum;

/// Result of [`fresnel_dielectric`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricFresnel {
    /// Unpolarised reflectance F ∈ [0, 1] (1 under total internal reflection).
    pub r: f32,
    /// Signed cosine of the transmitted direction: opposite in sign to cos θi, 0 under TIR.
    pub cos_theta_t: f32,
    /// Relative IOR in the direction of travel, η_t/η_i (η or 1/η depending on the side).
    pub eta_it: f32,
    /// Its reciprocal η_i/η_t: the factor that scales the tangential part of the refracted
    /// direction, and whose square scales transmitted radiance.
    pub eta_ti: f32,
}

/// Unpolarised Fresnel reflectance at a dielectric interface.
///
/// `cos_theta_i` is the cosine between the direction and the normal (negative: the direction
/// lies inside, on the −z side); `eta` = η_inside/η_outside is the relative IOR of the
/// interface (the side the normal points away from is "inside").
pub fn fresnel_dielectric(cos_theta_i: f32, eta: f32) -> DielectricFresnel {
    let outside = cos_theta_i >= 0.0;
    let (eta_it, eta_ti) = if outside { (eta, 1.0 / eta) } else { (1.0 / eta, eta) };
    let cos_t_sqr = 1.0 - (1.0 - cos_theta_i * cos_theta_i) * eta_ti * eta_ti;
    let ci = cos_theta_i.abs();
    let ct = cos_t_sqr.max(0.0).sqrt();
    let r = if eta == 1.0 {
        0.0
    } else if ci == 0.0 {
        1.0
    } else {
        let a_s = (ci - eta_it * ct) / (ci + eta_it * ct);
        let a_p = (ct - eta_it * ci) / (ct + eta_it * ci);
        0.5 * (a_s * a_s + a_p * a_p)
    };
    let cos_theta_t = if cos_theta_i >= 0.0 { -ct } else { ct };
    DielectricFresnel { r, cos_theta_t, eta_it, eta_ti }
}

/// A conductor's complex index of refraction η + i·k (per channel, dimensionless). Mitsuba's
/// default (`material` = `none`: η = 0, k = 1) is told apart: its Fresnel reflectance
/// |(cos θ − i)/(cos θ + i)|² is 1 at every angle, so it needs no arithmetic (the general
/// formula also gives exactly 1 there: `perfect_mirror_is_the_general_formula`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConductorIor {
    /// η = 0, k = 1: a perfect mirror.
    Perfect,
    Complex {
        eta: Spectrum,
        k: Spectrum,
    },
}

impl ConductorIor {
    pub fn new(eta: Spectrum, k: Spectrum) -> Self {
        if eta == Spectrum::ZERO && k == Spectrum::ONE {
            ConductorIor::Perfect
        } else {
            ConductorIor::Complex { eta, k }
        }
    }

    /// η, the real part.
    pub fn eta(&self) -> Spectrum {
        match self {
            ConductorIor::Perfect => Spectrum::ZERO,
            ConductorIor::Complex { eta, .. } => *eta,
        }
    }

    /// k, the imaginary part.
    pub fn k(&self) -> Spectrum {
        match self {
            ConductorIor::Perfect => Spectrum::ONE,
            ConductorIor::Complex { k, .. } => *k,
        }
    }

    /// Fresnel reflectance for light arriving from outside at cos θ = `cos_theta_i` ≥ 0.
    #[inline]
    pub fn fresnel(&self, cos_theta_i: f32) -> Spectrum {
        match self {
            ConductorIor::Perfect => Spectrum::ONE,
            ConductorIor::Complex { eta, k } => fresnel_conductor(cos_theta_i, *eta, *k),
        }
    }
}

/// Unpolarised Fresnel reflectance of a conductor with complex IOR η + i·k (per channel),
/// for light arriving from outside (`cos_theta_i` ≥ 0).
pub fn fresnel_conductor(cos_theta_i: f32, eta: Spectrum, k: Spectrum) -> Spectrum {
    let f = |eta_r: f32, eta_i: f32| -> f32 {
        let c2 = cos_theta_i * cos_theta_i;
        let s2 = 1.0 - c2;
        let s4 = s2 * s2;
        let t1 = eta_r * eta_r - eta_i * eta_i - s2;
        let a2pb2 = (t1 * t1 + 4.0 * eta_i * eta_i * eta_r * eta_r).max(0.0).sqrt();
        let a = (0.5 * (a2pb2 + t1)).max(0.0).sqrt();
        let term1 = a2pb2 + c2;
        let term2 = 2.0 * cos_theta_i * a;
        let r_s = (term1 - term2) / (term1 + term2);
        let term3 = a2pb2 * c2 + s4;
        let term4 = term2 * s2;
        let r_p = r_s * (term3 - term4) / (term3 + term4);
        0.5 * (r_s + r_p)
    };
    Spectrum::new(f(eta.x, k.x), f(eta.y, k.y), f(eta.z, k.z))
}

/// Diffuse Fresnel reflectance F_dr(η) = 2∫₀¹ F(μ, η) μ dμ: the fraction of uniformly
/// diffuse (Lambertian) radiance that an interface of relative IOR η reflects back. Mitsuba's
/// fits, which `plastic` relies on: Egan & Hilgeman (1973) for η < 1, d'Eon & Irving (2011)
/// otherwise (relative error ≤ 0.2 % for 1 ≤ η ≤ 10; checked against quadrature in the tests).
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        let p = [0.919317f32, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
        p.iter().rev().fold(0.0, |acc, c| acc * inv + c)
    }
}

/// Mirror direction about the shading normal (+z).
#[inline]
pub fn reflect(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

/// Mirror direction of `w` about the unit normal `m`.
#[inline]
pub fn reflect_about(w: Vec3, m: Vec3) -> Vec3 {
    2.0 * w.dot(m) * m - w
}

/// Refraction through the shading normal, with `cos_theta_t` and `eta_ti` from
/// [`fresnel_dielectric`].
#[inline]
pub fn refract(w: Vec3, cos_theta_t: f32, eta_ti: f32) -> Vec3 {
    Vec3::new(-eta_ti * w.x, -eta_ti * w.y, cos_theta_t)
}

/// Refraction of `w` through a microfacet with unit normal `m`, with `cos_theta_t` and
/// `eta_ti` from [`fresnel_dielectric`] evaluated at `w·m`.
#[inline]
pub fn refract_about(w: Vec3, m: Vec3, cos_theta_t: f32, eta_ti: f32) -> Vec3 {
    m * (w.dot(m) * eta_ti + cos_theta_t) - w * eta_ti
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shortcut of [`ConductorIor::Perfect`] changes no pixel: the general formula gives
    /// exactly 1 for η = 0, k = 1 at every angle (here 10⁵ of them, grazing included).
    #[test]
    fn perfect_mirror_is_the_general_formula() {
        assert_eq!(ConductorIor::new(Spectrum::ZERO, Spectrum::ONE), ConductorIor::Perfect);
        for i in 0..=100_000 {
            let cos = i as f32 / 100_000.0;
            assert_eq!(
                fresnel_conductor(cos, Spectrum::ZERO, Spectrum::ONE),
                Spectrum::ONE,
                "cos θ = {cos}"
            );
        }
        // other conductors keep the general formula
        let gold = ConductorIor::new(Spectrum::new(0.2, 0.4, 1.4), Spectrum::new(3.6, 2.4, 1.8));
        assert!(matches!(gold, ConductorIor::Complex { .. }));
        assert!(gold.fresnel(0.5).max_element() < 1.0);
    }

    #[test]
    fn diffuse_reflectance_fit_matches_quadrature() {
        // F_dr = 2∫ F(μ) μ dμ by Gauss–Legendre on [0, 1]; the fits are good to 0.2 % (η > 1)
        // and 1 % (η < 1, Egan–Hilgeman at these IORs).
        let (x, w) = crate::radiometry::gauss_legendre::<64>();
        for (eta, tol) in [
            (1.1f32, 2e-3),
            (1.333, 2e-3),
            (1.49, 2e-3),
            (2.0, 2e-3),
            (1.0 / 1.49, 1e-2),
            (1.0 / 1.333, 1e-2),
        ] {
            let exact: f64 = x
                .iter()
                .zip(&w)
                .map(|(&xi, &wi)| {
                    let mu = 0.5 * (xi + 1.0);
                    wi * 0.5 * 2.0 * fresnel_dielectric(mu as f32, eta).r as f64 * mu
                })
                .sum();
            let fit = fresnel_diffuse_reflectance(eta) as f64;
            assert!(
                (fit - exact).abs() <= tol * exact,
                "η = {eta}: fit {fit} vs quadrature {exact}"
            );
        }
    }

    #[test]
    fn normal_incidence_dielectric() {
        for eta in [1.333f32, 1.5046, 2.419] {
            let f = fresnel_dielectric(1.0, eta);
            let expect = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((f.r - expect).abs() < 1e-6, "{eta}: {} vs {expect}", f.r);
            assert!((f.cos_theta_t + 1.0).abs() < 1e-6);
            // same from inside
            let g = fresnel_dielectric(-1.0, eta);
            assert!((g.r - expect).abs() < 1e-6);
            assert!((g.cos_theta_t - 1.0).abs() < 1e-6 && g.eta_it == 1.0 / eta);
        }
    }

    #[test]
    fn total_internal_reflection_and_grazing() {
        let eta = 1.5f32;
        let crit = (1.0 / eta).asin();
        // just beyond the critical angle, from inside
        let f = fresnel_dielectric(-(crit + 0.01).cos(), eta);
        assert_eq!(f.r, 1.0);
        assert_eq!(f.cos_theta_t, 0.0);
        // just inside it: partial transmission
        let f = fresnel_dielectric(-(crit - 0.01).cos(), eta);
        assert!(f.r < 1.0 && f.r > 0.0);
        // grazing from outside → 1
        let f = fresnel_dielectric(1e-4, eta);
        assert!(f.r > 0.999, "{}", f.r);
        // Snell's law: η_i sin θi = η_t sin θt
        let ci = 40f32.to_radians().cos();
        let f = fresnel_dielectric(ci, eta);
        let si = (1.0 - ci * ci).sqrt();
        let st = (1.0 - f.cos_theta_t * f.cos_theta_t).sqrt();
        assert!((si - eta * st).abs() < 1e-6);
        // refracted direction is unit and on the other side
        let w = Vec3::new(si, 0.0, ci);
        let t = refract(w, f.cos_theta_t, f.eta_ti);
        assert!((t.length() - 1.0).abs() < 1e-5 && t.z < 0.0);
    }

    #[test]
    fn conductor_normal_incidence_and_grazing() {
        let eta = Spectrum::new(0.143036, 0.375307, 1.44205);
        let k = Spectrum::new(3.983, 2.38556, 1.60336);
        let f = fresnel_conductor(1.0, eta, k);
        for c in 0..3 {
            let (n, kk) = (eta[c], k[c]);
            let expect = ((n - 1.0).powi(2) + kk * kk) / ((n + 1.0).powi(2) + kk * kk);
            assert!((f[c] - expect).abs() < 1e-5, "{c}: {} vs {expect}", f[c]);
        }
        let g = fresnel_conductor(1e-4, eta, k);
        assert!(g.min_element() > 0.999, "{g:?}");
        // eta 0, k 1: perfect mirror at every angle
        for ct in [1.0f32, 0.7, 0.2, 0.01] {
            let m = fresnel_conductor(ct, Spectrum::ZERO, Spectrum::ONE);
            assert!((m - Spectrum::ONE).abs().max_element() < 1e-6, "{m:?}");
        }
        // a conductor with k = 0 reduces to the dielectric formula
        let d = fresnel_conductor(0.6, Spectrum::splat(1.5), Spectrum::ZERO);
        assert!((d.x - fresnel_dielectric(0.6, 1.5).r).abs() < 1e-5);
    }

    #[test]
    fn reflect_about_normal() {
        let w = Vec3::new(0.3, -0.4, 0.866).normalize();
        assert!((reflect_about(w, Vec3::Z) - reflect(w)).length() < 1e-6);
    }
}
