//! False-colour previews of scalar maps (irradiance, illuminance) with a labelled colour
//! scale, for reading light levels off an image.
//!
//! The scale is linear from 0 to the 99.5th percentile of the map (so a few very bright
//! pixels do not wash it out); values above it are drawn in the top colour. Colours follow a
//! perceptually ordered dark-blue → green → yellow ramp (viridis-like).

use std::path::Path;

use super::{encode_png_rgb8, Image};

/// Viridis control points (0, 0.25, 0.5, 0.75, 1), sRGB 8-bit.
const RAMP: [[f32; 3]; 5] = [
    [68.0, 1.0, 84.0],
    [59.0, 82.0, 139.0],
    [33.0, 145.0, 140.0],
    [94.0, 201.0, 98.0],
    [253.0, 231.0, 37.0],
];

pub(super) fn ramp(t: f32) -> [u8; 3] {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * 4.0;
    let i = (x as usize).min(3);
    let f = x - i as f32;
    let (a, b) = (RAMP[i], RAMP[i + 1]);
    [0, 1, 2].map(|c| (a[c] + (b[c] - a[c]) * f).round() as u8)
}

/// 5×7 glyphs, one byte per row (low 5 bits, MSB = left column).
fn glyph(c: char) -> [u8; 7] {
    match c {
        '0' => [14, 17, 19, 21, 25, 17, 14],
        '1' => [4, 12, 4, 4, 4, 4, 14],
        '2' => [14, 17, 1, 2, 4, 8, 31],
        '3' => [31, 2, 4, 2, 1, 17, 14],
        '4' => [2, 6, 10, 18, 31, 2, 2],
        '5' => [31, 16, 30, 1, 1, 17, 14],
        '6' => [6, 8, 16, 30, 17, 17, 14],
        '7' => [31, 1, 2, 4, 8, 8, 8],
        '8' => [14, 17, 17, 14, 17, 17, 14],
        '9' => [14, 17, 17, 15, 1, 2, 12],
        '.' => [0, 0, 0, 0, 0, 12, 12],
        '+' => [0, 4, 4, 31, 4, 4, 0],
        '-' => [0, 0, 0, 31, 0, 0, 0],
        '/' => [1, 1, 2, 4, 8, 16, 16],
        '²' => [12, 2, 4, 14, 0, 0, 0],
        'W' => [17, 17, 17, 21, 21, 21, 10],
        'a' => [0, 0, 14, 1, 15, 17, 15],
        'c' => [0, 0, 14, 16, 16, 17, 14],
        'd' => [1, 1, 13, 19, 17, 17, 15],
        'e' => [0, 0, 14, 17, 31, 16, 14],
        'i' => [4, 0, 12, 4, 4, 4, 14],
        'l' => [12, 4, 4, 4, 4, 4, 14],
        'm' => [0, 0, 26, 21, 21, 17, 17],
        'n' => [0, 0, 22, 25, 17, 17, 17],
        'r' => [0, 0, 22, 25, 16, 16, 16],
        'u' => [0, 0, 17, 17, 17, 19, 13],
        'x' => [0, 0, 17, 10, 4, 10, 17],
        '(' => [2, 4, 8, 8, 8, 4, 2],
        ')' => [8, 4, 2, 2, 2, 4, 8],
        _ => [0; 7],
    }
}

/// An sRGB picture being drawn.
pub(super) struct Canvas {
    pub w: usize,
    pub h: usize,
    pub rgb: Vec<u8>,
}

impl Canvas {
    pub fn set(&mut self, x: usize, y: usize, c: [u8; 3]) {
        if x < self.w && y < self.h {
            let i = 3 * (y * self.w + x);
            self.rgb[i..i + 3].copy_from_slice(&c);
        }
    }

