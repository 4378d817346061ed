//! `measured`: a material measured by RGL's gonio-photometer, in the adaptive parameterisation
//! of Dupuy and Jakob (2018, "An adaptive parameterization for efficient material
//! acquisition and rendering"), read from the material database's RGB `.bsdf` files.
//!
//! | parameter  | type   | default    | meaning |
//! |------------|--------|------------|---------|
//! | `filename` | string | (required) | the material's RGB file (`*_rgb.bsdf`), a Mitsuba tensor file, relative to the scene |
//!
//! **Model** (Mitsuba 3's `measured`, term for term). With v the viewer's direction and l the
//! light's (both local, above the surface), h = (v + l)/|v + l|, θ and φ their spherical
//! angles and u(θ) = √(2θ/π), u(φ) = (φ + π)/2π their unit coordinates, the file tabulates
//! over the grid of incident angles (φᵥ, θᵥ) (`phi_i`, `theta_i`):
//! - `vndf`: the density of visible normals over (u(θ_h), u(φ_h)) (φ_h taken relative to φᵥ
//!   for an isotropic material), a [`Marginal2D`] warp;
//! - `rgb`: the reflected RGB, ρ·cos θ_l, stored over the *uniform* square that warp maps
//!   from: the value of a pair is looked up at `vndf.invert(u(h))`;
//! - `ndf` over u(h) and `sigma` (the projected area) over u(v): with `jacobian` set, the
//!   value is multiplied by D(h)/(4σ(v));
//! - `luminance`: the density the square is sampled with before the VNDF warp.
//!
//! So ρ(v, l) = rgb(vndf⁻¹(u(h)); φᵥ, θᵥ)·D(h)/(4σ(v)) / cos θ_l (1/sr). Between tabulated
//! values every table is interpolated (bilinearly on its grid, linearly across φᵥ and θᵥ).
//! An anisotropic file covers φᵥ over 2π/k (k = 2 or 4): v and l are mirrored into that
//! range first; so, as Mitsuba 3.9.1 does, is an isotropic file's, as if it covered half the
//! range (this matters where σ depends on φᵥ). One-sided: 0 unless both directions lie
//! above the surface.
//!
//! **Sampling** (as Mitsuba): the uniforms are warped by `luminance` and then by `vndf` to h,
//! and l is v reflected about h; pdf = p_vndf·p_luminance / (2π²·u(θ_h)·sin θ_h·4(v·h)),
//! with 2π²·u·sin θ floored at 10⁻⁶ as Mitsuba floors it. The weight is ρ·cos θ_l/pdf.
//!
//! **Where steradian differs.** A spectral file (one with `wavelengths`) is an error naming
//! the RGB file to use instead, as in Mitsuba's RGB variants. Negative, non-finite or (for
//! `sigma`) zero table values, and `phi_i`/`theta_i` that do not increase, are errors where
//! Mitsuba would render NaNs or wrong interpolations.

use std::f32::consts::{FRAC_2_PI, PI, TAU};
use std::fmt;
use std::path::Path;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::tensor_file::{self, Field};
use super::{BsdfSample, Lobe, ShadingPoint};
use crate::sampling::marginal_2d::Marginal2D;
use crate::Spectrum;

/// The mirroring Mitsuba 3.9.1 applies to an isotropic file: that of a file covering half
/// the range of φᵥ (its eval, against this and the other choices, on 40 random pairs of
/// directions: 5·10⁻⁷ relative against 0.29 unmirrored).
const ISOTROPIC_REDUCTION: u32 = 2;

/// The tables of one material file.
#[derive(Clone, PartialEq)]
pub struct MeasuredTables {
    /// The file's `description`, for messages.
    description: String,
    /// At most two φᵥ values: the material is isotropic.
    isotropic: bool,
    /// 2 or 4: φᵥ covers 2π/`reduction` and directions are mirrored into it; 1: no mirroring.
    reduction: u32,
    /// Whether the value carries the D(h)/(4σ(v)) factor.
    jacobian: bool,
    ndf: Marginal2D,
    sigma: Marginal2D,
    vndf: Marginal2D,
    luminance: Marginal2D,
    rgb: Marginal2D,
}

