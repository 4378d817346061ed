//! Reading texture images: PNG (8 and 16 bit, grey, grey+alpha, RGB, RGBA, palette), JPEG
//! (baseline and progressive, grey or RGB), OpenEXR (the R, G, B channels of the first
//! layer that has them) and Radiance RGBE `.hdr` (`rgbe.rs`). The format is recognised from the file's first bytes, as Mitsuba
//! does, not from its extension.
//!
//! Integer images come back normalised to [0, 1] and still sRGB-encoded (the caller decides
//! whether to linearise, see `bitmap`'s `raw`); EXR and RGBE values are linear. An alpha channel is
//! dropped, as Mitsuba's `bitmap` converts Y·A to Y and RGBA to RGB without premultiplying.

use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

/// The file format an image was stored in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Jpeg,
    Exr,
    Rgbe,
}

impl ImageFormat {
    /// True for formats whose integer values are sRGB-encoded (everything but EXR and RGBE).
    pub fn is_srgb(&self) -> bool {
        !matches!(self, ImageFormat::Exr | ImageFormat::Rgbe)
    }
}

/// Pixels of an image file, row 0 at the top of the picture.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedImage {
    pub width: usize,
    pub height: usize,
    /// 1 (grey) or 3 (RGB).
    pub channels: usize,
    /// `width · height · channels` values, row-major.
    pub data: Vec<f32>,
    pub format: ImageFormat,
}

/// Reads a PNG, JPEG, EXR or RGBE file. Errors name the file and the problem.
pub fn read_image(path: &Path) -> Result<LoadedImage, String> {
    let err = |msg: String| format!("cannot read image \"{}\": {msg}", path.display());
    let mut file = File::open(path).map_err(|e| err(e.to_string()))?;
    let mut magic = [0u8; 4];
    let n = file.read(&mut magic).map_err(|e| err(e.to_string()))?;
    drop(file);
    let magic = &magic[..n];
    if magic.starts_with(&[0x89, b'P', b'N', b'G']) {
        read_png(path).map_err(err)
    } else if magic.starts_with(&[0xFF, 0xD8]) {
        read_jpeg(path).map_err(err)
    } else if magic.starts_with(&[0x76, 0x2F, 0x31, 0x01]) {
        let img = crate::film::read_exr(path)?;
        Ok(LoadedImage {
            width: img.width as usize,
            height: img.height as usize,
            channels: 3,
            data: img.data,
            format: ImageFormat::Exr,
        })
    } else if magic.starts_with(b"#?") {
        let bytes = std::fs::read(path).map_err(|e| err(e.to_string()))?;
        let (width, height, data) = super::rgbe::decode_rgbe(&bytes).map_err(err)?;
        Ok(LoadedImage { width, height, channels: 3, data, format: ImageFormat::Rgbe })
    } else {
        Err(err(
            "not a PNG, JPEG, OpenEXR or Radiance RGBE file (steradian reads these four formats)"
                .into(),
        ))
    }
}

fn read_png(path: &Path) -> Result<LoadedImage, String> {
    let file = File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = png::Decoder::new(BufReader::new(file));
    // palette → RGB, tRNS → alpha, 1/2/4-bit grey → 8 bit
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let mut buf = vec![0u8; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    let (width, height) = (info.width as usize, info.height as usize);
    let stored = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err("palette image was not expanded".into()),
    };
    let values: Vec<f32> = match info.bit_depth {
        png::BitDepth::Sixteen => buf[..info.buffer_size()]
            .chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]) as f32 / 65535.0)
            .collect(),
        _ => buf[..info.buffer_size()].iter().map(|&b| b as f32 / 255.0).collect(),
    };
    Ok(drop_alpha(width, height, stored, values, ImageFormat::Png))
}

