//! Isolux pictures: a work plane's grid of illuminances drawn as a plan, in false colour
//! between the cell centres (bilinear), with contour lines at round values, each cell's value
//! written at its centre and a labelled scale.
//!
//! Contours sit at multiples of the smallest round step (1, 2 or 5 × 10ᵏ) that gives at most
//! eight lines over the grid's range; a pixel is drawn dark where a contour level lies between its
//! value and its right or lower neighbour's.

use std::path::Path;

use super::encode_png_rgb8;
use super::falsecolor::{format_tick, ramp, Canvas};

/// Pixels per cell side, at least (larger grids get smaller cells, down to this).
const CELL_MIN: usize = 24;
/// Pixels of picture per side for the grid, about.
const PICTURE: usize = 480;

/// The smallest round step giving at most eight contour lines over `range`.
pub fn contour_step(range: f64) -> f64 {
    if !(range.is_finite() && range > 0.0) {
        return 1.0;
    }
    let raw = range / 6.0;
    let k = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * k).find(|s| range / s <= 8.0).unwrap_or(10.0 * k)
}

/// The isolux picture of `values` (ny rows of nx, row 0 the plan's top) titled
/// `title (unit)`: (width, height, sRGB bytes).
pub fn isolux(
    values: &[f64],
    nx: usize,
    ny: usize,
    title: &str,
    unit: &str,
) -> (u32, u32, Vec<u8>) {
    let cell = (PICTURE / nx.max(ny)).max(CELL_MIN);
    let (gw, gh) = (nx * cell, ny * cell);
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let top = if hi > 0.0 { hi } else { 1.0 };
    let step = contour_step(hi - lo.min(hi));
    // the value at a picture pixel: bilinear between the cell centres, held at the borders
    let at = |x: usize, y: usize| -> f64 {
        let fx = ((x as f64 + 0.5) / cell as f64 - 0.5).clamp(0.0, (nx - 1) as f64);
        let fy = ((y as f64 + 0.5) / cell as f64 - 0.5).clamp(0.0, (ny - 1) as f64);
        let (i, j) =
            ((fx as usize).min(nx.saturating_sub(2)), (fy as usize).min(ny.saturating_sub(2)));
        let (tx, ty) = (fx - i as f64, fy - j as f64);
        let v = |i: usize, j: usize| values[j.min(ny - 1) * nx + i.min(nx - 1)];
        let top = v(i, j) + (v(i + 1, j) - v(i, j)) * tx;
        let bottom = v(i, j + 1) + (v(i + 1, j + 1) - v(i, j + 1)) * tx;
        top + (bottom - top) * ty
    };
    let field: Vec<f64> =
        (0..gh).flat_map(|y| (0..gw).map(move |x| (x, y))).map(|(x, y)| at(x, y)).collect();

    let margin = 8;
    let title_h = 7 + 2 * margin;
    let (bar_w, label_w) = (16, 6 * 9 + 6);
    let (w, h) =
        (margin + gw + margin + bar_w + margin / 2 + label_w, title_h + gh.max(120) + margin);
    let mut c = Canvas { w, h, rgb: vec![255; w * h * 3] };
    let (black, white) = ([0, 0, 0], [255, 255, 255]);
    c.text(margin, margin, &format!("{title} ({unit})"), 1, black);
    let level = |v: f64| (v / step).floor();
    for y in 0..gh {
        for x in 0..gw {
            let v = field[y * gw + x];
            let crosses = (x + 1 < gw && level(field[y * gw + x + 1]) != level(v))
                || (y + 1 < gh && level(field[(y + 1) * gw + x]) != level(v));
            let color = if crosses { black } else { ramp((v / top) as f32) };
            c.set(margin + x, title_h + y, color);
        }
    }
    // each cell's value at its centre, on a white patch so that it reads on any colour
    if cell >= 6 * 5 + 4 {
        for j in 0..ny {
            for i in 0..nx {
                let text = format_tick(values[j * nx + i]);
                let tw = text.chars().count() * 6;
                let (x0, y0) = (margin + i * cell + cell / 2, title_h + j * cell + cell / 2);
                let (x0, y0) = (x0.saturating_sub(tw / 2), y0.saturating_sub(4));
                for dy in 0..9 {
                    for dx in 0..tw + 2 {
                        c.set(x0 + dx - 1, y0 + dy - 1, white);
                    }
                }
                c.text(x0, y0, &text, 1, black);
            }
        }
    }
    // the scale: 0 to the maximum, the contour levels ticked
    let bar_x = margin + gw + margin;
    let bar_h = gh.max(120);
    for y in 0..bar_h {
        let t = 1.0 - y as f64 / (bar_h - 1).max(1) as f64;
        for x in 0..bar_w {
            c.set(bar_x + x, title_h + y, ramp(t as f32));
        }
    }
    let ticks = (top / step).floor() as usize;
    let every = ticks.div_ceil(8).max(1);
    for k in (0..=ticks).step_by(every) {
        let v = k as f64 * step;
        let y = title_h + ((1.0 - v / top) * (bar_h - 1) as f64) as usize;
        for x in 0..4 {
            c.set(bar_x + bar_w + x, y, black);
        }
        let ty = y.saturating_sub(3).clamp(title_h, title_h + bar_h - 7);
        c.text(bar_x + bar_w + 6, ty, &format_tick(v), 1, black);
    }
    (w as u32, h as u32, c.rgb)
}

/// Writes [`isolux`] as a PNG.
pub fn isolux_png(
    path: &Path,
    values: &[f64],
    nx: usize,
    ny: usize,
    title: &str,
    unit: &str,
) -> Result<(), String> {
    let (w, h, rgb) = isolux(values, nx, ny, title, unit);
    std::fs::write(path, encode_png_rgb8(w, h, &rgb))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contour_steps_are_round_and_give_four_to_eight_lines() {
        for (range, step) in [(1000.0, 200.0), (73.0, 10.0), (0.9, 0.2), (4.0, 0.5), (1e-3, 2e-4)] {
            let s = contour_step(range);
            assert!((s / step - 1.0).abs() < 1e-9, "range {range}: step {s}, want {step}");
            assert!((4.0..=8.0).contains(&(range / s)), "{range}: {} lines", range / s);
        }
    }

    #[test]
    fn contours_cross_a_ramp_where_its_value_crosses_the_levels() {
        // a ramp from 0 to 100 lx along x: contour columns where the value passes 20, 40, …
        let (nx, ny) = (11, 3);
        let values: Vec<f64> = (0..ny).flat_map(|_| (0..nx).map(|i| 10.0 * i as f64)).collect();
        let (w, h, rgb) = isolux(&values, nx, ny, "E", "lx");
        assert_eq!(rgb.len(), (w * h * 3) as usize);
        let row = 8 + 7 + 8 + 2; // first grid row, away from the labels
        let dark: Vec<usize> = (0..w as usize)
            .filter(|&x| {
                let i = 3 * (row * w as usize + x);
                rgb[i..i + 3] == [0, 0, 0]
            })
            .collect();
        // step 20 lx over 0–100: lines at 20, 40, 60, 80 (and none at the 100 lx border)
        assert!(dark.len() >= 4, "{dark:?}");
    }
}
