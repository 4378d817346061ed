//! Reading texture images: PNG (8 and 16 bit, grey, grey+alpha, RGB, RGBA, palette), JPEG
//! (baseline and progressive, grey or RGB), OpenEXR (the R, G, B channels of the first
//! layer that has them), Radiance RGBE `.hdr` (`rgbe.rs`), and the formats Mitsuba 3 also
//! reads: BMP, Targa (`.tga`), binary PPM (`P6`; Mitsuba 3.9.1 reads no other PNM) and PFM
//! (portable float map). The
//! format is recognised from the file's first bytes, as Mitsuba does, not from its extension;
//! Targa, which has no signature, from its `.tga` extension, as Mitsuba does.
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
    Bmp,
    Tga,
    /// Binary PPM.
    Pnm,
    /// Portable float map.
    Pfm,
}

impl ImageFormat {
    /// True for formats whose integer values are sRGB-encoded (all but EXR, RGBE and PFM,
    /// whose values are linear floats).
    pub fn is_srgb(&self) -> bool {
        !matches!(self, ImageFormat::Exr | ImageFormat::Rgbe | ImageFormat::Pfm)
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

/// Reads an image file of one of the module's formats. Errors name the file and the problem.
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
    } else if magic.starts_with(b"BM") {
        read_with_image_crate(path, image::ImageFormat::Bmp, ImageFormat::Bmp).map_err(err)
    } else if magic.starts_with(b"PF") || magic.starts_with(b"Pf") {
        let bytes = std::fs::read(path).map_err(|e| err(e.to_string()))?;
        decode_pfm(&bytes).map_err(err)
    } else if magic.starts_with(b"P6") {
        read_with_image_crate(path, image::ImageFormat::Pnm, ImageFormat::Pnm).map_err(err)
    } else if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("tga")) {
        read_with_image_crate(path, image::ImageFormat::Tga, ImageFormat::Tga).map_err(err)
    } else {
        Err(err("not a PNG, JPEG, OpenEXR, Radiance RGBE, BMP, Targa (.tga), binary PPM or PFM \
                 file (the formats steradian reads, as Mitsuba 3 does)"
            .into()))
    }
}

/// A BMP, Targa or PPM image through the `image` crate: grey or RGB, normalised to [0, 1]
/// (still sRGB-encoded), alpha dropped.
fn read_with_image_crate(
    path: &Path,
    format: image::ImageFormat,
    ours: ImageFormat,
) -> Result<LoadedImage, String> {
    let file = File::open(path).map_err(|e| e.to_string())?;
    let img = image::ImageReader::with_format(BufReader::new(file), format)
        .decode()
        .map_err(|e| e.to_string())?;
    let (width, height) = (img.width() as usize, img.height() as usize);
    let (channels, data) = if img.color().has_color() {
        (3, img.to_rgb32f().into_raw())
    } else {
        (1, img.to_luma32f().into_raw())
    };
    Ok(LoadedImage { width, height, channels, data, format: ours })
}

