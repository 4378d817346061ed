//! `merl`: a measured isotropic BRDF in the MERL binary format (Matusik et al. 2003, "A
//! data-driven reflectance model"); steradian's own plugin (Mitsuba 3 has none).
//!
//! | parameter  | type   | default | meaning |
//! |------------|--------|---------|---------|
//! | `filename` | string | —       | the `.binary` file, raw or gzip-compressed (`.binary.gz`), relative to the scene file |
//!
//! **File format.** Three little-endian i32 dimensions, which must be (90, 90, 180), then
//! 3·90·90·180 little-endian f64 in channel-major order (all red values, then green, then
//! blue; 35 MB). Value `k` of a channel is ρ/scale at θ_h index `k / (90·180)`, θ_d index
//! `(k / 180) mod 90` and φ_d index `k mod 180`, with scales 1/1500 (R), 1.15/1500 (G),
//! 1.66/1500 (B), so that ρ (1/sr) = value·scale. The half/difference angles are those of
//! Rusinkiewicz (1998): h = (wi + wo)/|wi + wo|, θ_h its polar angle, and the difference
//! vector d is wi rotated by −φ_h about the normal and by −θ_h about the binormal; θ_d, φ_d
//! its angles. Sample i of θ_h lies at θ_h = (i/90)²·90° (the square-root spacing that
//! concentrates samples near the specular peak), sample j of θ_d at j degrees, sample k of
//! φ_d at k degrees; φ_d is folded into [0°, 180°) by reciprocity (φ_d and φ_d + 180° swap
//! wi and wo). A negative value marks a configuration that was not measured (below the
//! horizon). A file starting with the gzip magic bytes is decompressed first.
//!
//! **Evaluation.** The reference reader (MERL's `BRDFRead.cpp`) truncates the continuous
//! indices x_h = 90·√(θ_h/90°), x_d = θ_d/1°, x_φ = φ_d/1° to the sample below. steradian
//! interpolates **trilinearly in this index space** between the 8 surrounding samples
//! (samples at x = 0, 1, …; the same lookup as the reference reader at the samples
//! themselves): x_φ wraps around (sample 179 neighbours sample 0), x_h and x_d beyond the
//! last sample (89) use it. Samples marked missing are left out and the weights of the
//! others renormalised; with all 8 missing, ρ = 0. The result is exactly reciprocal and
//! continuous, and reproduces a constant (Lambertian) table exactly. One-sided:
//! ρ = 0 unless wo and wi lie above the surface. Measured data is used as it is (a
//! measurement may reflect more than it receives at grazing angles).
//!
//! **Sampling** is tabulated from the data. The outgoing polar angle θ_o is split into 32
//! equal bins; for the centre of each, the BRDF is tabulated over wi (relative to wo's
//! azimuth) on a 64 × 64 grid of the square that maps to the cosine-weighted hemisphere by
//! u = sin²θ_i, v = (φ_i − φ_o)/2π (an area-preserving polar map of the unit disk), each cell
//! holding the largest of 3 × 3 values of the mean channel in it. wi is drawn from that
//! piecewise-constant 2-D distribution (defensively mixed with 10 % uniform, i.e. cosine
//! sampling, so that no reflecting direction has zero density), giving the exact density
//! pdf(wi) = p_grid(u, v)·cos θ_i/π for the bin wo falls in. The weight is ρ·cos θ_i/pdf.
//! Memory: the table as f32 RGB (17.5 MB) plus 1 MB of sampling tables.

use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, PI, TAU};
use std::fmt;
use std::io::Read;
use std::path::Path;
use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3};
use rayon::prelude::*;

use super::{cos_theta, BsdfSample, ShadingPoint};
use crate::sampling::piecewise_constant::PiecewiseConstant2D;
use crate::Spectrum;

/// Samples of θ_h, θ_d and φ_d in the MERL format.
pub const RES_THETA_H: usize = 90;
pub const RES_THETA_D: usize = 90;
pub const RES_PHI_D: usize = 180;
/// Entries per channel.
const ENTRIES: usize = RES_THETA_H * RES_THETA_D * RES_PHI_D;
/// ρ (1/sr) = stored value × scale, per channel (R, G, B).
pub const SCALE: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// Bins of θ_o, and the u × v grid over wi per bin, of the sampling tables.
const SAMPLE_THETA_O: usize = 32;
const SAMPLE_NU: usize = 64;
const SAMPLE_NV: usize = 64;
/// Sub-samples per cell side when tabulating for sampling.
const SAMPLE_SUB: usize = 3;
/// Fraction of cosine-weighted (uniform on the grid) sampling mixed in.
const DEFENSIVE: f32 = 0.1;

