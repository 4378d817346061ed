//! BSDFs: ρ(wo, wi), the ratio of reflected radiance to incident irradiance (1/sr).
//!
//! Conventions (see the crate docs): directions are given in the local shading frame (+z is
//! the shading normal), both point away from the surface, and `eval` returns the BSDF itself
//! **without** the cosine factor. Surfaces are one-sided like Mitsuba's: reflection models
//! return 0 unless both directions lie above the surface; `twosided` makes both faces
//! reflect.

mod blendbsdf;
mod bumpmap;
mod conductor;
mod dielectric;
mod diffuse;
pub mod fresnel;
pub mod ior;
mod mask;
mod merl;
pub mod microfacet;
mod normalmap;
mod perturbed;
mod phong;
mod plastic;
mod roughconductor;
mod roughdielectric;
mod roughplastic;
mod thindielectric;
mod twosided;

pub use blendbsdf::BlendBsdf;
pub use bumpmap::BumpMap;
pub use conductor::Conductor;
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use mask::Mask;
pub use merl::{Merl, MerlTable};
pub use microfacet::{MicrofacetDistribution, MicrofacetKind};
pub use normalmap::NormalMap;
pub use perturbed::PerturbOptions;
pub use phong::Phong;
pub use plastic::{InternalScattering, Plastic};
pub use roughconductor::RoughConductor;
pub use roughdielectric::RoughDielectric;
pub use roughplastic::RoughPlastic;
pub use thindielectric::ThinDielectric;
pub use twosided::TwoSided;

use glam::{Vec2, Vec3};

use crate::Spectrum;

/// What kind of scattering a sampled direction came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// Spreads over a solid angle (Lambertian, rough microfacets): has a finite density.
    Smooth,
    /// A Dirac delta (mirror, smooth glass): only reachable by sampling.
    Delta,
}

/// A direction drawn from a BSDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Sampled incident direction, local frame.
    pub wi: Vec3,
    /// Density of `wi` in 1/sr; for `Lobe::Delta`, the probability of having chosen that delta
    /// lobe (1 when it is the BSDF's only lobe). MIS never uses it for delta lobes.
    pub pdf: f32,
    /// The Monte Carlo weight ρ(wo, wi)·|cos θi| / pdf (dimensionless).
    pub weight: Spectrum,
    pub lobe: Lobe,
    /// Relative index of refraction η_t/η_i of the interface crossed by the sampled
    /// direction (1 for reflection and for straight pass-through), as Mitsuba's
    /// `BSDFSample::eta`. Transmission weights include the radiance factor (η_i/η_t)², so
    /// Russian roulette uses throughput·η² with η the product of these values along the path.
    pub eta: f32,
}

/// Where the BSDF is evaluated: the surface coordinates textures need and the local
/// differential geometry that bump and normal maps perturb.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint {
    /// Surface (texture) coordinates.
    pub uv: Vec2,
    /// ∂p/∂u and ∂p/∂v in the local shading frame (m per unit of u, v).
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    /// The geometric normal in the local shading frame (unit).
    pub ng: Vec3,
}

impl ShadingPoint {
    /// A point at `uv` of a flat surface whose shading frame is its (u, v, n) frame.
    pub fn at_uv(uv: Vec2) -> Self {
        ShadingPoint { uv, dpdu: Vec3::X, dpdv: Vec3::Y, ng: Vec3::Z }
    }

    /// The shading point of a surface interaction (its vectors taken to the shading frame).
    #[inline]
    pub fn new(si: &crate::geometry::SurfaceInteraction) -> Self {
        ShadingPoint {
            uv: si.uv,
            dpdu: si.to_local(si.dpdu),
            dpdv: si.to_local(si.dpdv),
            ng: si.to_local(si.n),
        }
    }
}

/// A BSDF. Closed enum: one variant per BSDF plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Bsdf {
    Diffuse(Diffuse),
    TwoSided(TwoSided),
    Conductor(Conductor),
    RoughConductor(RoughConductor),
    Dielectric(Dielectric),
    ThinDielectric(ThinDielectric),
    RoughDielectric(RoughDielectric),
    Plastic(Plastic),
    RoughPlastic(RoughPlastic),
    Phong(Phong),
    Merl(Merl),
    Mask(Mask),
    BlendBsdf(BlendBsdf),
    BumpMap(BumpMap),
    NormalMap(NormalMap),
}

