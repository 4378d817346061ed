//! Colour as linear RGB.
//!
//! steradian renders in RGB like Mitsuba 3's `*_rgb` variants: each channel carries the same
//! radiometric quantity (a radiance, an irradiance, a reflectance...) for its primary. Values
//! are linear (no gamma) and unclamped.

/// A linear RGB triple. The unit is that of the quantity it stands for.
///
/// Stored as glam's 16-byte aligned `Vec3A`, so that each operation on the three channels is
/// one SSE instruction (the throughput products of the path tracer, BSDF values, MIS-weighted
/// contributions): 2–3 % less render time than `Vec3` on cornell, materials and veach,
/// bit-identical images (2026-12-02, AMD EPYC, 2 cores).
pub type Spectrum = glam::Vec3A;

/// Luminance weights of linear sRGB / Rec. 709 primaries (the Y row of RGB → XYZ).
pub const LUMINANCE_WEIGHTS: Spectrum = Spectrum::new(0.212671, 0.715160, 0.072169);

/// Linear sRGB (Rec. 709 primaries, D65) to CIE XYZ, Mitsuba 3's `srgb_to_xyz`; its middle
/// row is [`LUMINANCE_WEIGHTS`].
pub const RGB_TO_XYZ: [[f64; 3]; 3] = [
    [0.412453, 0.357580, 0.180423],
    [0.212671, 0.715160, 0.072169],
    [0.019334, 0.119193, 0.950227],
];

/// CIE XYZ of a linear sRGB value (same unit).
#[inline]
pub fn srgb_to_xyz(s: Spectrum) -> Spectrum {
    let row = |r: [f64; 3]| r[0] as f32 * s.x + r[1] as f32 * s.y + r[2] as f32 * s.z;
    Spectrum::new(row(RGB_TO_XYZ[0]), row(RGB_TO_XYZ[1]), row(RGB_TO_XYZ[2]))
}

/// Photopic luminance Y of a linear RGB value (same unit as the value).
#[inline]
pub fn luminance(s: Spectrum) -> f32 {
    s.dot(LUMINANCE_WEIGHTS)
}

/// [`luminance`] of an RGB pixel of an image's data (three values), in f64: for a standard
/// error per channel it is the bound Σ w_c σ_c, exact when the channels' errors are perfectly
/// correlated.
#[inline]
pub fn luminance_f64(rgb: &[f32]) -> f64 {
    (0..3).map(|c| LUMINANCE_WEIGHTS[c] as f64 * rgb[c] as f64).sum()
}

/// True when every channel is finite.
#[inline]
pub fn is_finite(s: Spectrum) -> bool {
    s.is_finite()
}