/// A MERL table: ρ (1/sr, RGB) at the 90 × 90 × 180 (θ_h, θ_d, φ_d) samples.
#[derive(Clone, PartialEq)]
pub struct MerlTable {
    /// ρ at sample ((i_h·90 + i_d)·180 + i_φ); a negative red value marks a missing sample.
    data: Vec<[f32; 3]>,
}

impl fmt::Debug for MerlTable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let missing = self.data.iter().filter(|v| v[0] < 0.0).count();
        write!(
            f,
            "MerlTable {{ {RES_THETA_H}×{RES_THETA_D}×{RES_PHI_D} samples, {missing} missing }}"
        )
    }
}

#[inline]
fn index(ih: usize, id: usize, ip: usize) -> usize {
    (ih * RES_THETA_D + id) * RES_PHI_D + ip
}

/// The (θ_h, θ_d, φ_d) of wo, wi (radians; φ_d folded into [0, π)).
#[inline]
fn half_diff(wo: Vec3, wi: Vec3) -> (f32, f32, f32) {
    let h = (wo + wi).normalize();
    let theta_h = (h.x * h.x + h.y * h.y).sqrt().atan2(h.z);
    let phi_h = h.y.atan2(h.x);
    // d = R_y(−θ_h) R_z(−φ_h) wi
    let (sp, cp) = phi_h.sin_cos();
    let (x, y, z) = (wi.x * cp + wi.y * sp, -wi.x * sp + wi.y * cp, wi.z);
    let (st, ct) = theta_h.sin_cos();
    let (dx, dy, dz) = (x * ct - z * st, y, x * st + z * ct);
    let theta_d = (dx * dx + dy * dy).sqrt().atan2(dz);
    let mut phi_d = dy.atan2(dx);
    if phi_d < 0.0 {
        phi_d += PI;
    }
    (theta_h, theta_d, phi_d)
}

/// wo and wi (f64) for given half/difference angles with φ_h = 0: the inverse of
/// [`half_diff`].
fn from_half_diff(theta_h: f64, theta_d: f64, phi_d: f64) -> (DVec3, DVec3) {
    let d = DVec3::new(theta_d.sin() * phi_d.cos(), theta_d.sin() * phi_d.sin(), theta_d.cos());
    let (st, ct) = theta_h.sin_cos();
    let wi = DVec3::new(d.x * ct + d.z * st, d.y, -d.x * st + d.z * ct);
    let h = DVec3::new(st, 0.0, ct);
    let wo = 2.0 * wi.dot(h) * h - wi;
    (wo, wi)
}

/// Continuous index x of a sample coordinate, split into the lower sample, the upper one
/// and the weight of the upper one; clamped at the last sample.
#[inline]
fn split_clamped(x: f32, n: usize) -> (usize, usize, f32) {
    let last = (n - 1) as f32;
    let x = x.clamp(0.0, last);
    let i0 = (x as usize).min(n - 1);
    let i1 = (i0 + 1).min(n - 1);
    (i0, i1, x - i0 as f32)
}

impl MerlTable {
    /// Reads a MERL file (raw or gzip-compressed).
    pub fn read(path: &Path) -> Result<Self, String> {
        let bytes = std::fs::read(path)
            .map_err(|e| format!("cannot read MERL file {}: {e}", path.display()))?;
        Self::from_bytes(&bytes).map_err(|e| format!("MERL file {}: {e}", path.display()))
    }

