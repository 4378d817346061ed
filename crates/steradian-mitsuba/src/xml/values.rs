//! Property elements: `<boolean>`, `<integer>`, `<float>`, `<string>`, `<point>`,
//! `<vector>`, `<rgb>` and `<spectrum>` read into a typed [`PropertyValue`].
//!
//! Parsed strictly, as Mitsuba 3's `xml.cpp` does: `<integer>` refuses `1.5`; `<boolean>`
//! takes `true`/`false` in any case; `<point>`/`<vector>` need `value` (1 or 3 numbers) or
//! all of `x`, `y`, `z`; `<rgb>` takes 1 (broadcast) or 3 numbers. Spectra are reduced to RGB
//! by [`crate::spectrum`], in the role their name and owner give them.

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::attrs::{parse_f64, tokenize, Attr, Attrs};
use crate::error::LoadError;
use crate::properties::{PropertyValue, SpectrumValue};
use crate::spectrum::{self, SpectrumRole};

/// The value of property element `attrs` (its tag is `attrs.elem`), named `name`;
/// `within_emitter` is true for a direct property of an `<emitter>` (it decides a spectrum's
/// role); `resolve` finds a file a `<spectrum filename=…>` names. The element's attributes
/// have been checked by the caller.
pub(super) fn parse_value(
    attrs: &Attrs,
    name: &str,
    within_emitter: bool,
    resolve: &dyn Fn(&str) -> PathBuf,
) -> Result<PropertyValue, LoadError> {
    let tag = attrs.elem.as_str();
    let num = |a: &Attr, t: &str| -> Result<f64, LoadError> {
        parse_f64(t).ok_or_else(|| {
            LoadError::at(
                &a.pos,
                format!(
                    "could not parse floating point value \"{}\" in <{tag} name=\"{name}\">",
                    t.trim()
                ),
            )
        })
    };
    let value = match tag {
        "boolean" => {
            let a = attrs.require("value")?;
            match a.value.to_lowercase().as_str() {
                "true" => PropertyValue::Bool(true),
                "false" => PropertyValue::Bool(false),
                _ => {
                    return Err(LoadError::at(
                        &a.pos,
                        format!(
                            "could not parse boolean value \"{}\" (must be \"true\" or \"false\")",
                            a.value
                        ),
                    ))
                }
            }
        }
        "integer" => {
            let a = attrs.require("value")?;
            match a.value.trim().parse::<i64>() {
                Ok(i) => PropertyValue::Int(i),
                Err(_) => {
                    return Err(LoadError::at(
                        &a.pos,
                        format!(
                            "could not parse integer value \"{}\" in <integer name=\"{name}\">",
                            a.value
                        ),
                    ))
                }
            }
        }
        "float" => {
            let a = attrs.require("value")?;
            PropertyValue::Float(num(a, &a.value)?)
        }
        "string" => PropertyValue::String(attrs.require("value")?.value.clone()),
        "point" | "vector" => {
            let v = if let Some(a) = attrs.get("value") {
                if attrs.get("x").is_some() || attrs.get("y").is_some() || attrs.get("z").is_some()
                {
                    return Err(attrs
                        .error(format!("<{tag}> can't mix 'value' with 'x'/'y'/'z' attributes")));
                }
                let toks = tokenize(&a.value);
                let n = toks.iter().map(|t| num(a, t)).collect::<Result<Vec<_>, _>>()?;
                match n.len() {
                    1 => Vec3::splat(n[0] as f32),
                    3 => Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32),
                    k => {
                        return Err(LoadError::at(
                            &a.pos,
                            format!("'value' of <{tag}> must have 1 or 3 numbers, got {k}"),
                        ))
                    }
                }
            } else {
                // Mitsuba requires all of x, y and z.
                let mut v = [0.0f32; 3];
                for (i, c) in ["x", "y", "z"].iter().enumerate() {
                    let a = attrs.require(c)?;
                    v[i] = num(a, &a.value)? as f32;
                }
                Vec3::from(v)
            };
            if tag == "point" {
                PropertyValue::Point(v)
            } else {
                PropertyValue::Vector(v)
            }
        }
        "rgb" => {
            let a = attrs.require("value")?;
            let toks = tokenize(&a.value);
            let n = toks.iter().map(|t| num(a, t)).collect::<Result<Vec<_>, _>>()?;
            match n.len() {
                1 => PropertyValue::Rgb(Vec3::splat(n[0] as f32)),
                3 => PropertyValue::Rgb(Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32)),
                k => {
                    return Err(LoadError::at(
                        &a.pos,
                        format!("<rgb> needs one or three values, got {k}"),
                    ))
                }
            }
        }
        "spectrum" => {
            PropertyValue::Spectrum(parse_spectrum(attrs, name, within_emitter, resolve)?)
        }
        _ => return Err(attrs.error(format!("unexpected tag <{tag}>"))),
    };
    Ok(value)
}

