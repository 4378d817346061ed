//! 8-bit sRGB PNG previews of linear images.
//!
//! A preview is lossy by design: each linear value is multiplied by an exposure scale, clamped
//! to [0, 1], encoded with the sRGB OETF (12.92·x for x ≤ 0.0031308, else
//! 1.055·x^(1/2.4) − 0.055) and rounded to 8 bits. NaN encodes as 0. Files carry an sRGB chunk.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use super::image::Image;

/// sRGB-encodes one linear value (after clamping to [0, 1]) to 8 bits, rounding to nearest.
#[inline]
pub fn srgb_encode_u8(linear: f32) -> u8 {
    let x = if linear.is_nan() { 0.0 } else { linear.clamp(0.0, 1.0) };
    let v = if x <= 0.0031308 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
    (v * 255.0).round().clamp(0.0, 255.0) as u8
}

fn encode_to<W: std::io::Write>(
    writer: W,
    width: u32,
    height: u32,
    rgb: &[u8],
) -> Result<(), String> {
    if rgb.len() != 3 * width as usize * height as usize {
        return Err(format!(
            "{width}x{height} RGB8 needs {} bytes, got {}",
            3 * width as usize * height as usize,
            rgb.len()
        ));
    }
    let mut enc = ::png::Encoder::new(writer, width, height);
    enc.set_color(::png::ColorType::Rgb);
    enc.set_depth(::png::BitDepth::Eight);
    enc.set_source_srgb(::png::SrgbRenderingIntent::Perceptual);
    let mut w = enc.write_header().map_err(|e| e.to_string())?;
    w.write_image_data(rgb).map_err(|e| e.to_string())?;
    w.finish().map_err(|e| e.to_string())
}

/// Encodes 8-bit RGB data (row-major, top row first) as a PNG file in memory.
/// Panics if `rgb.len() != 3·width·height` or the size is zero.
pub fn encode_png_rgb8(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    encode_to(&mut out, width, height, rgb).expect("encode_png_rgb8: invalid input");
    out
}

/// Writes an 8-bit sRGB preview of `image`, each value multiplied by `exposure_scale` first.
pub fn write_png(path: &Path, image: &Image, exposure_scale: f32) -> Result<(), String> {
    let err = |msg: String| format!("cannot write PNG {}: {msg}", path.display());
    if image.data.len() != 3 * image.pixel_count() {
        return Err(err("image data length does not match its size".into()));
    }
    let rgb: Vec<u8> = image.data.iter().map(|&v| srgb_encode_u8(v * exposure_scale)).collect();
    let file = File::create(path).map_err(|e| err(e.to_string()))?;
    encode_to(BufWriter::new(file), image.width, image.height, &rgb).map_err(err)
}

/// Reads a PNG as 8-bit RGB: `(width, height, data)` with data row-major, top row first.
/// Grey is replicated, alpha dropped, 16-bit and palette images converted to 8-bit RGB.
pub fn read_png_rgb8(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let err = |msg: String| format!("cannot read PNG {}: {msg}", path.display());
    let file = File::open(path).map_err(|e| err(e.to_string()))?;
    let mut dec = ::png::Decoder::new(std::io::BufReader::new(file));
    dec.set_transformations(::png::Transformations::normalize_to_color8());
    let mut reader = dec.read_info().map_err(|e| err(e.to_string()))?;
    let mut buf = vec![0u8; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).map_err(|e| err(e.to_string()))?;
    let (w, h) = (info.width, info.height);
    let n = w as usize * h as usize;
    let channels = match info.color_type {
        ::png::ColorType::Grayscale => 1,
        ::png::ColorType::GrayscaleAlpha => 2,
        ::png::ColorType::Rgb => 3,
        ::png::ColorType::Rgba => 4,
        other => return Err(err(format!("unsupported colour type {other:?}"))),
    };
    let mut out = Vec::with_capacity(3 * n);
    for row in buf.chunks(info.line_size).take(h as usize) {
        for px in row[..w as usize * channels].chunks_exact(channels) {
            match channels {
                1 | 2 => out.extend([px[0]; 3]),
                _ => out.extend(&px[..3]),
            }
        }
    }
    Ok((w, h, out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::temp_dir;
    use crate::Spectrum;

    #[test]
    fn srgb_known_values() {
        assert_eq!(srgb_encode_u8(0.0), 0);
        assert_eq!(srgb_encode_u8(1.0), 255);
        assert_eq!(srgb_encode_u8(0.5), 188);
        assert_eq!(srgb_encode_u8(-3.0), 0);
        assert_eq!(srgb_encode_u8(7.0), 255);
        assert_eq!(srgb_encode_u8(f32::NAN), 0);
        // Linear segment: 0.002 → 12.92·0.002·255 = 6.59 → 7.
        assert_eq!(srgb_encode_u8(0.002), 7);
        // 0.18 (mid grey) → 1.055·0.18^(1/2.4) − 0.055 = 0.4614 → 117.7 → 118.
        let v = 1.055 * 0.18f64.powf(1.0 / 2.4) - 0.055;
        assert_eq!(srgb_encode_u8(0.18), (v * 255.0).round() as u8);
        // Monotone.
        let mut prev = 0;
        for i in 0..=1000 {
            let e = srgb_encode_u8(i as f32 / 1000.0);
            assert!(e >= prev);
            prev = e;
        }
    }

    #[test]
    fn png_round_trip() {
        let dir = temp_dir("film-png-png-round-trip");
        let mut img = Image::new(3, 2);
        img.set(0, 0, Spectrum::new(0.0, 0.5, 1.0));
        img.set(1, 0, Spectrum::new(0.25, 0.25, 0.25));
        img.set(2, 1, Spectrum::new(2.0, -1.0, 0.1));
        let p = dir.join("rt.png");
        write_png(&p, &img, 2.0).unwrap();
        let (w, h, data) = read_png_rgb8(&p).unwrap();
        assert_eq!((w, h), (3, 2));
        let want: Vec<u8> = img.data.iter().map(|&v| srgb_encode_u8(v * 2.0)).collect();
        assert_eq!(data, want);
        // With scale 2: 0.5 → 1.0 → 255, 0.25 → 0.5 → 188.
        assert_eq!(&data[0..6], &[0, 255, 255, 188, 188, 188]);
        // In-memory encoder gives a decodable PNG too.
        let bytes = encode_png_rgb8(3, 2, &want);
        let q = dir.join("mem.png");
        std::fs::write(&q, bytes).unwrap();
        assert_eq!(read_png_rgb8(&q).unwrap().2, want);
        assert!(read_png_rgb8(&dir.join("missing.png")).unwrap_err().contains("missing.png"));
        std::fs::remove_file(p).ok();
        std::fs::remove_file(q).ok();
    }
}
