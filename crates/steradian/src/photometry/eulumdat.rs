//! EULUMDAT (`.ldt`) photometric files.
//!
//! A fixed sequence of lines: 1 maker; 2 type indicator; 3 symmetry indicator Isym; 4 the
//! number Mc of C planes over the circle; 5 their spacing; 6 the number Ng of vertical angles
//! per plane; 7 their spacing; 8–12 report, name, number, file name, date; 13–15 the
//! luminaire's length, width, height (mm); 16–21 the luminous area's length, width and heights
//! (mm); 22 downward flux fraction (%); 23 light output ratio (%); 24 a conversion factor for
//! the intensities; 25 the tilt during measurement; 26 the number n of lamp sets, then n lines
//! each of lamp counts, lamp types, total lamp flux (lm), colour temperatures, colour
//! rendering, watts; ten direct ratios; the Mc C angles; the Ng vertical angles; then the
//! intensities in cd per 1000 lm of lamp flux, plane by plane, for the planes the symmetry
//! keeps: all (Isym 0), C0 only (1, rotational), C0–C180 (2), C90–C270 (3), C0–C90 (4).
//!
//! - Intensity: value × (total lamp flux of all sets)/1000 × the conversion factor, in cd.
//! - A decimal comma (`0,5`) is read as a decimal point, as European writers produce it.
//! - The light output ratio is not applied: the intensities already are the luminaire's, so
//!   its flux ∫ I dω is the lamps' flux times that ratio.

use super::{check, Photometry, PhotometryError};

/// Parses the text of a EULUMDAT file.
pub fn parse_eulumdat(text: &str) -> Result<Photometry, PhotometryError> {
    let lines: Vec<&str> = text.lines().map(|l| l.trim_end_matches('\r').trim()).collect();
    let line = |n: usize| -> Result<&str, PhotometryError> {
        lines.get(n - 1).copied().ok_or_else(|| {
            PhotometryError::new(lines.len().max(1), format!("the file ends before line {n}"))
        })
    };
    let number = |n: usize, what: &str| -> Result<f64, PhotometryError> {
        let t = line(n)?;
        t.replace(',', ".")
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| PhotometryError::new(n, format!("{what}: '{t}' is not a number")))
    };
    let count = |n: usize, what: &str| -> Result<usize, PhotometryError> {
        let v = number(n, what)?;
        if v < 0.0 || v.fract() != 0.0 || v > 100_000.0 {
            return Err(PhotometryError::new(n, format!("{what} must be a whole number, got {v}")));
        }
        Ok(v as usize)
    };
    let isym = count(3, "the symmetry indicator")?;
    let mc = count(4, "the number of C planes")?;
    let ng = count(6, "the number of vertical angles")?;
    if mc == 0 || ng < 2 {
        return Err(PhotometryError::new(
            if mc == 0 { 4 } else { 6 },
            "a EULUMDAT file needs at least 1 C plane and 2 vertical angles",
        ));
    }
    let mm = 1e-3;
    let area_length = number(16, "the luminous area's length")?;
    let area_width = number(17, "the luminous area's width")?;
    let area_height = number(18, "the luminous area's height")?;
    let conversion = number(24, "the conversion factor")?;
    let sets = count(26, "the number of lamp sets")?;
    // lamp counts (n), types (n), fluxes (n), colours (n), rendering (n), watts (n)
    let flux_line = 27 + 2 * sets;
    let mut lamp_flux = 0.0;
    for k in 0..sets {
        lamp_flux += number(flux_line + k, "a lamp set's total flux")?.abs();
    }
    let after_lamps = 27 + 6 * sets;
    let c_line = after_lamps + 10;
    let c_angles: Vec<f64> =
        (0..mc).map(|k| number(c_line + k, "a C angle")).collect::<Result<_, _>>()?;
    let g_line = c_line + mc;
    let vertical: Vec<f64> =
        (0..ng).map(|k| number(g_line + k, "a vertical angle")).collect::<Result<_, _>>()?;
    let (first, planes) = match isym {
        0 => (0, mc),
        1 => (0, 1),
        2 => (0, mc / 2 + 1),
        3 => (mc / 4, mc / 2 + 1),
        4 => (0, mc / 4 + 1),
        _ => {
            return Err(PhotometryError::new(
                3,
                format!("the symmetry indicator must be 0 to 4, got {isym}"),
            ))
        }
    };
    if first + planes > mc {
        return Err(PhotometryError::new(
            4,
            format!("{mc} C planes are too few for symmetry {isym}"),
        ));
    }
    let horizontal: Vec<f64> = c_angles[first..first + planes].to_vec();
    let i_line = g_line + ng;
    let scale = lamp_flux / 1000.0 * conversion;
    let mut candela = Vec::with_capacity(planes);
    for p in 0..planes {
        let row: Vec<f64> = (0..ng)
            .map(|k| number(i_line + p * ng + k, "an intensity").map(|v| v * scale))
            .collect::<Result<_, _>>()?;
        candela.push(row);
    }
    let p = Photometry {
        vertical,
        horizontal,
        candela,
        lamp_lumens: (lamp_flux > 0.0).then_some(lamp_flux),
        opening: [area_width * mm, area_length * mm, area_height * mm],
    };
    check(&p, c_line)?;
    Ok(p)
}
