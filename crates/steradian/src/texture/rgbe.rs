//! Reading Radiance `.hdr` (RGBE) images.
//!
//! The header starts with `#?` (`#?RADIANCE`, `#?RGBE`), holds `NAME=value` lines up to an
//! empty line (`FORMAT` must be `32-bit_rle_rgbe`; `32-bit_rle_xyze` is refused), then the
//! resolution line `-Y height +X width` (rows stored top to bottom, the only orientation
//! Mitsuba 3 reads too). Each scanline is stored in one of three ways, told apart per
//! scanline as Radiance does:
//! - flat: one 4-byte (R, G, B, E) pixel after another;
//! - old run-length: a pixel (1, 1, 1, n) repeats the previous pixel n·256ᵏ times, where k counts
//!   the repeat pixels directly before it;
//! - new run-length (widths 8 to 32767): the bytes (2, 2, width/256, width%256), then each of the
//!   four components for the whole scanline as runs (count byte > 128: the next byte repeated
//!   count − 128 times) and literals (count byte ≤ 128: that many bytes).
//!
//! A pixel decodes to c·2^(E − 136) per channel (0 when E = 0), without Radiance's half-step
//! offset (c + ½): the values Mitsuba 3 reads (checked with its `Bitmap` on the same file).
//! `EXPOSURE` and other header lines are ignored, as Mitsuba does. Truncated or malformed data
//! is an error naming what is wrong; nothing panics.

/// The widest image read (a scanline buffer of 4 bytes per pixel).
const MAX_WIDTH: usize = 1 << 20;

/// Decodes an RGBE file's bytes: (width, height, RGB values row-major, row 0 at the top).
pub fn decode_rgbe(bytes: &[u8]) -> Result<(usize, usize, Vec<f32>), String> {
    if !bytes.starts_with(b"#?") {
        return Err("not a Radiance RGBE file (no '#?' signature)".into());
    }
    let mut pos = 0usize;
    let next_line = |pos: &mut usize| -> Result<&[u8], String> {
        let rest = &bytes[*pos..];
        let end = rest
            .iter()
            .position(|&b| b == b'\n')
            .ok_or("truncated RGBE header (no end of line)")?;
        *pos += end + 1;
        Ok(&rest[..end])
    };
    next_line(&mut pos)?; // signature
    loop {
        let line = next_line(&mut pos)?;
        let line = String::from_utf8_lossy(line);
        let line = line.trim();
        if line.is_empty() {
            break;
        }
        if let Some(format) = line.strip_prefix("FORMAT=") {
            if format != "32-bit_rle_rgbe" {
                return Err(format!(
                    "RGBE FORMAT \"{format}\" is not supported (only 32-bit_rle_rgbe)"
                ));
            }
        }
    }
    let res = String::from_utf8_lossy(next_line(&mut pos)?).to_string();
    let fields: Vec<&str> = res.split_whitespace().collect();
    let (height, width) = match fields.as_slice() {
        ["-Y", h, "+X", w] => (
            h.parse::<usize>().map_err(|_| format!("bad RGBE resolution line \"{res}\""))?,
            w.parse::<usize>().map_err(|_| format!("bad RGBE resolution line \"{res}\""))?,
        ),
        _ => {
            return Err(format!(
                "RGBE resolution line \"{}\" is not supported (only \"-Y height +X width\")",
                res.trim()
            ))
        }
    };
    if width == 0 || height == 0 {
        return Err(format!("RGBE image has no pixels ({width}×{height})"));
    }
    if width > MAX_WIDTH {
        return Err(format!("RGBE image {width} pixels wide (steradian reads up to {MAX_WIDTH})"));
    }
    // decoded row by row, so that a header claiming more rows than the data holds fails at
    // the first missing row instead of allocating the whole claimed image
    let mut reader = Reader { data: &bytes[pos..], pos: 0 };
    let mut row = vec![[0u8; 4]; width];
    let mut out = Vec::new();
    for _ in 0..height {
        reader.scanline(&mut row)?;
        for p in &row {
            let f = if p[3] == 0 { 0.0 } else { (2.0f32).powi(p[3] as i32 - 136) };
            out.extend([p[0] as f32 * f, p[1] as f32 * f, p[2] as f32 * f]);
        }
    }
    Ok((width, height, out))
}

struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn byte(&mut self) -> Result<u8, String> {
        let b = *self.data.get(self.pos).ok_or("truncated RGBE pixel data")?;
        self.pos += 1;
        Ok(b)
    }

    fn pixel(&mut self) -> Result<[u8; 4], String> {
        Ok([self.byte()?, self.byte()?, self.byte()?, self.byte()?])
    }

    fn scanline(&mut self, row: &mut [[u8; 4]]) -> Result<(), String> {
        let width = row.len();
        if !(8..=0x7fff).contains(&width) {
            return self.old_scanline(row, 0);
        }
        let first = self.pixel()?;
        if first[0] != 2 || first[1] != 2 || first[2] & 0x80 != 0 {
            row[0] = first;
            return self.old_scanline(row, 1);
        }
        let stated = ((first[2] as usize) << 8) | first[3] as usize;
        if stated != width {
            return Err(format!("RGBE scanline of width {stated} in an image {width} wide"));
        }
        for c in 0..4 {
            let mut x = 0;
            while x < width {
                let count = self.byte()? as usize;
                if count > 128 {
                    let n = count - 128;
                    let v = self.byte()?;
                    if x + n > width {
                        return Err("RGBE run overruns its scanline".into());
                    }
                    row[x..x + n].iter_mut().for_each(|p| p[c] = v);
                    x += n;
                } else {
                    if count == 0 || x + count > width {
                        return Err("bad RGBE scanline data".into());
                    }
                    for p in &mut row[x..x + count] {
                        p[c] = self.byte()?;
                    }
                    x += count;
                }
            }
        }
        Ok(())
    }

    /// Flat pixels with old-style repeats, from pixel `start` on.
    fn old_scanline(&mut self, row: &mut [[u8; 4]], start: usize) -> Result<(), String> {
        let mut x = start;
        let mut shift = 0u32;
        while x < row.len() {
            let p = self.pixel()?;
            if p[0] == 1 && p[1] == 1 && p[2] == 1 {
                if x == 0 {
                    return Err("RGBE repeat with no pixel before it".into());
                }
                let n = (p[3] as usize).checked_shl(shift).filter(|_| shift < 32).unwrap_or(0);
                if n == 0 || x + n > row.len() {
                    return Err("RGBE repeat overruns its scanline".into());
                }
                let prev = row[x - 1];
                row[x..x + n].fill(prev);
                x += n;
                shift += 8;
            } else {
                row[x] = p;
                x += 1;
                shift = 0;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &[u8] = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2.0\n\n";

    fn file(res: &str, data: &[u8]) -> Vec<u8> {
        let mut v = HEADER.to_vec();
        v.extend_from_slice(res.as_bytes());
        v.push(b'\n');
        v.extend_from_slice(data);
        v
    }

    #[test]
    fn flat_pixels_decode_as_mitsuba_reads_them() {
        // values printed by Mitsuba 3.9.1's Bitmap for this file
        let f = file("-Y 1 +X 2", &[128, 64, 32, 129, 255, 0, 1, 120]);
        let (w, h, v) = decode_rgbe(&f).unwrap();
        assert_eq!((w, h), (2, 1));
        assert_eq!(v, vec![1.0, 0.5, 0.25, 255.0 / 65536.0, 0.0, 1.0 / 65536.0]);
    }

    #[test]
    fn both_run_length_encodings() {
        // new RLE, width 8: R = run of 8 × 10; G literal 1..8; B run 5 × 0 + literal 3; E run 8 × 130
        let mut d = vec![2, 2, 0, 8];
        d.extend([128 + 8, 10]);
        d.extend([8, 1, 2, 3, 4, 5, 6, 7, 8]);
        d.extend([128 + 5, 0, 3, 7, 7, 7]);
        d.extend([128 + 8, 130]);
        // second scanline: old RLE, one pixel then repeat 7 times
        d.extend([4, 4, 4, 129, 1, 1, 1, 7]);
        let (w, h, v) = decode_rgbe(&file("-Y 2 +X 8", &d)).unwrap();
        assert_eq!((w, h), (8, 2));
        let s = 2f32.powi(130 - 136);
        for x in 0..8 {
            assert_eq!(
                &v[3 * x..3 * x + 3],
                &[10.0 * s, (x + 1) as f32 * s, if x < 5 { 0.0 } else { 7.0 * s }]
            );
            assert_eq!(&v[24 + 3 * x..24 + 3 * x + 3], &[4.0 / 128.0; 3]);
        }
        // old RLE with a repeat count spread over two repeat pixels: 1 + 2 + 1·256 > width
        let e =
            decode_rgbe(&file("-Y 1 +X 4", &[9, 9, 9, 128, 1, 1, 1, 2, 1, 1, 1, 1])).unwrap_err();
        assert!(e.contains("overruns"), "{e}");
    }

    #[test]
    fn malformed_files_are_errors() {
        let good = file("-Y 1 +X 2", &[128, 64, 32, 129, 255, 0, 1, 120]);
        for cut in 0..good.len() {
            assert!(decode_rgbe(&good[..cut]).is_err(), "truncated at {cut}");
        }
        let mut d = vec![2, 2, 0, 9];
        d.extend([128 + 8, 10]);
        assert!(decode_rgbe(&file("-Y 1 +X 8", &d)).unwrap_err().contains("width 9"));
        let d = [2, 2, 0, 8, 128 + 9, 1];
        assert!(decode_rgbe(&file("-Y 1 +X 8", &d)).unwrap_err().contains("overruns"));
        let d = [2, 2, 0, 8, 0];
        assert!(decode_rgbe(&file("-Y 1 +X 8", &d)).is_err());
        assert!(decode_rgbe(&file("+Y 1 +X 2", &[0; 8])).unwrap_err().contains("not supported"));
        assert!(decode_rgbe(&file("-Y 0 +X 2", &[])).is_err());
        assert!(decode_rgbe(&file("-Y 99999999 +X 99999999", &[0; 8])).is_err());
        assert!(decode_rgbe(&file("-Y 1 +X 1", &[1, 1, 1, 5])).unwrap_err().contains("no pixel"));
        let xyz = b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\0\0\0\0";
        assert!(decode_rgbe(xyz).unwrap_err().contains("xyze"));
        // garbage after the signature: an error, never a panic
        let mut rng = crate::sampling::Pcg32::new(7, 1);
        for _ in 0..2000 {
            let mut f = good.clone();
            let i = (rng.next_u32() as usize) % f.len();
            f[i] = rng.next_u32() as u8;
            let _ = decode_rgbe(&f);
        }
    }
}