/// A portable float map: `PF` (RGB) or `Pf` (grey), the width and height, a scale whose sign
/// gives the byte order (negative: little-endian), then 32-bit floats row by row from the
/// bottom of the picture up.
fn decode_pfm(bytes: &[u8]) -> Result<LoadedImage, String> {
    // the header: three white-space separated tokens after the magic, then one white-space
    // byte before the data
    let mut at = 2;
    let mut token = || -> Result<String, String> {
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while at < bytes.len() && !bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        String::from_utf8(bytes[start..at].to_vec()).map_err(|_| "PFM header is not text".into())
    };
    let channels = if bytes.starts_with(b"PF") { 3 } else { 1 };
    let (w, h, scale) = (token()?, token()?, token()?);
    let width: usize = w.parse().map_err(|_| format!("PFM width \"{w}\" is not a number"))?;
    let height: usize = h.parse().map_err(|_| format!("PFM height \"{h}\" is not a number"))?;
    let scale: f32 = scale.parse().map_err(|_| format!("PFM scale \"{scale}\" is not a number"))?;
    if width == 0 || height == 0 {
        return Err(format!("PFM image of {width}×{height} pixels"));
    }
    let data_start = at + 1;
    let n = width.checked_mul(height).and_then(|p| p.checked_mul(channels));
    let end = n.and_then(|n| n.checked_mul(4)).and_then(|b| b.checked_add(data_start));
    let (Some(n), Some(end)) = (n, end) else { return Err("PFM image too large".into()) };
    if bytes.len() < end {
        return Err(format!("PFM data ends early ({} of {} bytes)", bytes.len(), end));
    }
    let word = |i: usize| {
        let b: [u8; 4] =
            bytes[data_start + 4 * i..data_start + 4 * i + 4].try_into().unwrap_or([0; 4]);
        if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let mut data = vec![0.0f32; n];
    let row = width * channels;
    for y in 0..height {
        // file row y is picture row height − 1 − y
        let dst = (height - 1 - y) * row;
        for i in 0..row {
            data[dst + i] = word(y * row + i);
        }
    }
    Ok(LoadedImage { width, height, channels, data, format: ImageFormat::Pfm })
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

    /// PFM rows run from the bottom of the picture up; the sign of the scale gives the byte
    /// order; BMP and PPM (through the `image` crate) keep 8-bit values as they are.
    #[test]
    fn pfm_bmp_and_ppm() {
        let dir = temp_dir("texture-image-pfm-bmp-ppm");
        // 1 × 2 grey: the file's first row (0.25) is the picture's bottom row
        let mut le = b"Pf\n1 2\n-1.0\n".to_vec();
        le.extend(0.25f32.to_le_bytes());
        le.extend(0.75f32.to_le_bytes());
        let p = dir.join("le.pfm");
        std::fs::write(&p, &le).unwrap();
        let img = read_image(&p).unwrap();
        assert_eq!((img.width, img.height, img.channels, img.format), (1, 2, 1, ImageFormat::Pfm));
        assert_eq!(img.data, vec![0.75, 0.25]);
        let mut be = b"PF 1 1 1.0 ".to_vec();
        for v in [1.5f32, 2.0, 4.0] {
            be.extend(v.to_be_bytes());
        }
        let p = dir.join("be.pfm");
        std::fs::write(&p, &be).unwrap();
        assert_eq!(read_image(&p).unwrap().data, vec![1.5, 2.0, 4.0]);
        assert!(!ImageFormat::Pfm.is_srgb() && ImageFormat::Bmp.is_srgb());
        // a 2 × 1 binary PPM
        let p = dir.join("two.ppm");
        std::fs::write(&p, b"P6\n2 1\n255\n\xff\x00\x33\x00\x66\x00").unwrap();
        let img = read_image(&p).unwrap();
        assert_eq!((img.width, img.height, img.channels, img.format), (2, 1, 3, ImageFormat::Pnm));
        assert_eq!(img.data, vec![1.0, 0.0, 0.2, 0.0, 0.4, 0.0]);
        // a 1 × 2 24-bit BMP (rows bottom up, BGR, padded to 4 bytes): top red, bottom blue
        let mut bmp = b"BM".to_vec();
        let pixels: [u8; 8] = [255, 0, 0, 0, 0, 0, 255, 0];
        let size = 14 + 40 + pixels.len() as u32;
        bmp.extend(size.to_le_bytes());
        bmp.extend([0u8; 4]);
        bmp.extend(54u32.to_le_bytes());
        bmp.extend(40u32.to_le_bytes());
        bmp.extend(1i32.to_le_bytes());
        bmp.extend(2i32.to_le_bytes());
        bmp.extend(1u16.to_le_bytes());
        bmp.extend(24u16.to_le_bytes());
        bmp.extend([0u8; 24]);
        bmp.extend(pixels);
        let p = dir.join("two.bmp");
        std::fs::write(&p, &bmp).unwrap();
        let img = read_image(&p).unwrap();
        assert_eq!((img.width, img.height, img.channels, img.format), (1, 2, 3, ImageFormat::Bmp));
        assert_eq!(img.data, vec![1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
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
        assert!(read_image(&p).unwrap_err().contains("not a PNG, JPEG, OpenEXR, Radiance RGBE"));
        // a PFM whose data ends early, an ASCII PPM (which Mitsuba does not read either)
        let p = dir.join("short.pfm");
        std::fs::write(&p, b"PF\n2 2\n-1.0\n\0\0\0\0").unwrap();
        assert!(read_image(&p).unwrap_err().contains("PFM data ends early"));
        let p = dir.join("ascii.ppm");
        std::fs::write(&p, "P3\n1 1\n255\n1 2 3\n").unwrap();
        assert!(read_image(&p).unwrap_err().contains("ascii.ppm"));
        let p = dir.join("truncated.hdr");
        std::fs::write(&p, "#?RADIANCE\n\n-Y 2 +X 2\n\x01").unwrap();
        let e = read_image(&p).unwrap_err();
        assert!(e.contains("truncated.hdr") && e.contains("truncated RGBE"), "{e}");
    }
}