impl fmt::Debug for MeasuredTables {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("MeasuredTables")
            .field("description", &self.description)
            .field("isotropic", &self.isotropic)
            .field("reduction", &self.reduction)
            .finish()
    }
}

/// θ's unit coordinate u(θ) = √(2θ/π) (samples concentrate near the normal).
#[inline]
fn theta_to_u(theta: f32) -> f32 {
    (theta * FRAC_2_PI).sqrt()
}

#[inline]
fn u_to_theta(u: f32) -> f32 {
    u * u * (PI / 2.0)
}

#[inline]
fn phi_to_u(phi: f32) -> f32 {
    (phi + PI) * (1.0 / TAU)
}

#[inline]
fn u_to_phi(u: f32) -> f32 {
    (2.0 * u - 1.0) * PI
}

/// The polar angle of a unit vector, accurate near the pole: 2·asin(|d − ẑ|/2).
#[inline]
fn elevation(d: Vec3) -> f32 {
    let dist = (d.x * d.x + d.y * d.y + (d.z - 1.0) * (d.z - 1.0)).sqrt();
    2.0 * (0.5 * dist).clamp(-1.0, 1.0).asin()
}

/// x with its sign flipped where s ≥ 0 (Mitsuba's `mulsign_neg`).
#[inline]
fn mulsign_neg(x: f32, s: f32) -> f32 {
    if s >= 0.0 {
        -x
    } else {
        x
    }
}

impl MeasuredTables {
    /// Reads a material file.
    pub fn read(path: &Path) -> Result<Self, String> {
        let bytes = std::fs::read(path)
            .map_err(|e| format!("cannot read the material file {}: {e}", path.display()))?;
        Self::from_bytes(&bytes).map_err(|e| format!("material file {}: {e}", path.display()))
    }