    /// Parses the bytes of a MERL file (raw or gzip-compressed).
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        let expected = 12 + 3 * ENTRIES * 8;
        let inflated;
        let bytes = if bytes.starts_with(&[0x1f, 0x8b]) {
            let mut out = Vec::with_capacity(expected);
            // read one byte more than a valid file has, to detect trailing data cheaply
            flate2::read::GzDecoder::new(bytes)
                .take(expected as u64 + 1)
                .read_to_end(&mut out)
                .map_err(|e| format!("gzip data is corrupt: {e}"))?;
            inflated = out;
            &inflated[..]
        } else {
            bytes
        };
        if bytes.len() < 12 {
            return Err(format!(
                "truncated: {} bytes, too short for the 12-byte header",
                bytes.len()
            ));
        }
        let dim = |i: usize| i32::from_le_bytes(bytes[4 * i..4 * i + 4].try_into().unwrap());
        let dims = [dim(0), dim(1), dim(2)];
        if dims != [RES_THETA_H as i32, RES_THETA_D as i32, RES_PHI_D as i32] {
            return Err(format!(
                "wrong dimensions {}×{}×{} in the header: the MERL format has {RES_THETA_H}×{RES_THETA_D}×{RES_PHI_D} (θ_h × θ_d × φ_d)",
                dims[0], dims[1], dims[2]
            ));
        }
        if bytes.len() < expected {
            return Err(format!("truncated: {} bytes, a {RES_THETA_H}×{RES_THETA_D}×{RES_PHI_D} MERL file has {expected}", bytes.len()));
        }
        if bytes.len() > expected {
            return Err(format!(
                "{} bytes of trailing data after the table (a MERL file has {expected} bytes)",
                bytes.len() - expected
            ));
        }
        let value = |c: usize, k: usize| {
            let o = 12 + (c * ENTRIES + k) * 8;
            f64::from_le_bytes(bytes[o..o + 8].try_into().unwrap())
        };
        let mut data = Vec::with_capacity(ENTRIES);
        for k in 0..ENTRIES {
            let v = [value(0, k), value(1, k), value(2, k)];
            if let Some(c) = (0..3).find(|&c| !v[c].is_finite()) {
                return Err(format!(
                    "value {} of channel {c} (entry {k}) is not a finite number",
                    v[c]
                ));
            }
            data.push(if v.iter().any(|&x| x < 0.0) {
                [-1.0; 3]
            } else {
                [0, 1, 2].map(|c| (v[c] * SCALE[c]) as f32)
            });
        }
        Ok(MerlTable { data })
    }

    /// Tabulates `f(wo, wi)` (ρ in 1/sr) at the format's samples; samples with wo or wi
    /// below the horizon are marked missing, as in measured files.
    pub fn tabulate(f: impl Fn(Vec3, Vec3) -> Spectrum + Sync) -> Self {
        let data = (0..ENTRIES)
            .into_par_iter()
            .map(|k| {
                let (ih, id, ip) =
                    (k / (RES_THETA_D * RES_PHI_D), (k / RES_PHI_D) % RES_THETA_D, k % RES_PHI_D);
                let theta_h =
                    (ih as f64 / RES_THETA_H as f64).powi(2) * std::f64::consts::FRAC_PI_2;
                let theta_d = (id as f64).to_radians();
                let phi_d = (ip as f64).to_radians();
                let (wo, wi) = from_half_diff(theta_h, theta_d, phi_d);
                if wo.z <= 0.0 || wi.z <= 0.0 {
                    return [-1.0; 3];
                }
                let v = f(wo.as_vec3().normalize(), wi.as_vec3().normalize());
                [v.x.max(0.0), v.y.max(0.0), v.z.max(0.0)]
            })
            .collect();
        MerlTable { data }
    }

    /// The file's bytes (uncompressed). Stored values are rounded to multiples of `quantum`
    /// (in the file's units, ρ/scale) when it is positive: coarse steps compress well.
    pub fn to_bytes(&self, quantum: f64) -> Vec<u8> {
        let mut out = Vec::with_capacity(12 + 3 * ENTRIES * 8);
        for d in [RES_THETA_H, RES_THETA_D, RES_PHI_D] {
            out.extend_from_slice(&(d as i32).to_le_bytes());
        }
        for (c, scale) in SCALE.iter().enumerate() {
            for v in &self.data {
                let x = if v[0] < 0.0 {
                    -1.0
                } else {
                    let x = v[c] as f64 / scale;
                    if quantum > 0.0 {
                        (x / quantum).round() * quantum
                    } else {
                        x
                    }
                };
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out
    }

    /// The 8 samples around (wo, wi) and their trilinear weights (see the module docs).
    #[inline]
    fn stencil(wo: Vec3, wi: Vec3) -> [(usize, f32); 8] {
        let (theta_h, theta_d, phi_d) = half_diff(wo, wi);
        let xh = (theta_h.max(0.0) / FRAC_PI_2).sqrt() * RES_THETA_H as f32;
        let xd = theta_d / FRAC_PI_2 * RES_THETA_D as f32;
        let (h0, h1, th) = split_clamped(xh, RES_THETA_H);
        let (d0, d1, td) = split_clamped(xd, RES_THETA_D);
        let xp = phi_d.to_degrees().max(0.0);
        let p0f = xp.floor();
        let tp = xp - p0f;
        let p0 = (p0f as usize) % RES_PHI_D;
        let p1 = (p0 + 1) % RES_PHI_D;
        let mut out = [(0, 0.0); 8];
        let mut k = 0;
        for (ih, wh) in [(h0, 1.0 - th), (h1, th)] {
            for (id, wd) in [(d0, 1.0 - td), (d1, td)] {
                for (ip, wp) in [(p0, 1.0 - tp), (p1, tp)] {
                    out[k] = (index(ih, id, ip), wh * wd * wp);
                    k += 1;
                }
            }
        }
        out
    }

    /// ρ(wo, wi) in 1/sr by trilinear interpolation in index space (see the module docs);
    /// both directions must lie above the surface.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Spectrum {
        let (mut acc, mut wsum) = (Spectrum::ZERO, 0.0);
        for (i, w) in Self::stencil(wo, wi) {
            let v = self.data[i];
            if w > 0.0 && v[0] >= 0.0 {
                acc += w * Spectrum::from_array(v);
                wsum += w;
            }
        }
        if wsum > 0.0 {
            acc / wsum
        } else {
            Spectrum::ZERO
        }
    }
}

