//! Spectra given as `wavelength:value` lists, reduced to linear sRGB the way Mitsuba 3's
//! RGB variants do (`spectrum_list_to_srgb` in `src/core/spectrum.cpp`, called from
//! `create_texture_from_spectrum` in `src/core/xml.cpp`):
//!
//! * values are first multiplied by `MI_CIE_Y_NORMALIZATION` = 1/106.7502593994140625;
//! * the piecewise-linear spectrum is sampled at 1000 points evenly spaced over
//!   [360, 830] nm (both ends included); samples outside the given wavelength range
//!   contribute nothing; each sample is weighted by the CIE 1931 2° colour-matching
//!   functions (the 5 nm table, 95 entries, linearly interpolated) and, when `d65` is set,
//!   by the CIE D65 illuminant normalised by 1/98.99741751876255;
//! * the sum is multiplied by (830 − 360)/1000 and converted XYZ → linear sRGB;
//! * a *bounded* result is clamped to [0, 1], an unbounded one to [0, ∞).
//!
//! Which flags apply depends on where the spectrum is (see [`SpectrumRole`]).

use glam::Vec3;

const CIE_MIN: f64 = 360.0;
const CIE_MAX: f64 = 830.0;
const CIE_SAMPLES: usize = 95;
const CIE_Y_NORMALIZATION: f64 = 1.0 / 106.750_259_399_414_062_5;
const D65_NORMALIZATION: f64 = 1.0 / 98.997_417_518_762_55;

/// CIE 1931 2° colour-matching function x̄, 360–830 nm in 5 nm steps.
#[rustfmt::skip]
static CIE_X: [f32; CIE_SAMPLES] = [
    0.0001299, 0.0002321, 0.0004149, 0.0007416, 0.001368, 0.002236, 0.004243, 0.00765,
    0.01431, 0.02319, 0.04351, 0.07763, 0.13438, 0.21477, 0.2839, 0.3285,
    0.34828, 0.34806, 0.3362, 0.3187, 0.2908, 0.2511, 0.19536, 0.1421,
    0.09564, 0.05795001, 0.03201, 0.0147, 0.0049, 0.0024, 0.0093, 0.0291,
    0.06327, 0.1096, 0.1655, 0.2257499, 0.2904, 0.3597, 0.4334499, 0.5120501,
    0.5945, 0.6784, 0.7621, 0.8425, 0.9163, 0.9786, 1.0263, 1.0567,
    1.0622, 1.0456, 1.0026, 0.9384, 0.8544499, 0.7514, 0.6424, 0.5419,
    0.4479, 0.3608, 0.2835, 0.2187, 0.1649, 0.1212, 0.0874, 0.0636,
    0.04677, 0.0329, 0.0227, 0.01584, 0.01135916, 0.008110916, 0.005790346, 0.004109457,
    0.002899327, 0.00204919, 0.001439971, 0.0009999493, 0.0006900786, 0.0004760213, 0.0003323011, 0.0002348261,
    0.0001661505, 0.000117413, 0.00008307527, 0.00005870652, 0.00004150994, 0.00002935326, 0.00002067383, 0.00001455977,
    0.00001025398, 0.000007221456, 0.000005085868, 0.000003581652, 0.000002522525, 0.000001776509, 0.000001251141,
];