    /// Parses the bytes of a material file.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        let fields = tensor_file::parse(bytes)?;
        let field = |name: &str| -> Result<&Field, String> {
            fields.get(name).ok_or_else(|| format!("it has no \"{name}\" field"))
        };
        if fields.contains_key("wavelengths") {
            return Err("it holds spectral measurements (a \"wavelengths\" field); steradian \
                        renders in RGB, as Mitsuba's RGB variants do: use the material's RGB \
                        file (`*_rgb.bsdf`)"
                .into());
        }
        let floats = |name: &str, rank: usize| -> Result<(Vec<f32>, Vec<usize>), String> {
            let f = field(name)?;
            let values = f
                .f32s()
                .ok_or_else(|| format!("field \"{name}\" is not float32 (type {})", f.dtype))?;
            if f.shape.len() != rank {
                return Err(format!(
                    "field \"{name}\" has shape {:?}; rank {rank} expected",
                    f.shape
                ));
            }
            Ok((values, f.shape.clone()))
        };
        let bytes_of = |name: &str| -> Result<&[u8], String> {
            let f = field(name)?;
            f.u8s()
                .filter(|_| f.shape.len() == 1)
                .ok_or_else(|| format!("field \"{name}\" must be a one-dimensional uint8 array"))
        };
        let description = String::from_utf8_lossy(bytes_of("description")?).into_owned();
        let jacobian = match bytes_of("jacobian")? {
            [j] => *j != 0,
            other => {
                return Err(format!("field \"jacobian\" has {} values; 1 expected", other.len()))
            }
        };
        let (theta_i, _) = floats("theta_i", 1)?;
        let (phi_i, _) = floats("phi_i", 1)?;
        let (ndf, ndf_shape) = floats("ndf", 2)?;
        let (sigma, sigma_shape) = floats("sigma", 2)?;
        let (vndf, vndf_shape) = floats("vndf", 4)?;
        let (luminance, lum_shape) = floats("luminance", 4)?;
        let (rgb, rgb_shape) = floats("rgb", 5)?;
        let (np, nt) = (phi_i.len(), theta_i.len());
        let consistent = vndf_shape[..2] == [np, nt]
            && lum_shape[..2] == [np, nt]
            && lum_shape[2] == lum_shape[3]
            && rgb_shape[..3] == [np, nt, 3]
            && rgb_shape[3] == rgb_shape[4]
            && lum_shape[2..] == rgb_shape[3..];
        if !consistent {
            return Err(format!(
                "inconsistent shapes: phi_i {np}, theta_i {nt}, vndf {vndf_shape:?}, luminance \
                 {lum_shape:?}, rgb {rgb_shape:?} (expected vndf (φ, θ, n, m), luminance and \
                 rgb (φ, θ, n, n) and (φ, θ, 3, n, n))"
            ));
        }
        if jacobian && sigma.iter().any(|&s| s <= 0.0) {
            return Err("a \"sigma\" value is not positive: the projected area divides".into());
        }
        let isotropic = np <= 2;
        let reduction = if isotropic {
            ISOTROPIC_REDUCTION
        } else {
            let k = (TAU / (phi_i[np - 1] - phi_i[0])).round();
            if !(k.is_finite() && k >= 1.0) {
                return Err(format!(
                    "phi_i spans {:?}: not a fraction of 2π",
                    (phi_i[0], phi_i[np - 1])
                ));
            }
            k as u32
        };
        let named = |name: &'static str| move |e: String| format!("field \"{name}\": {e}");
        let angles = vec![phi_i.clone(), theta_i.clone()];
        Ok(MeasuredTables {
            description,
            isotropic,
            reduction,
            jacobian,
            ndf: Marginal2D::interpolant(&ndf, ndf_shape[1], ndf_shape[0], vec![])
                .map_err(named("ndf"))?,
            sigma: Marginal2D::interpolant(&sigma, sigma_shape[1], sigma_shape[0], vec![])
                .map_err(named("sigma"))?,
            vndf: Marginal2D::density(&vndf, vndf_shape[3], vndf_shape[2], angles.clone())
                .map_err(named("vndf"))?,
            luminance: Marginal2D::density(&luminance, lum_shape[3], lum_shape[2], angles)
                .map_err(named("luminance"))?,
            rgb: Marginal2D::interpolant(
                &rgb,
                rgb_shape[4],
                rgb_shape[3],
                vec![phi_i, theta_i, vec![0.0, 1.0, 2.0]],
            )
            .map_err(named("rgb"))?,
        })
    }

    /// The file's description.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The signs that mirror a direction into the tabulated range of φᵥ (module docs), from
    /// the viewer's direction: (sx, sy) for `mulsign_neg`, or `None` without mirroring.
    #[inline]
    fn mirror(&self, v: Vec3) -> Option<(f32, f32)> {
        (self.reduction >= 2).then(|| {
            let sy = v.y;
            (if self.reduction == 4 { v.x } else { sy }, sy)
        })
    }

    /// The RGB value ρ·cos θ_l at the warped point `sample` for the viewer's angles, with the
    /// D/(4σ) factor.
    #[inline]
    fn reflected(
        &self,
        sample: [f32; 2],
        phi_v: f32,
        theta_v: f32,
        u_h: [f32; 2],
        u_v: [f32; 2],
    ) -> Spectrum {
        let c = |k: f32| self.rgb.eval(sample, &[phi_v, theta_v, k]);
        let rgb = Spectrum::new(c(0.0), c(1.0), c(2.0));
        if self.jacobian {
            rgb * (self.ndf.eval(u_h, &[]) / (4.0 * self.sigma.eval(u_v, &[])))
        } else {
            rgb
        }
    }

    /// The unit coordinates of h for the viewer at `v` (mirrored), and the viewer's angles.
    #[inline]
    fn half_vector_coordinates(&self, v: Vec3, h: Vec3) -> ([f32; 2], f32, f32) {
        let (theta_v, phi_v) = (elevation(v), v.y.atan2(v.x));
        let phi_h = h.y.atan2(h.x);
        let u_phi = phi_to_u(if self.isotropic { phi_h - phi_v } else { phi_h });
        ([theta_to_u(elevation(h)), u_phi - u_phi.floor()], phi_v, theta_v)
    }

    /// (ρ·cos θ_l, pdf) for viewer `v` and light `l` (local, both above the surface).
    fn eval_pdf(&self, v: Vec3, l: Vec3) -> (Spectrum, f32) {
        let (v, l) = match self.mirror(v) {
            Some((sx, sy)) => (
                Vec3::new(mulsign_neg(v.x, sx), mulsign_neg(v.y, sy), v.z),
                Vec3::new(mulsign_neg(l.x, sx), mulsign_neg(l.y, sy), l.z),
            ),
            None => (v, l),
        };
        let h = (v + l).normalize();
        let (u_h, phi_v, theta_v) = self.half_vector_coordinates(v, h);
        let u_v = [theta_to_u(theta_v), phi_to_u(phi_v)];
        let params = [phi_v, theta_v];
        let (sample, vndf_pdf) = self.vndf.invert(u_h, &params);
        let value = self.reflected(sample, phi_v, theta_v, u_h, u_v);
        // sin θ_h from h's tangent components: 1 − cos² loses it near the mirror direction,
        // where the density is largest (Mitsuba's pdf takes that path; sampling does not)
        let sin_theta_h = (h.x * h.x + h.y * h.y).sqrt();
        let jacobian = (2.0 * PI * PI * u_h[0] * sin_theta_h).max(1e-6) * 4.0 * v.dot(h);
        (value, vndf_pdf * self.luminance.eval(sample, &params) / jacobian)
    }
}