/// Dispatches a method call to the variant's implementation.
macro_rules! dispatch {
    ($self:expr, $b:ident => $e:expr) => {
        match $self {
            Bsdf::Diffuse($b) => $e,
            Bsdf::TwoSided($b) => $e,
            Bsdf::Conductor($b) => $e,
            Bsdf::RoughConductor($b) => $e,
            Bsdf::Dielectric($b) => $e,
            Bsdf::ThinDielectric($b) => $e,
            Bsdf::RoughDielectric($b) => $e,
            Bsdf::Plastic($b) => $e,
            Bsdf::RoughPlastic($b) => $e,
            Bsdf::Phong($b) => $e,
            Bsdf::Merl($b) => $e,
            Bsdf::Mask($b) => $e,
            Bsdf::BlendBsdf($b) => $e,
            Bsdf::BumpMap($b) => $e,
            Bsdf::NormalMap($b) => $e,
        }
    };
}

impl Bsdf {
    /// ρ(wo, wi) in 1/sr, without the cosine.
    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        dispatch!(self, b => b.eval(sp, wo, wi))
    }

    /// Density (1/sr) with which `sample` proposes `wi` given `wo`.
    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        dispatch!(self, b => b.pdf(sp, wo, wi))
    }

    /// Draws `wi` given `wo` with uniforms `u1` (lobe choice) and `u2` (direction).
    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        dispatch!(self, b => b.sample(sp, wo, u1, u2))
    }

    /// True for a Lambertian surface (`diffuse`, or `twosided` with `diffuse` on both sides):
    /// ρ is a constant, so light sampling alone weighs its samples by the cosine only.
    #[inline]
    pub fn is_lambertian(&self) -> bool {
        match self {
            Bsdf::Diffuse(_) => true,
            Bsdf::TwoSided(b) => b.front.is_lambertian() && b.back.is_lambertian(),
            _ => false,
        }
    }

    /// True when some lobe has a finite density, so that light sampling can help.
    #[inline]
    pub fn has_smooth_lobe(&self) -> bool {
        match self {
            Bsdf::Diffuse(_)
            | Bsdf::RoughConductor(_)
            | Bsdf::RoughDielectric(_)
            | Bsdf::Plastic(_)
            | Bsdf::RoughPlastic(_) => true,
            Bsdf::Phong(_) | Bsdf::Merl(_) => true,
            Bsdf::Conductor(_) | Bsdf::Dielectric(_) | Bsdf::ThinDielectric(_) => false,
            Bsdf::TwoSided(b) => b.has_smooth_lobe(),
            Bsdf::Mask(b) => b.has_smooth_lobe(),
            Bsdf::BlendBsdf(b) => b.has_smooth_lobe(),
            Bsdf::BumpMap(b) => b.has_smooth_lobe(),
            Bsdf::NormalMap(b) => b.has_smooth_lobe(),
        }
    }

    /// Mitsuba's BSDF for a shape that has none: `diffuse` with reflectance 0.5.
    pub fn default_diffuse() -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(Spectrum::splat(Diffuse::DEFAULT_REFLECTANCE).into()))
    }

    /// Mitsuba's BSDF for an emitting shape that has none: a black `diffuse`.
    pub fn black() -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(Spectrum::ZERO.into()))
    }
}

/// The sample of a BSDF that proposed `wi` with density `pdf`, its whole `pdf(wo, wi)` over
/// every lobe that could have drawn it: weight `f·cos θᵢ / pdf`, with `f` evaluated only when
/// the density is positive. `None` when it is not (or is NaN).
#[inline]
pub(crate) fn smooth_sample(
    wi: Vec3,
    pdf: f32,
    f: impl FnOnce() -> Spectrum,
) -> Option<BsdfSample> {
    if !positive(pdf) {
        return None;
    }
    Some(BsdfSample { wi, pdf, weight: f() * (cos_theta(wi) / pdf), lobe: Lobe::Smooth, eta: 1.0 })
}

/// True for x > 0; false for zero, negatives and NaN.
#[inline]
pub(crate) fn positive(x: f32) -> bool {
    x > 0.0
}

/// cos θ of a local direction.
#[inline]
pub(crate) fn cos_theta(w: Vec3) -> f32 {
    w.z
}

#[cfg(test)]
pub(crate) mod testing {
    //! Shared checks every BSDF must pass: sampling matches the density (χ² test),
    //! the sample weight equals eval·cos/pdf, reciprocity, and energy conservation.

    use std::f64::consts::PI;

    use glam::{Vec2, Vec3};

    use super::{Bsdf, Lobe, ShadingPoint};
    use crate::sampling::Pcg32;

    pub fn sp() -> ShadingPoint {
        ShadingPoint::at_uv(Vec2::new(0.3, 0.6))
    }