    /// Draws `text` with its top-left corner at (x, y), each font pixel `scale`² pixels.
    pub fn text(&mut self, x: usize, y: usize, text: &str, scale: usize, color: [u8; 3]) {
        for (k, ch) in text.chars().enumerate() {
            let g = glyph(ch);
            for (row, bits) in g.iter().enumerate() {
                for col in 0..5 {
                    if bits & (16 >> col) != 0 {
                        for dy in 0..scale {
                            for dx in 0..scale {
                                self.set(
                                    x + (k * 6 + col) * scale + dx,
                                    y + row * scale + dy,
                                    color,
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The value of a scalar map at each pixel: the mean of the three channels.
fn scalar(image: &Image) -> Vec<f32> {
    image.data.chunks_exact(3).map(|p| (p[0] + p[1] + p[2]) / 3.0).collect()
}

/// A tick label: 3 significant digits, scientific notation outside [0.01, 10⁴).
pub fn format_tick(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (0.01..10_000.0).contains(&v.abs()) {
        let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.2e}").replace("e", "e+").replace("e+-", "e-")
    }
}

/// Renders the map (mean of channels) in false colour with a scale bar titled
/// `title (unit)` and five labelled ticks, and returns (width, height, sRGB bytes).
pub fn false_color(image: &Image, title: &str, unit: &str) -> (u32, u32, Vec<u8>) {
    let values = scalar(image);
    let mut sorted: Vec<f32> = values.iter().copied().filter(|v| v.is_finite()).collect();
    sorted.sort_by(|a, b| a.total_cmp(b));
    let top = sorted
        .get(((sorted.len() as f64 * 0.995) as usize).min(sorted.len().saturating_sub(1)))
        .copied()
        .unwrap_or(1.0);
    let top =
        if top > 0.0 { top } else { sorted.last().copied().filter(|v| *v > 0.0).unwrap_or(1.0) };

    let (iw, ih) = (image.width as usize, image.height as usize);
    let scale = if ih >= 400 { 2 } else { 1 };
    let bar_w = 16 * scale;
    let label_w = 6 * 8 * scale + 6 * scale;
    let margin = 8 * scale;
    let title_h = 7 * scale + 2 * margin;
    let w = iw + margin + bar_w + margin / 2 + label_w;
    let h = ih.max(120) + title_h;
    let mut c = Canvas { w, h, rgb: vec![255; w * h * 3] };
    let black = [0, 0, 0];

    for y in 0..ih {
        for x in 0..iw {
            c.set(x, y + title_h, ramp(values[y * iw + x] / top));
        }
    }
    c.text(margin / 2, margin, &format!("{title} ({unit})"), scale, black);

    // the bar, value increasing upwards, and ticks at 0, ¼, ½, ¾, 1 of the range
    let bar_x = iw + margin;
    let (bar_top, bar_h) = (title_h, ih.max(120));
    for y in 0..bar_h {
        let t = 1.0 - y as f32 / (bar_h - 1).max(1) as f32;
        for x in 0..bar_w {
            c.set(bar_x + x, bar_top + y, ramp(t));
        }
    }
    for k in 0..=4 {
        let t = k as f32 / 4.0;
        let y = bar_top + ((1.0 - t) * (bar_h - 1) as f32) as usize;
        for x in 0..(4 * scale) {
            c.set(bar_x + bar_w + x, y, black);
        }
        let ty = y.saturating_sub(3 * scale).clamp(bar_top, bar_top + bar_h - 7 * scale);
        c.text(bar_x + bar_w + 6 * scale, ty, &format_tick((top * t) as f64), scale, black);
    }
    (w as u32, h as u32, c.rgb)
}

/// Writes [`false_color`] as a PNG.
pub fn false_color_png(path: &Path, image: &Image, title: &str, unit: &str) -> Result<(), String> {
    let (w, h, rgb) = false_color(image, title, unit);
    std::fs::write(path, encode_png_rgb8(w, h, &rgb))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_readable() {
        assert_eq!(format_tick(0.0), "0");
        assert_eq!(format_tick(12.345), "12.3");
        assert_eq!(format_tick(0.5), "0.500");
        assert_eq!(format_tick(250000.0), "2.50e+5");
        assert_eq!(format_tick(0.001), "1.00e-3");
    }

    #[test]
    fn ramp_is_monotonic_in_brightness_and_maps_the_map() {
        let lum = |c: [u8; 3]| 0.2126 * c[0] as f32 + 0.7152 * c[1] as f32 + 0.0722 * c[2] as f32;
        let mut last = -1.0;
        for i in 0..=20 {
            let l = lum(ramp(i as f32 / 20.0));
            assert!(l > last);
            last = l;
        }
        let mut img = Image::new(4, 2);
        img.set(3, 1, crate::Spectrum::splat(2.0));
        let (w, h, rgb) = false_color(&img, "irradiance", "W/m²");
        assert_eq!(rgb.len(), (w * h * 3) as usize);
        assert!(w > 4 && h >= 120);
    }
}