/// `<spectrum value="…">`: one number (uniform) or `wavelength:value` pairs; or
/// `<spectrum filename="…">`: a file of such pairs (see [`read_spd`]).
fn parse_spectrum(
    attrs: &Attrs,
    name: &str,
    within_emitter: bool,
    resolve: &dyn Fn(&str) -> PathBuf,
) -> Result<SpectrumValue, LoadError> {
    let role = SpectrumRole::of(name, within_emitter);
    match (attrs.get("value"), attrs.get("filename")) {
        (Some(_), Some(_)) | (None, None) => {
            Err(attrs
                .error("<spectrum> needs exactly one of the attributes 'value' and 'filename'"))
        }
        (None, Some(a)) => {
            let path = resolve(&a.value);
            let (wl, vals) = read_spd(&path).map_err(|m| LoadError::at(&a.pos, m))?;
            Ok(SpectrumValue::Rgb(spectrum::wavelength_list_to_rgb(&wl, &vals, role)))
        }
        (Some(a), None) => {
            let toks = tokenize(&a.value);
            if toks.len() == 1 && !toks[0].contains(':') {
                let v = parse_f64(toks[0]).ok_or_else(|| {
                    LoadError::at(
                        &a.pos,
                        format!("could not parse constant spectrum \"{}\"", toks[0]),
                    )
                })?;
                return Ok(match spectrum::uniform_to_rgb(v, role) {
                    Some(c) => SpectrumValue::Rgb(c),
                    None => SpectrumValue::Uniform(v as f32),
                });
            }
            let mut wl = Vec::new();
            let mut vals = Vec::new();
            for t in &toks {
                let pair: Vec<&str> = t.split(':').collect();
                let (w, v) = match pair.as_slice() {
                    [w, v] => (parse_f64(w), parse_f64(v)),
                    _ => {
                        return Err(LoadError::at(
                            &a.pos,
                            format!(
                                "invalid spectrum entry \"{t}\" (expected wavelength:value pairs)"
                            ),
                        ))
                    }
                };
                match (w, v) {
                    (Some(w), Some(v)) if w.is_finite() && v.is_finite() => {
                        if let Some(&prev) = wl.last() {
                            if w <= prev {
                                return Err(LoadError::at(
                                    &a.pos,
                                    "spectrum wavelengths must be strictly increasing",
                                ));
                            }
                        }
                        wl.push(w);
                        vals.push(v);
                    }
                    _ => {
                        return Err(LoadError::at(
                            &a.pos,
                            format!("could not parse wavelength:value pair \"{t}\""),
                        ))
                    }
                }
            }
            if wl.len() < 2 {
                return Err(LoadError::at(
                    &a.pos,
                    "a spectrum needs at least two wavelength:value pairs",
                ));
            }
            Ok(SpectrumValue::Rgb(spectrum::wavelength_list_to_rgb(&wl, &vals, role)))
        }
    }
}

/// The wavelengths (nm) and values of a spectrum file, as Mitsuba 3 reads one
/// (`spectrum_from_file`): a line per sample, "wavelength value" separated by white space,
/// `#` starting a comment line, blank lines skipped; at least two samples, wavelengths
/// strictly increasing and every number finite (the message names the line otherwise).
fn read_spd(path: &Path) -> Result<(Vec<f64>, Vec<f64>), String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read spectrum file \"{}\": {e}", path.display()))?;
    let (mut wl, mut vals) = (Vec::new(), Vec::new());
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |what: &str| format!("{}:{}: {what} in \"{line}\"", path.display(), i + 1);
        let toks: Vec<&str> = line.split_whitespace().collect();
        let [w, v] = toks.as_slice() else {
            return Err(bad("expected a wavelength and a value"));
        };
        let (Some(w), Some(v)) = (parse_f64(w), parse_f64(v)) else {
            return Err(bad("could not parse a number"));
        };
        if !(w.is_finite() && v.is_finite()) {
            return Err(bad("a number is not finite"));
        }
        if wl.last().is_some_and(|&prev| w <= prev) {
            return Err(bad("wavelengths must be strictly increasing"));
        }
        wl.push(w);
        vals.push(v);
    }
    if wl.len() < 2 {
        return Err(format!(
            "spectrum file \"{}\" needs at least two wavelength-value lines",
            path.display()
        ));
    }
    Ok((wl, vals))
}