fn read_jpeg(path: &Path) -> Result<LoadedImage, String> {
    let file = File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = jpeg_decoder::Decoder::new(BufReader::new(file));
    let pixels = decoder.decode().map_err(|e| e.to_string())?;
    let info = decoder.info().ok_or("JPEG without a frame header")?;
    let (width, height) = (info.width as usize, info.height as usize);
    let (channels, values): (usize, Vec<f32>) = match info.pixel_format {
        jpeg_decoder::PixelFormat::L8 => (1, pixels.iter().map(|&b| b as f32 / 255.0).collect()),
        jpeg_decoder::PixelFormat::L16 => (
            1,
            pixels
                .chunks_exact(2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]) as f32 / 65535.0)
                .collect(),
        ),
        jpeg_decoder::PixelFormat::RGB24 => (3, pixels.iter().map(|&b| b as f32 / 255.0).collect()),
        jpeg_decoder::PixelFormat::CMYK32 => {
            return Err("CMYK JPEG images are not supported".into())
        }
    };
    if values.len() != width * height * channels {
        return Err(format!("decoded {} values for a {width}×{height} image", values.len()));
    }
    Ok(LoadedImage { width, height, channels, data: values, format: ImageFormat::Jpeg })
}

/// Keeps the colour channels of interleaved pixels with `stored` channels (1 to 4).
fn drop_alpha(
    width: usize,
    height: usize,
    stored: usize,
    values: Vec<f32>,
    format: ImageFormat,
) -> LoadedImage {
    let channels = if stored >= 3 { 3 } else { 1 };
    let data = if stored == channels {
        values
    } else {
        values.chunks_exact(stored).flat_map(|p| p[..channels].to_vec()).collect()
    };
    LoadedImage { width, height, channels, data, format }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::temp_dir;

    fn write_png(
        path: &Path,
        w: u32,
        h: u32,
        color: png::ColorType,
        depth: png::BitDepth,
        data: &[u8],
    ) {
        let file = File::create(path).unwrap();
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        enc.write_header().unwrap().write_image_data(data).unwrap();
    }

    #[test]
    fn png_variants_and_alpha() {
        let dir = temp_dir("texture-image-png-variants-and-alpha");
        let p = dir.join("rgba.png");
        write_png(
            &p,
            2,
            1,
            png::ColorType::Rgba,
            png::BitDepth::Eight,
            &[255, 0, 51, 7, 0, 102, 0, 255],
        );
        let img = read_image(&p).unwrap();
        assert_eq!((img.width, img.height, img.channels, img.format), (2, 1, 3, ImageFormat::Png));
        assert_eq!(img.data, vec![1.0, 0.0, 0.2, 0.0, 0.4, 0.0]);
        let p = dir.join("grey16.png");
        write_png(
            &p,
            1,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &[0xFF, 0xFF, 0x80, 0x00],
        );
        let img = read_image(&p).unwrap();
        assert_eq!((img.channels, img.data.len()), (1, 2));
        assert!((img.data[1] - 32768.0 / 65535.0).abs() < 1e-7 && img.data[0] == 1.0);
    }

    #[test]
    fn errors_name_the_file() {
        let dir = temp_dir("texture-image-errors-name-the-file");
        let e = read_image(&dir.join("missing.png")).unwrap_err();
        assert!(e.contains("missing.png"), "{e}");
        let p = dir.join("corrupt.png");
        std::fs::write(&p, [0x89, b'P', b'N', b'G', 1, 2, 3]).unwrap();
        let e = read_image(&p).unwrap_err();
        assert!(e.contains("corrupt.png"), "{e}");
        let p = dir.join("corrupt.jpg");
        std::fs::write(&p, [0xFF, 0xD8, 0xFF, 0x00, 9, 9]).unwrap();
        assert!(read_image(&p).unwrap_err().contains("corrupt.jpg"));
        let p = dir.join("text.png");
        std::fs::write(&p, "hello").unwrap();
        assert!(read_image(&p).unwrap_err().contains("not a PNG, JPEG, OpenEXR or Radiance"));
        let p = dir.join("truncated.hdr");
        std::fs::write(&p, "#?RADIANCE\n\n-Y 2 +X 2\n\x01").unwrap();
        let e = read_image(&p).unwrap_err();
        assert!(e.contains("truncated.hdr") && e.contains("truncated RGBE"), "{e}");
    }
}
