//! Inverse trigonometric functions in single precision, as polynomials: libm's `acosf` and
//! `atan2f` cost several times more, and they run at every light sample (a spherical
//! rectangle's four angles) and at every sphere, disk and cylinder hit (its uv). Both are
//! within 4·10⁻⁷ rad of the exact value, about f32's resolution near π.

use std::f32::consts::{FRAC_PI_2, PI};

/// arccos(x) for x ∈ [−1, 1] (clamped): Abramowitz & Stegun 4.4.46's polynomial,
/// arccos x = √(1−x)·Σ aᵢxⁱ for x ≥ 0 (error ≤ 2·10⁻⁸) and π − arccos(−x) below.
#[inline]
pub fn acos(x: f32) -> f32 {
    const A: [f32; 8] = [
        FRAC_PI_2,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_3,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let ax = x.abs().min(1.0);
    // Horner's rule with plain products: `mul_add` would call libm's fmaf without FMA hardware
    let p = ((((((A[7] * ax + A[6]) * ax + A[5]) * ax + A[4]) * ax + A[3]) * ax + A[2]) * ax
        + A[1])
        * ax
        + A[0];
    let r = (1.0 - ax).sqrt() * p;
    if x < 0.0 {
        PI - r
    } else {
        r
    }
}

/// The angle of the point (x, y) from the +x axis, in [−π, π], as libm's `atan2(y, x)`:
/// Abramowitz & Stegun 4.4.49's polynomial, arctan a = a·(1 + Σ a₂ₖa²ᵏ) for a ∈ [0, 1]
/// (error ≤ 2·10⁻⁸), on a = min(|x|, |y|)/max(|x|, |y|), then folded into the octant of
/// (x, y). (0, 0) gives 0; NaN gives NaN.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    const A: [f32; 8] = [
        -0.333_331_45,
        0.199_935_51,
        -0.142_088_99,
        0.106_562_64,
        -0.075_289_64,
        0.042_909_614,
        -0.016_165_737,
        0.002_866_225_7,
    ];
    if x.is_nan() || y.is_nan() {
        return x + y;
    }
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    if hi == 0.0 {
        return 0.0f32.copysign(y) + if x.is_sign_negative() { PI.copysign(y) } else { 0.0 };
    }
    let a = lo / hi;
    let s = a * a;
    let p = (((((((A[7] * s + A[6]) * s + A[5]) * s + A[4]) * s + A[3]) * s + A[2]) * s + A[1])
        * s
        + A[0])
        * s;
    let mut r = a + a * p;
    if ay > ax {
        r = FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    r.copysign(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn acos_matches_libm() {
        for i in 0..=20_000 {
            let x = -1.0 + i as f32 * 1e-4;
            let err = (acos(x) as f64 - (x as f64).acos()).abs();
            assert!(err <= 4e-7, "acos({x}): error {err}");
        }
        assert_eq!(acos(1.5), 0.0);
        assert!((acos(-1.5) - PI).abs() < 1e-6);
    }

    /// Every direction of a fine circle (and radii from tiny to huge), against f64's atan2.
    #[test]
    fn atan2_matches_libm_all_around() {
        let mut worst = 0.0f64;
        for i in 0..100_000 {
            let phi = -std::f64::consts::PI + i as f64 * (std::f64::consts::TAU / 100_000.0);
            for r in [1e-20f64, 1e-3, 1.0, 7.5, 1e20] {
                let (x, y) = ((r * phi.cos()) as f32, (r * phi.sin()) as f32);
                let err = (atan2(y, x) as f64 - (y as f64).atan2(x as f64)).abs();
                worst = worst.max(err);
            }
        }
        assert!(worst <= 4e-7, "worst error {worst}");
    }

    #[test]
    fn atan2_on_the_axes_and_at_the_origin() {
        for (y, x) in [
            (0.0f32, 1.0f32),
            (1.0, 0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (-1.0, 0.0),
            (0.0, 0.0),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (3.0, 3.0),
            (-2.0, -2.0),
        ] {
            assert_eq!(atan2(y, x), y.atan2(x), "atan2({y}, {x})");
        }
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
    }
}