/// CIE 1931 2° colour-matching function ȳ, 360–830 nm in 5 nm steps.
#[rustfmt::skip]
static CIE_Y: [f32; CIE_SAMPLES] = [
    0.000003917, 0.000006965, 0.00001239, 0.00002202, 0.000039, 0.000064, 0.00012, 0.000217,
    0.000396, 0.00064, 0.00121, 0.00218, 0.004, 0.0073, 0.0116, 0.01684,
    0.023, 0.0298, 0.038, 0.048, 0.06, 0.0739, 0.09098, 0.1126,
    0.13902, 0.1693, 0.20802, 0.2586, 0.323, 0.4073, 0.503, 0.6082,
    0.71, 0.7932, 0.862, 0.9148501, 0.954, 0.9803, 0.9949501, 1.0,
    0.995, 0.9786, 0.952, 0.9154, 0.87, 0.8163, 0.757, 0.6949,
    0.631, 0.5668, 0.503, 0.4412, 0.381, 0.321, 0.265, 0.217,
    0.175, 0.1382, 0.107, 0.0816, 0.061, 0.04458, 0.032, 0.0232,
    0.017, 0.01192, 0.00821, 0.005723, 0.004102, 0.002929, 0.002091, 0.001484,
    0.001047, 0.00074, 0.00052, 0.0003611, 0.0002492, 0.0001719, 0.00012, 0.0000848,
    0.00006, 0.0000424, 0.00003, 0.0000212, 0.00001499, 0.0000106, 0.0000074657, 0.0000052578,
    0.0000037029, 0.0000026078, 0.0000018366, 0.0000012934, 0.00000091093, 0.00000064153, 0.00000045181,
];

/// CIE 1931 2° colour-matching function z̄, 360–830 nm in 5 nm steps.
#[rustfmt::skip]
static CIE_Z: [f32; CIE_SAMPLES] = [
    0.0006061, 0.001086, 0.001946, 0.003486, 0.006450001, 0.01054999, 0.02005001, 0.03621,
    0.06785001, 0.1102, 0.2074, 0.3713, 0.6456, 1.0390501, 1.3856, 1.62296,
    1.74706, 1.7826, 1.77211, 1.7441, 1.6692, 1.5281, 1.28764, 1.0419,
    0.8129501, 0.6162, 0.46518, 0.3533, 0.272, 0.2123, 0.1582, 0.1117,
    0.07824999, 0.05725001, 0.04216, 0.02984, 0.0203, 0.0134, 0.008749999, 0.005749999,
    0.0039, 0.002749999, 0.0021, 0.0018, 0.001650001, 0.0014, 0.0011, 0.001,
    0.0008, 0.0006, 0.00034, 0.00024, 0.00019, 0.0001, 0.00004999999, 0.00003,
    0.00002, 0.00001, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
];

/// CIE D65 relative spectral power (100 at 560 nm), 360–830 nm in 5 nm steps.
#[rustfmt::skip]
static D65: [f32; CIE_SAMPLES] = [
    46.6383, 49.3637, 52.0891, 51.0323, 49.9755, 52.3118, 54.6482,
    68.7015, 82.7549, 87.1204, 91.486, 92.4589, 93.4318, 90.057,
    86.6823, 95.7736, 104.865, 110.936, 117.008, 117.41, 117.812,
    116.336, 114.861, 115.392, 115.923, 112.367, 108.811, 109.082,
    109.354, 108.578, 107.802, 106.296, 104.79, 106.239, 107.689,
    106.047, 104.405, 104.225, 104.046, 102.023, 100.0, 98.1671,
    96.3342, 96.0611, 95.788, 92.2368, 88.6856, 89.3459, 90.0062,
    89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886, 83.4939,
    83.6992, 81.863, 80.0268, 80.1207, 80.2146, 81.2462, 82.2778,
    80.281, 78.2842, 74.0027, 69.7213, 70.6652, 71.6091, 72.979,
    74.349, 67.9765, 61.604, 65.7448, 69.8856, 72.4863, 75.087,
    69.3398, 63.5927, 55.0054, 46.4182, 56.6118, 66.8054, 65.0941,
    63.3828, 63.8434, 64.304, 61.8779, 59.4519, 55.7054, 51.959,
    54.6998, 57.4406, 58.8765, 60.3125,
];

/// Linear interpolation in a 5 nm table; 0 outside [360, 830] nm.
fn table_lookup(table: &[f32; CIE_SAMPLES], wavelength: f64) -> f64 {
    if !(CIE_MIN..=CIE_MAX).contains(&wavelength) {
        return 0.0;
    }
    let t = (wavelength - CIE_MIN) * ((CIE_SAMPLES - 1) as f64 / (CIE_MAX - CIE_MIN));
    let i0 = (t as usize).min(CIE_SAMPLES - 2);
    let w1 = t - i0 as f64;
    (1.0 - w1) * table[i0] as f64 + w1 * table[i0 + 1] as f64
}