/// The tabulated sampling distributions over wi, one per θ_o bin.
#[derive(Clone, PartialEq)]
struct MerlSampling {
    bins: Vec<PiecewiseConstant2D>,
}

/// wi from the sampling square (u = sin²θ_i, v = φ_i/2π), in the frame where wo's azimuth is 0.
#[inline]
fn square_to_direction(u: f32, v: f32) -> Vec3 {
    let r = u.max(0.0).sqrt();
    let (s, c) = (TAU * v).sin_cos();
    Vec3::new(r * c, r * s, (1.0 - u).max(0.0).sqrt())
}

#[inline]
fn direction_to_square(w: Vec3) -> (f32, f32) {
    let u = (w.x * w.x + w.y * w.y).min(1.0);
    let mut v = w.y.atan2(w.x) / TAU;
    if v < 0.0 {
        v += 1.0;
    }
    (u, v.min(1.0))
}

/// The bin of θ_o and the rotation (cos, sin of φ_o) taking wo's azimuth to 0.
#[inline]
fn wo_bin(wo: Vec3) -> (usize, f32, f32) {
    let theta_o = (wo.x * wo.x + wo.y * wo.y).sqrt().atan2(wo.z);
    let bin = ((theta_o / FRAC_PI_2 * SAMPLE_THETA_O as f32) as usize).min(SAMPLE_THETA_O - 1);
    let (s, c) = wo.y.atan2(wo.x).sin_cos();
    (bin, c, s)
}

impl MerlSampling {
    fn new(table: &MerlTable) -> Self {
        let bins = (0..SAMPLE_THETA_O)
            .into_par_iter()
            .map(|b| {
                let theta_o = (b as f32 + 0.5) / SAMPLE_THETA_O as f32 * FRAC_PI_2;
                let wo = Vec3::new(theta_o.sin(), 0.0, theta_o.cos());
                let mut f = vec![0f32; SAMPLE_NU * SAMPLE_NV];
                for iu in 0..SAMPLE_NU {
                    for iv in 0..SAMPLE_NV {
                        let mut m = 0f32;
                        for a in 0..SAMPLE_SUB {
                            for c in 0..SAMPLE_SUB {
                                let u = (iu as f32 + (a as f32 + 0.5) / SAMPLE_SUB as f32)
                                    / SAMPLE_NU as f32;
                                let v = (iv as f32 + (c as f32 + 0.5) / SAMPLE_SUB as f32)
                                    / SAMPLE_NV as f32;
                                let wi = square_to_direction(u, v);
                                m = m.max(table.eval(wo, wi).element_sum() / 3.0);
                            }
                        }
                        f[iu * SAMPLE_NV + iv] = if m.is_finite() { m } else { 0.0 };
                    }
                }
                let mean = f.iter().map(|&x| x as f64).sum::<f64>() as f32 / f.len() as f32;
                for x in &mut f {
                    *x = if mean > 0.0 { (1.0 - DEFENSIVE) * *x / mean + DEFENSIVE } else { 1.0 };
                }
                PiecewiseConstant2D::new(&f, SAMPLE_NU, SAMPLE_NV)
            })
            .collect();
        MerlSampling { bins }
    }
}

