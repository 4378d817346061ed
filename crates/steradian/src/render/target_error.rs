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

/// Whether every pixel of `film` (holding `spp` samples per pixel) has reached relative error
/// `e` (see the module docs).
pub fn reached(film: &Film, spp: u32, e: f64) -> bool {
    if spp < MIN_SAMPLES_FOR_TARGET {
        return false;
    }
    let (value, error) = (film.develop(), film.develop_stderr());
    value.data.chunks_exact(3).zip(error.data.chunks_exact(3)).all(|(v, s)| {
        let (v, s) = (luminance_f64(v), luminance_f64(s));
        CONFIDENCE_Z * s <= e * v.abs() || (v == 0.0 && s == 0.0)
    })
}