    pub fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
        let (st, ct) = theta_deg.to_radians().sin_cos();
        let (sp, cp) = phi_deg.to_radians().sin_cos();
        Vec3::new(st * cp, st * sp, ct)
    }

    /// Pearson χ² goodness-of-fit of `sample` against `pdf` on a (θ, φ) grid over the sphere,
    /// cells with small expected counts pooled (pbrt-v4 / Mitsuba 3 style). Returns the
    /// p-value.
    pub fn chi2_pvalue(bsdf: &Bsdf, wo: Vec3, n: usize, seed: u64) -> f64 {
        chi2_pvalue_sub(bsdf, wo, n, seed, 8)
    }

    /// [`chi2_pvalue`] with `sub`² pdf evaluations per cell for the expected counts: sharp
    /// lobes (α ≲ 0.1) need a finer quadrature than the default 8² to be integrated exactly.
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
        const NT: usize = 20;
        const NP: usize = 40;
        let mut observed = vec![0f64; NT * NP];
        let mut rng = Pcg32::new(seed, 11);
        let sp = sp();
        let mut delta = 0usize;
        for _ in 0..n {
            let u1 = rng.next_f32();
            let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
            if let Some(s) = bsdf.sample(&sp, wo, u1, u2) {
                // the path tracer takes sampled directions as they come, without renormalising
                assert!(
                    (s.wi.length() - 1.0).abs() < 1e-5,
                    "sampled direction {} is not a unit vector (|wi| = {})",
                    s.wi,
                    s.wi.length()
                );
                if s.lobe == Lobe::Delta {
                    delta += 1;
                    continue;
                }
                let w = s.wi;
                let t = (w.z.clamp(-1.0, 1.0) as f64).acos();
                let mut p = (w.y as f64).atan2(w.x as f64);
                if p < 0.0 {
                    p += 2.0 * PI;
                }
                let it = ((t / PI * NT as f64) as usize).min(NT - 1);
                let ip = ((p / (2.0 * PI) * NP as f64) as usize).min(NP - 1);
                observed[it * NP + ip] += 1.0;
            }
        }
        assert!(allow_delta || delta == 0, "chi2 test covers smooth lobes only");
        // expected counts: integrate the pdf over each cell (midpoint rule on a fine grid)
        let sub_n = sub;
        let mut expected = vec![0f64; NT * NP];
        for it in 0..NT {
            for ip in 0..NP {
                let mut acc = 0.0;
                for a in 0..sub_n {
                    for b in 0..sub_n {
                        let t0 = (it as f64 + (a as f64 + 0.5) / sub_n as f64) * PI / NT as f64;
                        let p0 =
                            (ip as f64 + (b as f64 + 0.5) / sub_n as f64) * 2.0 * PI / NP as f64;
                        let w = Vec3::new(
                            (t0.sin() * p0.cos()) as f32,
                            (t0.sin() * p0.sin()) as f32,
                            t0.cos() as f32,
                        );
                        acc += bsdf.pdf(&sp, wo, w) as f64 * t0.sin();
                    }
                }
                let cell = (PI / NT as f64) * (2.0 * PI / NP as f64) / (sub_n * sub_n) as f64;
                expected[it * NP + ip] = acc * cell * n as f64;
            }
        }
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

    /// Checks that a sample's weight equals eval·|cos|/pdf and its pdf equals `pdf()`.
    pub fn check_sample_consistency(bsdf: &Bsdf, wo: Vec3, seed: u64) {
        let mut rng = Pcg32::new(seed, 5);
        let sp = sp();
        for _ in 0..2000 {
            let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
            let Some(s) = bsdf.sample(&sp, wo, rng.next_f32(), u2) else { continue };
            if s.lobe == Lobe::Delta {
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

    /// Directional albedo ∫ρ cos dωi by sampling, with its standard error.
    pub fn albedo(bsdf: &Bsdf, wo: Vec3, n: usize, seed: u64) -> ([f64; 3], [f64; 3]) {
        let mut rng = Pcg32::new(seed, 17);
        let sp = sp();
        let (mut s1, mut s2) = ([0f64; 3], [0f64; 3]);
        for _ in 0..n {
            let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
            if let Some(s) = bsdf.sample(&sp, wo, rng.next_f32(), u2) {
                assert!(
                    (s.wi.length() - 1.0).abs() < 1e-5,
                    "sampled direction {} is not a unit vector (|wi| = {})",
                    s.wi,
                    s.wi.length()
                );
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
}
