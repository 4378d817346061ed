//! IES LM-63 photometric files (the 1986, 1991, 1995, 2002 and 2019 editions).
//!
//! Layout: an optional first line naming the edition (`IESNA:LM-63-2002`, `IES:LM-63-2019`,
//! …), keyword lines (`[MANUFAC] …`) up to the `TILT=` line, then numbers separated by blanks,
//! commas or line breaks: lamps, lumens per lamp, candela multiplier, the counts of vertical
//! and horizontal angles, the photometric type, the unit of length (1 feet, 2 metres), the
//! luminous opening's width, length and height; the ballast factor, a field that the 1995
//! edition calls the ballast–lamp photometric factor (later editions: "future use", 1), the
//! input watts; the vertical angles, the horizontal angles, and the candela values plane by
//! plane.
//!
//! - Intensity: value × candela multiplier × ballast factor × the 1995 factor, in cd.
//!   Lumens per lamp −1 means absolute photometry: no lamp flux is stated.
//! - `TILT=NONE` and `TILT=INCLUDE` (lamp-to-luminaire geometry, then angles and multipliers):
//!   the luminaire is taken as measured, so the tilt multiplier at 0° applies (linear between
//!   the tabulated angles). `TILT=<file>` (a separate tilt file) is refused.
//! - Photometric type C only (interior and area luminaires); types A and B (automotive,
//!   floodlights) are refused with their names.

use super::{check, Photometry, PhotometryError};

/// The numbers of a file after its `TILT=` line, each with its line number.
struct Numbers<'a> {
    tokens: Vec<(usize, &'a str)>,
    next: usize,
    /// The last line of the file, for "ends early" messages.
    last_line: usize,
}

impl<'a> Numbers<'a> {
    fn new(lines: &[(usize, &'a str)]) -> Self {
        let tokens = lines
            .iter()
            .flat_map(|&(n, l)| {
                l.split(|c: char| c.is_whitespace() || c == ',')
                    .filter(|t| !t.is_empty())
                    .map(move |t| (n, t))
            })
            .collect();
        let last_line = lines.last().map_or(1, |l| l.0);
        Numbers { tokens, next: 0, last_line }
    }

    fn number(&mut self, what: &str) -> Result<(f64, usize), PhotometryError> {
        let Some(&(line, t)) = self.tokens.get(self.next) else {
            return Err(PhotometryError::new(
                self.last_line,
                format!("the file ends before {what}"),
            ));
        };
        self.next += 1;
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((v, line)),
            _ => Err(PhotometryError::new(line, format!("{what}: '{t}' is not a number"))),
        }
    }

    fn count(&mut self, what: &str) -> Result<(usize, usize), PhotometryError> {
        let (v, line) = self.number(what)?;
        if v < 1.0 || v.fract() != 0.0 || v > 100_000.0 {
            return Err(PhotometryError::new(line, format!("{what} must be a count ≥ 1, got {v}")));
        }
        Ok((v as usize, line))
    }

    fn list(&mut self, n: usize, what: &str) -> Result<Vec<f64>, PhotometryError> {
        (0..n).map(|_| self.number(what).map(|v| v.0)).collect()
    }
}

/// Parses the text of an IES LM-63 file.
pub fn parse_ies(text: &str) -> Result<Photometry, PhotometryError> {
    let lines: Vec<(usize, &str)> =
        text.lines().enumerate().map(|(i, l)| (i + 1, l.trim_end_matches('\r'))).collect();
    let Some(tilt_at) = lines.iter().position(|(_, l)| l.trim_start().starts_with("TILT")) else {
        return Err(PhotometryError::new(
            lines.len().max(1),
            "no 'TILT=' line: this is not an IES LM-63 photometric file",
        ));
    };
    let (tilt_line, tilt) = lines[tilt_at];
    let tilt = tilt.trim_start()["TILT".len()..].trim_start().trim_start_matches('=').trim();
    let mut nums = Numbers::new(&lines[tilt_at + 1..]);
    let tilt_factor = match tilt {
        "NONE" => 1.0,
        "INCLUDE" => {
            nums.number("the lamp-to-luminaire geometry")?;
            let (n, _) = nums.count("the number of tilt angles")?;
            let angles = nums.list(n, "a tilt angle")?;
            let factors = nums.list(n, "a tilt multiplier")?;
            interpolate(&angles, &factors, 0.0)
        }
        other => {
            return Err(PhotometryError::new(
                tilt_line,
                format!(
                    "TILT={other}: separate tilt files are not supported (give TILT=NONE or \
                     TILT=INCLUDE)"
                ),
            ))
        }
    };
    let (lamps, _) = nums.number("the number of lamps")?;
    let (lumens_per_lamp, _) = nums.number("the lumens per lamp")?;
    let (multiplier, _) = nums.number("the candela multiplier")?;
    let (n_vertical, _) = nums.count("the number of vertical angles")?;
    let (n_horizontal, _) = nums.count("the number of horizontal angles")?;
    let (kind, kind_line) = nums.number("the photometric type")?;
    match kind as i64 {
        1 => {}
        2 | 3 => {
            return Err(PhotometryError::new(
                kind_line,
                format!(
                    "photometric type {} is not supported (only type C: vertical angles from the \
                     nadir)",
                    if kind == 2.0 { "B" } else { "A" }
                ),
            ))
        }
        _ => {
            return Err(PhotometryError::new(
                kind_line,
                format!("the photometric type must be 1 (C), 2 (B) or 3 (A), got {kind}"),
            ))
        }
    }
    let (units, units_line) = nums.number("the unit of length")?;
    let metres = match units as i64 {
        1 => 0.3048,
        2 => 1.0,
        _ => {
            return Err(PhotometryError::new(
                units_line,
                format!("the unit of length must be 1 (feet) or 2 (metres), got {units}"),
            ))
        }
    };
    let (width, _) = nums.number("the opening's width")?;
    let (length, _) = nums.number("the opening's length")?;
    let (height, _) = nums.number("the opening's height")?;
    let (ballast, _) = nums.number("the ballast factor")?;
    let (photometric_factor, _) = nums.number("the ballast-lamp photometric factor")?;
    nums.number("the input watts")?;
    let data_line = nums.tokens.get(nums.next).map_or(nums.last_line, |t| t.0);
    let vertical = nums.list(n_vertical, "a vertical angle")?;
    let horizontal = nums.list(n_horizontal, "a horizontal angle")?;
    let scale = multiplier * ballast * photometric_factor * tilt_factor;
    let mut candela = Vec::with_capacity(n_horizontal);
    for _ in 0..n_horizontal {
        candela.push(nums.list(n_vertical, "a candela value")?.iter().map(|v| v * scale).collect());
    }
    if let Some(&(line, t)) = nums.tokens.get(nums.next) {
        return Err(PhotometryError::new(
            line,
            format!("'{t}' after the last candela value: the counts do not match the data"),
        ));
    }
    let lamp_lumens = (lumens_per_lamp > 0.0).then_some(lamps * lumens_per_lamp);
    let p = Photometry {
        vertical,
        horizontal,
        candela,
        lamp_lumens,
        opening: [width.abs() * metres, length.abs() * metres, height.abs() * metres],
    };
    check(&p, data_line)?;
    Ok(p)
}

/// The piecewise-linear function through (xs, ys) at x (clamped to the ends).
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&a| a <= x);
    if i == 0 {
        return ys[0];
    }
    if i >= xs.len() {
        return ys[ys.len() - 1];
    }
    let t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
    ys[i - 1] + (ys[i] - ys[i - 1]) * t
}