/// The `measured` BSDF: shared tables.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    tables: Arc<MeasuredTables>,
}

impl Measured {
    pub fn new(tables: MeasuredTables) -> Self {
        Measured { tables: Arc::new(tables) }
    }

    pub fn tables(&self) -> &MeasuredTables {
        &self.tables
    }

    /// ρ(wo, wi) (1/sr), wo the viewer's direction.
    #[inline]
    pub fn eval(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Spectrum::ZERO;
        }
        self.tables.eval_pdf(wo, wi).0 / wi.z
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        self.tables.eval_pdf(wo, wi).1.max(0.0)
    }

    #[inline]
    pub fn sample(&self, _sp: &ShadingPoint, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let t = &*self.tables;
        if wo.z <= 0.0 {
            return None;
        }
        let mirror = t.mirror(wo);
        let v = match mirror {
            Some((sx, sy)) => Vec3::new(mulsign_neg(wo.x, sx), mulsign_neg(wo.y, sy), wo.z),
            None => wo,
        };
        let (theta_v, phi_v) = (elevation(v), v.y.atan2(v.x));
        let params = [phi_v, theta_v];
        let (sample, pdf_luminance) = t.luminance.sample([u2.y, u2.x], &params);
        let (u_h, pdf_vndf) = t.vndf.sample(sample, &params);
        let phi_h = u_to_phi(u_h[1]) + if t.isotropic { phi_v } else { 0.0 };
        let theta_h = u_to_theta(u_h[0]);
        let (sin_phi, cos_phi) = phi_h.sin_cos();
        let (sin_theta, cos_theta) = theta_h.sin_cos();
        let h = Vec3::new(cos_phi * sin_theta, sin_phi * sin_theta, cos_theta);
        let jacobian = (2.0 * PI * PI * u_h[0] * sin_theta).max(1e-6) * 4.0 * v.dot(h);
        let pdf = pdf_vndf * pdf_luminance / jacobian;
        let l = 2.0 * v.dot(h) * h - v;
        let u_v = [theta_to_u(theta_v), phi_to_u(phi_v)];
        let value = t.reflected(sample, phi_v, theta_v, u_h, u_v);
        let wi = match mirror {
            Some((sx, sy)) => Vec3::new(mulsign_neg(l.x, sx), mulsign_neg(l.y, sy), l.z),
            None => l,
        };
        if wi.z <= 0.0 || !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        Some(BsdfSample { wi, pdf, weight: value / pdf, lobe: Lobe::Smooth, eta: 1.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::bsdf::{chi2_pvalue_sub, compare_with_mitsuba_table, dir, sp};

    fn material(name: &str) -> Measured {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/bsdf/testdata").join(name);
        Measured::new(MeasuredTables::read(&path).expect("the test material loads"))
    }

    fn materials() -> Vec<super::super::Bsdf> {
        ["measured_iso_rgb.bsdf", "measured_aniso_rgb.bsdf"]
            .map(|n| super::super::Bsdf::Measured(material(n)))
            .to_vec()
    }

    /// The two materials with a VNDF that vanishes at the normal (scripts/make_measured_bsdf.py).
    fn smooth_materials() -> Vec<super::super::Bsdf> {
        ["measured_smooth_iso_rgb.bsdf", "measured_smooth_aniso_rgb.bsdf"]
            .map(|n| super::super::Bsdf::Measured(material(n)))
            .to_vec()
    }

    #[test]
    fn values_and_densities_match_mitsuba() {
        // testdata/measured.csv: Mitsuba 3.9.1's eval and pdf of the two synthetic files of
        // scripts/make_measured_bsdf.py (scripts/bsdf_table.py measured)
        compare_with_mitsuba_table(&materials(), include_str!("testdata/measured.csv"));
    }

    /// Viewer directions (degrees), with azimuths in several quadrants so that the
    /// anisotropic files' mirroring is crossed.
    const VIEWS: [(f32, f32); 5] =
        [(0.0, 0.0), (25.0, 35.0), (55.0, 130.0), (80.0, 250.0), (40.0, 300.0)];

    #[test]
    fn sampling_matches_the_density() {
        // χ² of 2·10⁵ samples per viewer direction, 1 % level over the family (Bonferroni);
        // on the smooth files, whose density the grid's quadrature integrates exactly
        let tests = (2 * VIEWS.len()) as f64;
        for (i, b) in smooth_materials().iter().enumerate() {
            for (j, &(theta, phi)) in VIEWS.iter().enumerate() {
                let p = chi2_pvalue_sub(b, dir(theta, phi), 200_000, (10 * i + j) as u64, 64);
                assert!(p > 0.01 / tests, "material {i}, view ({theta}°, {phi}°): p-value {p}");
            }
        }
    }

    #[test]
    fn samples_carry_their_density_and_weight() {
        for b in materials().iter().chain(&smooth_materials()) {
            for (j, &(theta, phi)) in VIEWS.iter().enumerate() {
                sample_agrees_with_eval_and_pdf(b, dir(theta, phi), j as u64);
            }
        }
    }

    /// A sample's pdf and weight against `pdf()` and `eval()` of its direction. Within 3·10⁻⁴ rad
    /// of the mirror direction the density grows as θ_h^(−3/2) and a direction in f32 no
    /// longer pins h down (θ_h loses ~3·10⁻⁸ rad): those samples, as in Mitsuba, are left
    /// out, and must be few.
    fn sample_agrees_with_eval_and_pdf(b: &super::super::Bsdf, wo: Vec3, seed: u64) {
        let (s, mut rng) = (sp(), Pcg32::new(seed, 5));
        let (mut checked, mut near_mirror) = (0, 0);
        for _ in 0..4000 {
            let u2 = Vec2::new(rng.next_f32(), rng.next_f32());
            let Some(x) = b.sample(&s, wo, 0.5, u2) else { continue };
            if elevation((wo + x.wi).normalize()) < 3e-4 {
                near_mirror += 1;
                continue;
            }
            checked += 1;
            let pdf = b.pdf(&s, wo, x.wi);
            assert!((pdf - x.pdf).abs() <= 1e-3 * pdf, "pdf {pdf} vs sample {}", x.pdf);
            let expect = b.eval(&s, wo, x.wi) * x.wi.z / x.pdf;
            let err = (expect - x.weight).abs().max_element();
            assert!(err <= 1e-3 * expect.max_element(), "weight {} vs {expect}", x.weight);
        }
        // the synthetic tables peak at the mirror direction: up to 2 % of samples fall there
        // at normal incidence
        assert!(
            checked > 2000 && near_mirror * 20 < checked,
            "{checked} checked, {near_mirror} near the mirror direction"
        );
    }

    #[test]
    fn files_are_checked() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/bsdf/testdata");
        let bytes = std::fs::read(dir.join("measured_iso_rgb.bsdf")).unwrap();
        assert!(MeasuredTables::from_bytes(&bytes[..bytes.len() - 4])
            .unwrap_err()
            .contains("past the end"));
        let spectral = bytes
            .windows(3)
            .position(|w| w == b"rgb")
            .map(|i| {
                // rename the field to one Mitsuba's spectral files have
                let mut b = bytes.clone();
                b[i..i + 3].copy_from_slice(b"xyz");
                b
            })
            .unwrap();
        assert!(MeasuredTables::from_bytes(&spectral).unwrap_err().contains("\"rgb\""));
        assert_eq!(
            material("measured_iso_rgb.bsdf").tables().description(),
            "steradian synthetic test material"
        );
    }
}
