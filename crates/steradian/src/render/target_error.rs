//! Stopping at a stated error (`RenderOptions::target_error` = E, `--target-error`): for a
//! meter and for every cell of a work plane, the render stops after the first pass at which
//! each channel c of the reading has a 95 % confidence half-width of at most E times its value,
//!   1.96 · σ_c ≤ E · max(|v_c|, 0.01 · max_k |v_k|),
//! σ_c the channel's standard error; a channel below 1 % of the reading's brightest counts as
//! that 1 % ([`CHANNEL_FLOOR`]), so that a nearly black channel of a coloured light does not
//! hold the render. So every channel of the reading (and its luminance, a positive mix of
//! them) is within E of the truth in about 95 % of renders (the closed-form test checks at
//! least 90 % over 50 seeds; the public validation cases, 20 seeds each at E = 1 %: see
//! `benches/target_error/validation_cases.py`). A rule on the luminance alone let a blue
//! channel of the closed diffuse room stop at 1.9 % (2 of 20 seeds beyond 1 %, one at 2.6 %).
//! The check waits for [`MIN_SAMPLES_FOR_TARGET`] samples per pixel,
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

/// A meter's channel is judged against at least this fraction of the reading's brightest
/// channel.
pub const CHANNEL_FLOOR: f64 = 0.01;

/// Fraction of an image's pixels that must reach the target error.
pub const IMAGE_PIXEL_QUANTILE: f64 = 0.95;

/// An image pixel's error is relative to its luminance plus this fraction of the image's mean
/// luminance.
pub const IMAGE_ERROR_FLOOR: f64 = 0.01;

/// Whether every pixel of `film` (holding `spp` samples per pixel) has reached relative error
/// `e` in every channel (see the module docs).
pub fn reached(film: &Film, spp: u32, e: f64) -> bool {
    if spp < MIN_SAMPLES_FOR_TARGET {
        return false;
    }
    let (value, error) = (film.develop(), film.develop_stderr());
    value.data.chunks_exact(3).zip(error.data.chunks_exact(3)).all(|(v, s)| {
        let v = [v[0] as f64, v[1] as f64, v[2] as f64];
        let s = [s[0] as f64, s[1] as f64, s[2] as f64];
        reading_reached(v, s, e)
    })
}

/// Whether one reading, its value `v` and standard error `s` per channel, is within `e` at
/// 95 % confidence in every channel (see the module docs).
pub fn reading_reached(v: [f64; 3], s: [f64; 3], e: f64) -> bool {
    let floor = CHANNEL_FLOOR * v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    v.iter().zip(&s).all(|(v, s)| CONFIDENCE_Z * s <= e * v.abs().max(floor))
}

/// Whether the image on `film` (holding `spp` samples per pixel) has reached relative error
/// `e` (see the module docs): [`image_error`] is at most `e`.
pub fn image_reached(film: &Film, spp: u32, e: f64) -> bool {
    spp >= MIN_SAMPLES_FOR_TARGET && image_error(film) <= e
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
    if e.is_empty() {
        return 0.0;
    }
    // the k-th smallest, k = ⌈quantile · n⌉: linear time, as it runs after every pass
    let k = ((IMAGE_PIXEL_QUANTILE * n).ceil() as usize).clamp(1, e.len());
    *e.select_nth_unstable_by(k - 1, f64::total_cmp).1
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every channel must be there: a luminance within E does not hide a noisy blue channel,
    /// a nearly black channel counts as 1 % of the brightest, and a dark reading is reached.
    #[test]
    fn a_reading_is_reached_channel_by_channel() {
        let e = 0.01;
        // 1.96 σ = 0.5 %, 0.5 %, 1.9 % of the value: luminance (weights 0.21, 0.72, 0.07)
        // within 1 %, blue not
        let v = [1.43, 1.61, 2.05];
        let s = [0.0037, 0.0041, 0.0199];
        assert!(CONFIDENCE_Z * (0.21 * s[0] + 0.72 * s[1] + 0.07 * s[2]) <= e * 1.6);
        assert!(!reading_reached(v, s, e));
        assert!(reading_reached(v, [s[0], s[1], 0.009], e));
        // blue at 1e-4 of red with σ = 0.5 % of red's 1 %: reached; at 2× that, not
        assert!(reading_reached([1.0, 0.5, 1e-4], [0.001, 0.001, 0.5e-4], e));
        assert!(!reading_reached([1.0, 0.5, 1e-4], [0.001, 0.001, 0.6e-4], e));
        assert!(reading_reached([0.0; 3], [0.0; 3], e));
        assert!(!reading_reached([0.0; 3], [1e-9, 0.0, 0.0], e));
    }
}
