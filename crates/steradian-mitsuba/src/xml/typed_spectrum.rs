//! `<spectrum type="…" name="…">`: Mitsuba 3's spectrum plugins, read as the value of the
//! enclosing object's property `name` (steradian renders RGB, so each becomes one linear sRGB
//! colour when the file is read).
//!
//! | type        | parameters (default)                                  | RGB value |
//! |-------------|-------------------------------------------------------|-----------|
//! | `d65`       | `scale` (1)                                           | `scale` in every channel (D65 is sRGB's white), as Mitsuba's RGB variants give |
//! | `srgb`      | `color` (required)                                    | `color` |
//! | `uniform`   | `value` (1)                                           | `value` in every channel (no white-point conversion, unlike `<spectrum value="v"/>` in an emitter: Mitsuba's RGB variants agree) |
//! | `regular`   | `wavelength_min`, `wavelength_max` (nm), `values` (comma-separated) | the list, evenly spaced, converted as `<spectrum value="λ:v, …"/>` is |
//! | `irregular` | `wavelengths` (nm), `values` (comma-separated)        | as `<spectrum value="λ:v, …"/>` |
//!
//! **Where steradian differs on purpose.** Mitsuba's RGB variants refuse `regular` and
//! `irregular` ("not implemented"); steradian converts them as it converts an inline list.
//! `blackbody` is refused, as in Mitsuba's RGB variants (steradian has no spectral mode). A
//! spectrum with an `id` (to be referenced) is read as an object and refused where a value is
//! expected.

use glam::Vec3;

use crate::error::LoadError;
use crate::properties::{Properties, SpectrumValue};
use crate::source::SourcePos;
use crate::spectrum::{wavelength_list_to_rgb, SpectrumRole};

/// The spectrum plugins read as values.
pub(super) const TYPED_SPECTRA: [&str; 6] =
    ["d65", "srgb", "uniform", "regular", "irregular", "blackbody"];

/// The value of a `<spectrum type="ty">` with properties `props` at `pos`, for property
/// `name` of an object (`within_emitter`: a direct property of an `<emitter>`).
pub(super) fn typed_spectrum(
    ty: &str,
    props: &Properties,
    pos: &SourcePos,
    name: &str,
    within_emitter: bool,
) -> Result<SpectrumValue, LoadError> {
    let desc = format!("<spectrum type=\"{ty}\">");
    let value = match ty {
        "d65" => Vec3::splat(props.get_float("scale")?.unwrap_or(1.0)),
        "uniform" => Vec3::splat(props.get_float("value")?.unwrap_or(1.0)),
        "srgb" => props.get_spectrum("color")?.map(|c| Vec3::from(c.to_array())).ok_or_else(|| {
            LoadError::at(pos, format!("{desc}: missing parameter 'color'"))
        })?,
        "regular" | "irregular" => {
            let values = list(props, "values", pos, &desc)?;
            let wavelengths = if ty == "regular" {
                let bound = |p: &str| {
                    props.get_float(p)?.ok_or_else(|| {
                        LoadError::at(pos, format!("{desc}: missing parameter '{p}'"))
                    })
                };
                let (lo, hi) = (bound("wavelength_min")? as f64, bound("wavelength_max")? as f64);
                let n = values.len().max(2) - 1;
                (0..values.len()).map(|i| lo + (hi - lo) * i as f64 / n as f64).collect()
            } else {
                list(props, "wavelengths", pos, &desc)?
            };
            if values.len() < 2 || wavelengths.len() != values.len() {
                return Err(LoadError::at(
                    pos,
                    format!(
                        "{desc}: needs at least two values, one per wavelength ({} wavelengths, {} values)",
                        wavelengths.len(),
                        values.len()
                    ),
                ));
            }
            if wavelengths.windows(2).any(|w| w[1] <= w[0]) {
                return Err(LoadError::at(
                    pos,
                    format!("{desc}: wavelengths must increase"),
                ));
            }
            wavelength_list_to_rgb(&wavelengths, &values, SpectrumRole::of(name, within_emitter))
        }
        _ => {
            return Err(LoadError::at(
                pos,
                format!("the Mitsuba 3 spectrum plugin '{ty}' is not supported by steradian (Mitsuba renders it only in spectral variants; give an <rgb> value)"),
            ))
        }
    };
    props.check_all_used(&desc)?;
    if !value.is_finite() {
        return Err(LoadError::at(pos, format!("{desc}: the value {value} is not finite")));
    }
    Ok(SpectrumValue::Rgb(value))
}

/// A comma- or space-separated list of finite numbers.
fn list(props: &Properties, p: &str, pos: &SourcePos, desc: &str) -> Result<Vec<f64>, LoadError> {
    let s = props
        .get_string(p)?
        .ok_or_else(|| LoadError::at(pos, format!("{desc}: missing parameter '{p}'")))?;
    s.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                LoadError::at(pos, format!("{desc}: '{p}' holds \"{t}\", not a number"))
            })
        })
        .collect()
}