/// Mitsuba's XYZ → linear sRGB (Rec. 709 primaries, D65 white) matrix.
pub fn xyz_to_srgb(xyz: [f64; 3]) -> [f64; 3] {
    let [x, y, z] = xyz;
    [
        3.240479 * x - 1.537150 * y - 0.498535 * z,
        -0.969256 * x + 1.875991 * y + 0.041556 * z,
        0.055648 * x - 0.204043 * y + 1.057311 * z,
    ]
}

/// Mitsuba's `spectrum_list_to_srgb(wavelengths, values, bounded, d65)`, including the
/// `MI_CIE_Y_NORMALIZATION` scaling that `xml.cpp` applies to the values beforehand.
/// `wavelengths` must be sorted, with at least two entries and the same length as `values`.
pub fn spectrum_list_to_srgb(
    wavelengths: &[f64],
    values: &[f64],
    bounded: bool,
    d65: bool,
) -> Vec3 {
    assert!(wavelengths.len() >= 2 && wavelengths.len() == values.len());
    let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    let steps = 1000;
    let mut xyz = [0.0f64; 3];
    for i in 0..steps {
        let w = CIE_MIN + (i as f64 / (steps - 1) as f64) * (CIE_MAX - CIE_MIN);
        if w < first || w > last {
            continue;
        }
        // Largest index with wavelengths[idx] <= w, clamped to [0, n-2].
        let idx =
            wavelengths.partition_point(|&x| x <= w).saturating_sub(1).min(wavelengths.len() - 2);
        let (w0, w1) = (wavelengths[idx], wavelengths[idx + 1]);
        let (v0, v1) = (values[idx] * CIE_Y_NORMALIZATION, values[idx + 1] * CIE_Y_NORMALIZATION);
        let v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        let weight = v * if d65 { table_lookup(&D65, w) * D65_NORMALIZATION } else { 1.0 };
        xyz[0] += table_lookup(&CIE_X, w) * weight;
        xyz[1] += table_lookup(&CIE_Y, w) * weight;
        xyz[2] += table_lookup(&CIE_Z, w) * weight;
    }
    let scale = (CIE_MAX - CIE_MIN) / steps as f64;
    let rgb = xyz_to_srgb([xyz[0] * scale, xyz[1] * scale, xyz[2] * scale]);
    let clamp = |c: f64| if bounded { c.clamp(0.0, 1.0) } else { c.max(0.0) };
    Vec3::new(clamp(rgb[0]) as f32, clamp(rgb[1]) as f32, clamp(rgb[2]) as f32)
}

/// What a spectrum property describes; decides the flags Mitsuba passes (RGB variants).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpectrumRole {
    /// A reflectance-like quantity: bounded to [0, 1], integrated against D65.
    Reflectance,
    /// A property of an `<emitter>` (not an IOR): unbounded, integrated without D65, so a
    /// flat spectrum comes out as the sRGB value of the equal-energy white.
    Emission,
    /// `eta`, `k`, `int_ior` or `ext_ior`: unbounded, integrated against D65.
    Unbounded,
}

impl SpectrumRole {
    /// The role of property `name` of an object; `within_emitter` is true for direct
    /// properties of an `<emitter>` (Mitsuba's `within_emitter`). `sunsky`'s ground `albedo`
    /// is a reflectance although it sits in an emitter: Mitsuba 3.9.1 reads it as one
    /// (400:0.1, 700:0.6 gives (0.501608, 0.338203, 0.167512) there, as for a `diffuse`
    /// reflectance).
    pub fn of(name: &str, within_emitter: bool) -> Self {
        let unbounded = matches!(name, "eta" | "k" | "int_ior" | "ext_ior");
        if unbounded {
            SpectrumRole::Unbounded
        } else if within_emitter && name != "albedo" {
            SpectrumRole::Emission
        } else {
            SpectrumRole::Reflectance
        }
    }
}