/// The `merl` BSDF: a shared table and its sampling distributions.
#[derive(Clone)]
pub struct Merl {
    table: Arc<MerlTable>,
    sampling: Arc<MerlSampling>,
}

impl fmt::Debug for Merl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Merl({:?})", self.table)
    }
}

impl PartialEq for Merl {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.table, &other.table) || self.table == other.table
    }
}

impl Merl {
    /// The BSDF of a table; builds the sampling distributions (≈ 1.2 M table lookups).
    pub fn new(table: MerlTable) -> Self {
        let sampling = Arc::new(MerlSampling::new(&table));
        Merl { table: Arc::new(table), sampling }
    }

    pub fn table(&self) -> &MerlTable {
        &self.table
    }

    #[inline]
    pub fn eval(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return Spectrum::ZERO;
        }
        self.table.eval(wo, wi)
    }

    #[inline]
    pub fn pdf(&self, _sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        if cos_theta(wo) <= 0.0 || cos_theta(wi) <= 0.0 {
            return 0.0;
        }
        let (bin, c, s) = wo_bin(wo);
        let local = Vec3::new(c * wi.x + s * wi.y, -s * wi.x + c * wi.y, wi.z);
        let (u, v) = direction_to_square(local);
        self.sampling.bins[bin].pdf([u, v]) * cos_theta(wi) * FRAC_1_PI
    }

    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if cos_theta(wo) <= 0.0 {
            return None;
        }
        let (bin, c, s) = wo_bin(wo);
        let ([u, v], _) = self.sampling.bins[bin].sample([u2.x, u2.y]);
        let local = square_to_direction(u, v);
        let wi = Vec3::new(c * local.x - s * local.y, s * local.x + c * local.y, local.z);
        // the density of the cell wi lands in, recomputed as `pdf` does so the two agree
        super::smooth_sample(wi, self.pdf(sp, wo, wi), || self.eval(sp, wo, wi))
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Bsdf, Phong};
    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::bsdf::*;

    fn phong() -> Bsdf {
        Bsdf::Phong(
            Phong::new(
                Spectrum::new(0.3, 0.4, 0.1).into(),
                Spectrum::new(0.5, 0.3, 0.6).into(),
                20.0,
            )
            .unwrap(),
        )
    }

    fn tabulated(b: &Bsdf) -> MerlTable {
        MerlTable::tabulate(|wo, wi| b.eval(&sp(), wo, wi))
    }

    /// A tabulated Phong BRDF, through the file format (write, read back).
    fn merl_phong() -> (Bsdf, Bsdf) {
        let analytic = phong();
        let table = MerlTable::from_bytes(&tabulated(&analytic).to_bytes(0.0)).unwrap();
        (analytic, Bsdf::Merl(Merl::new(table)))
    }

    #[test]
    fn half_diff_round_trip() {
        let mut rng = Pcg32::new(7, 1);
        for _ in 0..1000 {
            let (th, td, pd) = (rng.next_f64() * 1.5, rng.next_f64() * 1.5, rng.next_f64() * 3.1);
            let (wo, wi) = from_half_diff(th, td, pd);
            let (a, b, c) = half_diff(wo.as_vec3(), wi.as_vec3());
            assert!(
                (a as f64 - th).abs() < 1e-4
                    && (b as f64 - td).abs() < 1e-4
                    && (c as f64 - pd).abs() < 1e-4,
                "{th} {td} {pd} → {a} {b} {c}"
            );
        }
    }

    #[test]
    fn lambertian_table_is_exact_and_phong_within_interpolation_error() {
        let lambert =
            Bsdf::Diffuse(super::super::Diffuse::new(Spectrum::new(0.8, 0.5, 0.2).into()));
        let lt = MerlTable::from_bytes(&tabulated(&lambert).to_bytes(0.0)).unwrap();
        let (analytic, merl) = merl_phong();
        let Bsdf::Merl(m) = &merl else { unreachable!() };
        let s = sp();
        let mut rng = Pcg32::new(11, 3);
        let (mut worst, mut sum, mut count, mut near_horizon) = (0f32, 0f64, 0, 0);
        for _ in 0..20_000 {
            let wo = warp_uniform(&mut rng);
            let wi = warp_uniform(&mut rng);
            let expect = lambert.eval(&s, wo, wi);
            let got = lt.eval(wo, wi);
            assert!(
                (got - expect).abs().max_element() <= 1e-6 * expect.max_element(),
                "{got} vs {expect}"
            );
            // Phong: trilinear weights form a convex combination, so the interpolated value
            // lies within the range of the (valid) samples around the point; a smooth BRDF
            // lies within that range too up to second order. The first-order bound: the
            // error is at most the spread of those samples.
            let (a, b) = (analytic.eval(&s, wo, wi), m.eval(&s, wo, wi));
            let corners: Vec<Spectrum> = MerlTable::stencil(wo, wi)
                .iter()
                .map(|&(i, _)| m.table().data[i])
                .filter(|v| v[0] >= 0.0)
                .map(Spectrum::from_array)
                .collect();
            let lo = corners.iter().fold(Spectrum::INFINITY, |x, &y| x.min(y));
            let hi = corners.iter().fold(Spectrum::NEG_INFINITY, |x, &y| x.max(y));
            let spread = hi - lo;
            if corners.len() < 8 {
                // next to the horizon the missing samples are left out: constant
                // extrapolation from the valid ones, no bound from the spread
                near_horizon += 1;
                continue;
            }
            assert!(
                ((a - b).abs() - spread).max_element() <= 1e-6 * a.max_element(),
                "wo {wo} wi {wi}: merl {b} vs analytic {a}, sample spread {spread}"
            );
            let rel = ((a - b).abs() / a).max_element();
            worst = worst.max(rel);
            sum += rel as f64;
            count += 1;
        }
        let mean = sum / count as f64;
        eprintln!("tabulated Phong n=20: mean relative error {mean:.2e}, worst {worst:.2e} ({count} points; {near_horizon} next to the horizon skipped)");
        assert!(near_horizon < count / 10);
        // on average, the second-order interpolation error is far below the sample spread
        assert!(mean < 5e-3, "mean relative error {mean}, worst {worst}");
    }

    fn warp_uniform(rng: &mut Pcg32) -> Vec3 {
        crate::sampling::warp::square_to_uniform_hemisphere(Vec2::new(
            rng.next_f32(),
            rng.next_f32(),
        ))
    }

    #[test]
    fn sampling_matches_pdf_chi2() {
        let lambert =
            Bsdf::Diffuse(super::super::Diffuse::new(Spectrum::new(0.8, 0.5, 0.2).into()));
        let d = super::super::MicrofacetDistribution::new(
            super::super::MicrofacetKind::Ggx,
            0.1,
            0.1,
            true,
        );
        let plastic = Bsdf::RoughPlastic(super::super::RoughPlastic::new(
            d,
            1.5,
            Spectrum::splat(0.3).into(),
            Spectrum::ONE.into(),
            super::super::InternalScattering::Linear,
        ));
        let tables = [(lambert, 8), (phong(), 24), (plastic, 48)];
        let angles = [0.0, 30.0, 60.0, 85.0];
        let tests = (tables.len() * angles.len()) as f64;
        let mut min_p = 1f64;
        for (i, (analytic, sub)) in tables.iter().enumerate() {
            let merl = Bsdf::Merl(Merl::new(tabulated(analytic)));
            for (j, theta) in angles.into_iter().enumerate() {
                let p =
                    chi2_pvalue_sub(&merl, dir(theta, 35.0), 200_000, (10 * i + j) as u64, *sub);
                min_p = min_p.min(p);
                assert!(p > 0.01 / tests, "table {i} θ={theta}: p-value {p}");
            }
        }
        eprintln!("smallest χ² p-value over {tests} tests: {min_p:.4}");
    }

    #[test]
    fn consistency_reciprocity_furnace() {
        let (analytic, merl) = merl_phong();
        let s = sp();
        for theta in [0.0, 40.0, 80.0] {
            check_sample_consistency(&merl, dir(theta, 20.0), 3);
        }
        for (a, c) in [
            (dir(20.0, 10.0), dir(25.0, 185.0)),
            (dir(70.0, 0.0), dir(65.0, 170.0)),
            (dir(5.0, 0.0), dir(80.0, 30.0)),
        ] {
            let (x, y) = (merl.eval(&s, a, c), merl.eval(&s, c, a));
            assert!((x - y).abs().max_element() <= 1e-4 * x.max_element(), "{x:?} vs {y:?}");
            assert_eq!(merl.eval(&s, -a, c), Spectrum::ZERO);
            assert_eq!(merl.pdf(&s, a, -c), 0.0);
        }
        // white furnace: the tabulated Phong's albedo matches the analytic one (≤ 1), within
        // the sampling error and the interpolation error found above (< 1 % on average)
        for theta in [0.0, 45.0, 80.0, 89.0] {
            let (m, se) = albedo(&merl, dir(theta, 10.0), 100_000, 4);
            let (ma, sea) = albedo(&analytic, dir(theta, 10.0), 100_000, 5);
            for c in 0..3 {
                assert!(m[c] <= 1.0 + 5.0 * se[c], "θ={theta}: albedo {m:?}");
                let tol = 5.0 * (se[c] * se[c] + sea[c] * sea[c]).sqrt() + 0.01 * ma[c];
                assert!(
                    (m[c] - ma[c]).abs() <= tol,
                    "θ={theta} channel {c}: merl {} ± {} vs analytic {} ± {}",
                    m[c],
                    se[c],
                    ma[c],
                    sea[c]
                );
            }
        }
    }

    #[test]
    fn missing_samples_are_skipped() {
        // a table missing its whole upper half of θ_d: lookups there use the lower samples
        let lambert = Bsdf::Diffuse(super::super::Diffuse::new(Spectrum::splat(0.6).into()));
        let mut t = tabulated(&lambert);
        for ih in 0..RES_THETA_H {
            for id in 45..RES_THETA_D {
                for ip in 0..RES_PHI_D {
                    t.data[index(ih, id, ip)] = [-1.0; 3];
                }
            }
        }
        let t = MerlTable::from_bytes(&t.to_bytes(0.0)).unwrap();
        let (wo, wi) = from_half_diff(0.3, 44.5f64.to_radians(), 0.5);
        let v = t.eval(wo.as_vec3(), wi.as_vec3());
        assert!((v.x - 0.6 / PI).abs() < 1e-6, "{v}");
        let (wo, wi) = from_half_diff(0.3, 60f64.to_radians(), 0.5);
        assert_eq!(t.eval(wo.as_vec3(), wi.as_vec3()), Spectrum::ZERO);
    }

    #[test]
    fn format_errors() {
        let good = tabulated(&phong()).to_bytes(0.0);
        let e = MerlTable::from_bytes(&good[..good.len() - 8]).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        let e = MerlTable::from_bytes(&good[..6]).unwrap_err();
        assert!(e.contains("truncated") && e.contains("header"), "{e}");
        let mut bad = good.clone();
        bad[8..12].copy_from_slice(&360i32.to_le_bytes());
        let e = MerlTable::from_bytes(&bad).unwrap_err();
        assert!(e.contains("90×90×360") && e.contains("90×90×180"), "{e}");
        let mut bad = good.clone();
        bad.extend_from_slice(&[0; 8]);
        assert!(MerlTable::from_bytes(&bad).unwrap_err().contains("trailing"));
        let mut bad = good;
        bad[12 + 8 * 1000..12 + 8 * 1001].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(MerlTable::from_bytes(&bad).unwrap_err().contains("not a finite"));
        let e = MerlTable::from_bytes(&[0x1f, 0x8b, 0, 0, 1]).unwrap_err();
        assert!(e.contains("gzip"), "{e}");
    }

    #[test]
    fn gzip_files_read_like_raw_ones() {
        use std::io::Write;
        let t = tabulated(&phong());
        let raw = t.to_bytes(0.25);
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        gz.write_all(&raw).unwrap();
        let gz = gz.finish().unwrap();
        assert_eq!(MerlTable::from_bytes(&gz).unwrap(), MerlTable::from_bytes(&raw).unwrap());
    }
}
