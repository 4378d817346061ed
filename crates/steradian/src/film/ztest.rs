//! Mitsuba 3's render-test rule: is an image an unbiased estimate of a reference?
//!
//! Per pixel and channel, after both the mean images and the reference's per-sample variance
//! image are converted from linear sRGB to CIE XYZ (as Mitsuba's test converts its bitmaps):
//!
//! z = |mean − ref| · √(spp / max(var_ref, 10⁻⁴)),  p = 2 (1 − Φ(z)) = erfc(z / √2)
//!
//! where `spp` is the tested image's samples per pixel, so `var_ref / spp` stands for the
//! variance of its pixel mean. A pixel passes when all three channels have p above the
//! Šidák-corrected level α' = 1 − (1 − α)^(1/N), α = 0.01 over the N pixel channels tested;
//! the image passes when at least 99.75 % of its pixels pass.

use super::Image;
use crate::spectrum::RGB_TO_XYZ;

/// Significance level of the whole image (before the Šidák correction).
pub const ZTEST_ALPHA: f64 = 0.01;
/// Share of pixels that must pass.
pub const ZTEST_PASS_FRACTION: f64 = 0.9975;
/// Floor of the reference variance (Mitsuba's), in the image's unit squared.
pub const ZTEST_MIN_VARIANCE: f64 = 1e-4;

/// The outcome of [`z_test`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZTest {
    pub pixels: usize,
    /// Pixels whose three channels all pass.
    pub passed: usize,
    /// The per-channel significance level after the Šidák correction.
    pub alpha_corrected: f64,
    /// The smallest p-value of any channel.
    pub min_p: f64,
}

impl ZTest {
    /// Share of pixels that passed.
    pub fn pass_fraction(&self) -> f64 {
        self.passed as f64 / self.pixels.max(1) as f64
    }

    /// Whether the image passes Mitsuba's rule.
    pub fn passes(&self) -> bool {
        self.pass_fraction() >= ZTEST_PASS_FRACTION
    }
}

/// Linear sRGB to CIE XYZ in f64 ([`RGB_TO_XYZ`]).
fn to_xyz(px: &[f32]) -> [f64; 3] {
    RGB_TO_XYZ.map(|row| row.iter().zip(px).map(|(m, &c)| m * c as f64).sum())
}

/// The complementary error function, with fractional error below 1.2·10⁻⁷ everywhere
/// (Chebyshev fit of Press et al., Numerical Recipes, 2nd ed., §6.2).
pub fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.26551223
        + t * (1.00002368
            + t * (0.37409196
                + t * (0.09678418
                    + t * (-0.18628806
                        + t * (0.27886807
                            + t * (-1.13520398
                                + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277))))))));
    let r = t * poly.exp();
    if x >= 0.0 {
        r
    } else {
        2.0 - r
    }
}

/// Tests `image`, rendered at `spp` samples per pixel, against `reference` and its per-sample
/// variance image `reference_var` (all the same size, RGB).
pub fn z_test(image: &Image, spp: u32, reference: &Image, reference_var: &Image) -> ZTest {
    assert_eq!((image.width, image.height), (reference.width, reference.height));
    assert_eq!((image.width, image.height), (reference_var.width, reference_var.height));
    let pixels = image.pixel_count();
    let alpha_corrected = 1.0 - (1.0 - ZTEST_ALPHA).powf(1.0 / (3 * pixels.max(1)) as f64);
    let (mut passed, mut min_p) = (0, 1.0f64);
    let chunks = |im: &Image| im.data.chunks_exact(3).map(to_xyz).collect::<Vec<_>>();
    let (a, r, v) = (chunks(image), chunks(reference), chunks(reference_var));
    for i in 0..pixels {
        let mut ok = true;
        for c in 0..3 {
            let z =
                (a[i][c] - r[i][c]).abs() * (spp as f64 / v[i][c].max(ZTEST_MIN_VARIANCE)).sqrt();
            // NaN in either image fails the pixel
            let p = if z.is_nan() { 0.0 } else { erfc(z / std::f64::consts::SQRT_2) };
            min_p = min_p.min(p);
            ok &= p > alpha_corrected;
        }
        passed += ok as usize;
    }
    ZTest { pixels, passed, alpha_corrected, min_p }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    #[test]
    fn erfc_matches_known_values() {
        for (x, want) in [
            (0.0, 1.0),
            (0.5, 0.4795001221869535),
            (1.0, 0.15729920705028513),
            (2.0, 0.004677734981047266),
            (4.0, 1.541725790028002e-8),
            (-1.0, 1.8427007929497148),
        ] {
            assert!((erfc(x) - want).abs() <= 1.2e-7 * want, "erfc({x}) = {}", erfc(x));
        }
    }

    fn image(w: u32, h: u32, f: impl FnMut(usize) -> f32) -> Image {
        Image { width: w, height: h, data: (0..(w * h * 3) as usize).map(f).collect() }
    }

    /// Pixel means of `spp` samples of a uniform variable with variance 1/12 around `mean`.
    fn noisy(mean: f32, spp: u32, seed: u64) -> Image {
        let mut rng = Pcg32::new(seed, 7);
        image(64, 64, |_| {
            let s: f32 = (0..spp).map(|_| rng.next_f32() - 0.5).sum();
            mean + s / spp as f32
        })
    }

    #[test]
    fn unbiased_images_pass_and_biased_ones_fail() {
        let reference = image(64, 64, |_| 0.5);
        // per-sample variance of a uniform [0, 1) variable, per RGB channel; a grey pixel's XYZ
        // variance is then the matrix row sums times that (the rule converts variances linearly)
        let var = image(64, 64, |_| 1.0 / 12.0);
        let t = z_test(&noisy(0.5, 64, 1), 64, &reference, &var);
        assert!(t.passes(), "{t:?}");
        // a 10 % bias (0.05) is 1.4 standard errors of a 64-sample pixel: too few pixels cross
        // the corrected level (z > 4.9) to fail the image; a 40 % bias (5.5 errors) fails it
        let t = z_test(&noisy(0.55, 64, 2), 64, &reference, &var);
        assert!(t.passes(), "{t:?}");
        let t = z_test(&noisy(0.7, 64, 2), 64, &reference, &var);
        assert!(!t.passes(), "{t:?}");
        // a NaN pixel fails
        let mut nan = noisy(0.5, 64, 3);
        nan.data[0] = f32::NAN;
        let t = z_test(&nan, 64, &reference, &var);
        assert_eq!(t.passed, t.pixels - 1);
    }
}