/// RGB of a `wavelength:value` list in the given role.
pub fn wavelength_list_to_rgb(wavelengths: &[f64], values: &[f64], role: SpectrumRole) -> Vec3 {
    match role {
        SpectrumRole::Reflectance => spectrum_list_to_srgb(wavelengths, values, true, true),
        SpectrumRole::Emission => spectrum_list_to_srgb(wavelengths, values, false, false),
        SpectrumRole::Unbounded => spectrum_list_to_srgb(wavelengths, values, false, true),
    }
}

/// RGB of `<spectrum value="v"/>` (one number) inside an emitter: Mitsuba turns the flat
/// spectrum into `v · xyz_to_srgb(1, 1, 1)` so RGB and spectral renders agree. `None` means
/// the value stays a plain uniform spectrum (every other role).
pub fn uniform_to_rgb(value: f64, role: SpectrumRole) -> Option<Vec3> {
    match role {
        SpectrumRole::Emission => {
            let c = xyz_to_srgb([1.0, 1.0, 1.0]);
            Some(Vec3::new((value * c[0]) as f32, (value * c[1]) as f32, (value * c[2]) as f32))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
        (a - b).abs().max_element() < tol
    }

    #[test]
    fn flat_reflectance_is_white() {
        // A flat spectrum of 1 integrated against D65 is the D65 white point: (1, 1, 1) in
        // sRGB up to Mitsuba's own discretisation (bounded → clamped at 1).
        let c = wavelength_list_to_rgb(&[360.0, 830.0], &[1.0, 1.0], SpectrumRole::Unbounded);
        assert!(close(c, Vec3::ONE, 2e-3), "{c}");
        let c = wavelength_list_to_rgb(&[360.0, 830.0], &[0.5, 0.5], SpectrumRole::Reflectance);
        assert!(close(c, Vec3::splat(0.5), 1e-3), "{c}");
    }

    #[test]
    fn flat_emission_is_equal_energy_white() {
        let c = wavelength_list_to_rgb(&[360.0, 830.0], &[1.0, 1.0], SpectrumRole::Emission);
        assert!(close(c, Vec3::new(1.204794, 0.948292, 0.908916), 3e-3), "{c}");
        let u = uniform_to_rgb(2.0, SpectrumRole::Emission).unwrap();
        assert!(close(u, Vec3::new(2.409588, 1.896584, 1.817832), 1e-5), "{u}");
        assert_eq!(uniform_to_rgb(2.0, SpectrumRole::Reflectance), None);
    }

    #[test]
    fn narrow_band_is_coloured_and_clamped() {
        // A red band: R dominates, and a bounded spectrum never leaves [0, 1].
        let c = wavelength_list_to_rgb(
            &[600.0, 610.0, 690.0, 700.0],
            &[0.0, 1.0, 1.0, 0.0],
            SpectrumRole::Reflectance,
        );
        assert!(c.x > c.y && c.x > c.z, "{c}");
        assert!(c.max_element() <= 1.0 && c.min_element() >= 0.0);
        // Outside the given range the spectrum contributes nothing.
        let c = wavelength_list_to_rgb(&[200.0, 300.0], &[1.0, 1.0], SpectrumRole::Unbounded);
        assert_eq!(c, Vec3::ZERO);
    }

    /// `sunsky`'s `albedo` in an emitter converts as a reflectance, to Mitsuba 3.9.1's values.
    #[test]
    fn an_emitters_albedo_is_a_reflectance() {
        let role = SpectrumRole::of("albedo", true);
        assert_eq!(role, SpectrumRole::Reflectance);
        let c = wavelength_list_to_rgb(&[400.0, 700.0], &[0.1, 0.6], role);
        let mitsuba = Vec3::new(0.501_608, 0.338_203, 0.167_512);
        assert!((c - mitsuba).abs().max_element() < 2e-5, "{c}");
    }
}
