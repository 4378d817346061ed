//! Stopping at a stated error (`RenderOptions::target_error` = E, `--target-error`): for a
//! meter and for every cell of a work plane, the render stops after the first pass at which
//! the reading's 95 % confidence half-width is at most E times its value,
//!   1.96 · σ(Y) ≤ E · Y,
//! Y the reading's luminance (for a grey or white light, any channel) and σ its standard error
//! (taken as Σ w_c σ_c over the channels, an upper bound, see `grid_reading.rs`). So the
//! reading is within E of the truth in about 95 % of renders (the closed-form test checks at
//! least 90 % over 50 seeds). The check waits for [`MIN_SAMPLES_FOR_TARGET`] samples per pixel,
//! so that σ itself is estimated from enough samples; it runs only between passes (which grow
//! up to spp/32), and `spp` caps the samples. A reading of 0 with σ = 0 (a point no light
//! reaches) counts as reached.
//!
//! **Images.** A pixel of an image reaches E when 1.96 · σ(Y) ≤ E · (Y + 0.01 · Ȳ), Ȳ the
//! image's mean luminance: relative to the pixel's own value, with a floor of 1 % of the image
//! so that black and near-black pixels (shadows, an empty background) do not hold the render
//! forever; the image reaches E when [`IMAGE_PIXEL_QUANTILE`] of its pixels have. Each pixel's
//! σ is its own (the film's weighted moments), so the rule holds for any reconstruction filter,
//! where a rule on the image mean would have to know how the filter correlates neighbours.
//! About 95 % of the pixels that reached E are within E of the truth, so about 90 % of all
//! pixels (the test checks at least 85 % against a closed form).
//!
//! Stopping on an estimate of the error is a sequential rule: renders that stop early are
//! those whose error estimate came out low, which biases the reading by a fraction of σ that
//! is far below E at these sample counts (the test measures the rate, not only the mean).

use crate::film::Film;
use crate::spectrum::luminance_f64;

/// Standard errors in a 95 % (two-sided) confidence half-width.
pub const CONFIDENCE_Z: f64 = 1.96;

/// Samples per pixel at most where a target error is given and the samples are not.
pub const MAX_SPP_FOR_TARGET: u32 = 1 << 20;

/// Samples per pixel before a target error may end a render.
pub const MIN_SAMPLES_FOR_TARGET: u32 = 64;

/// Fraction of an image's pixels that must reach the target error.
pub const IMAGE_PIXEL_QUANTILE: f64 = 0.95;

/// An image pixel's error is relative to its luminance plus this fraction of the image's mean
/// luminance.
pub const IMAGE_ERROR_FLOOR: f64 = 0.01;

/// Whether every pixel of `film` (holding `spp` samples per pixel) has reached relative error
/// `e` (see the module docs).
pub fn reached(film: &Film, spp: u32, e: f64) -> bool {
    spp >= MIN_SAMPLES_FOR_TARGET
        && pixel_luminances(film)
            .iter()
            .all(|&(v, s)| CONFIDENCE_Z * s <= e * v.abs() || (v == 0.0 && s == 0.0))
}

/// Whether the image on `film` (holding `spp` samples per pixel) has reached relative error
/// `e` (see the module docs).
pub fn image_reached(film: &Film, spp: u32, e: f64) -> bool {
    if spp < MIN_SAMPLES_FOR_TARGET {
        return false;
    }
    let y = pixel_luminances(film);
    let n = y.len().max(1) as f64;
    let floor = IMAGE_ERROR_FLOOR * (y.iter().map(|(v, _)| v).sum::<f64>() / n).abs();
    let reached = y.iter().filter(|(v, s)| CONFIDENCE_Z * s <= e * (v.abs() + floor)).count();
    reached as f64 >= IMAGE_PIXEL_QUANTILE * n
}

/// The relative error that [`IMAGE_PIXEL_QUANTILE`] of the pixels of `film` have reached at
/// 95 % confidence (the image rule of the module docs): the image reaches a target error E when
/// this is at most E (pixels of one sample report no error, as their standard error is 0).
pub fn image_error(film: &Film) -> f64 {
    let y = pixel_luminances(film);
    let n = y.len() as f64;
    let floor = IMAGE_ERROR_FLOOR * (y.iter().map(|(v, _)| v).sum::<f64>() / n).abs();
    let mut e: Vec<f64> = y
        .iter()
        .map(|&(v, s)| match CONFIDENCE_Z * s / (v.abs() + floor) {
            e if e.is_nan() => 0.0,
            e => e,
        })
        .collect();
    e.sort_by(f64::total_cmp);
    let k = ((IMAGE_PIXEL_QUANTILE * n).ceil() as usize).clamp(1, e.len().max(1));
    e.get(k - 1).copied().unwrap_or(0.0)
}

/// Each pixel's luminance and the bound Σ w_c σ_c on its standard error.
fn pixel_luminances(film: &Film) -> Vec<(f64, f64)> {
    let (value, error) = (film.develop(), film.develop_stderr());
    value
        .data
        .chunks_exact(3)
        .zip(error.data.chunks_exact(3))
        .map(|(v, s)| (luminance_f64(v), luminance_f64(s)))
        .collect()
}
