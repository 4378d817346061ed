//! Developed images (linear f32 RGB) and image-comparison metrics.

use crate::Spectrum;

/// A linear RGB image: `data` holds `width·height·3` floats, RGB interleaved, row-major, top
/// row first (pixel (x, y) starts at index `3·(y·width + x)`).
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub data: Vec<f32>,
}

impl Image {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Image {
        Image { width, height, data: vec![0.0; width as usize * height as usize * 3] }
    }

    /// An image from interleaved RGB data; errors if the length is not `width·height·3`.
    pub fn from_data(width: u32, height: u32, data: Vec<f32>) -> Result<Image, String> {
        let expected = width as usize * height as usize * 3;
        if data.len() != expected {
            return Err(format!(
                "image {width}x{height} needs {expected} floats (RGB), got {}",
                data.len()
            ));
        }
        Ok(Image { width, height, data })
    }

    /// Number of pixels.
    #[inline]
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    #[inline]
    fn index(&self, x: u32, y: u32) -> usize {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside {}x{} image",
            self.width,
            self.height
        );
        3 * (y as usize * self.width as usize + x as usize)
    }

    /// The pixel at column `x`, row `y` (row 0 is the top). Panics outside the image.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> Spectrum {
        let i = self.index(x, y);
        Spectrum::new(self.data[i], self.data[i + 1], self.data[i + 2])
    }

    /// Sets the pixel at column `x`, row `y`. Panics outside the image.
    #[inline]
    pub fn set(&mut self, x: u32, y: u32, value: Spectrum) {
        let i = self.index(x, y);
        self.data[i] = value.x;
        self.data[i + 1] = value.y;
        self.data[i + 2] = value.z;
    }

    /// Illuminance (lx) from an irradiance image (W/m²): 683 lm/W × the luminance-weighted RGB,
    /// in all three channels. Applied to a standard-error image it treats the channels' errors
    /// as fully correlated (they come from the same light paths): an upper bound.
    pub fn to_illuminance(&self) -> Image {
        let mut out = self.clone();
        for px in out.data.chunks_exact_mut(3) {
            let y = 683.0 * crate::spectrum::luminance(Spectrum::new(px[0], px[1], px[2]));
            px.fill(y);
        }
        out
    }

    /// Mean of each channel over all pixels, summed in f64 (0 for an empty image).
    pub fn channel_means(&self) -> [f64; 3] {
        let mut sum = [0.0f64; 3];
        for px in self.data.chunks_exact(3) {
            for c in 0..3 {
                sum[c] += px[c] as f64;
            }
        }
        let n = self.pixel_count().max(1) as f64;
        sum.map(|s| s / n)
    }

    /// Per-channel ratio of this image's mean to `reference`'s mean (NaN or ±∞ where the
    /// reference mean is 0). A quick check of overall brightness/energy agreement.
    pub fn mean_ratio(&self, reference: &Image) -> [f64; 3] {
        let a = self.channel_means();
        let b = reference.channel_means();
        [a[0] / b[0], a[1] / b[1], a[2] / b[2]]
    }
}

fn check_same_size(a: &Image, b: &Image, what: &str) {
    assert!(
        a.width == b.width && a.height == b.height && a.data.len() == b.data.len(),
        "{what}: image sizes differ ({}x{} vs {}x{})",
        a.width,
        a.height,
        b.width,
        b.height
    );
}

/// Mean squared error over all pixels and channels, computed in f64. Panics if the sizes differ.
pub fn mse(a: &Image, b: &Image) -> f64 {
    check_same_size(a, b, "mse");
    if a.data.is_empty() {
        return 0.0;
    }
    let s: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(&x, &y)| {
            let d = x as f64 - y as f64;
            d * d
        })
        .sum();
    s / a.data.len() as f64
}

/// Relative MSE against a reference: the mean over pixels and channels of
/// `(a − b)² / (b² + 0.01)`, computed in f64. Panics if the sizes differ.
pub fn rel_mse(a: &Image, b_ref: &Image) -> f64 {
    check_same_size(a, b_ref, "rel_mse");
    if a.data.is_empty() {
        return 0.0;
    }
    let s: f64 = a
        .data
        .iter()
        .zip(&b_ref.data)
        .map(|(&x, &y)| {
            let (x, y) = (x as f64, y as f64);
            let d = x - y;
            d * d / (y * y + 0.01)
        })
        .sum();
    s / a.data.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    fn random_image(w: u32, h: u32, seed: u64) -> Image {
        let mut rng = Pcg32::new(seed, 1);
        let data = (0..w * h * 3).map(|_| rng.next_f32() * 3.0).collect();
        Image::from_data(w, h, data).unwrap()
    }

    #[test]
    fn get_set_layout() {
        let mut img = Image::new(4, 3);
        img.set(2, 1, Spectrum::new(1.0, 2.0, 3.0));
        assert_eq!(img.get(2, 1), Spectrum::new(1.0, 2.0, 3.0));
        let i = 3 * (4 + 2);
        assert_eq!(&img.data[i..i + 3], &[1.0, 2.0, 3.0]);
        assert!(Image::from_data(2, 2, vec![0.0; 11]).is_err());
    }

    #[test]
    fn metrics() {
        let b = random_image(7, 5, 3);
        assert_eq!(rel_mse(&b, &b), 0.0);
        assert_eq!(mse(&b, &b), 0.0);
        // Known perturbation: a = b + δ·(pixel-dependent sign).
        let mut a = b.clone();
        let mut expect_rel = 0.0f64;
        let mut expect_mse = 0.0f64;
        for (i, v) in a.data.iter_mut().enumerate() {
            let d = if i % 2 == 0 { 0.25f32 } else { -0.125 };
            let y = *v as f64;
            *v += d;
            let dd = *v as f64 - y;
            expect_rel += dd * dd / (y * y + 0.01);
            expect_mse += dd * dd;
        }
        let n = a.data.len() as f64;
        assert!((rel_mse(&a, &b) - expect_rel / n).abs() < 1e-12);
        assert!((mse(&a, &b) - expect_mse / n).abs() < 1e-12);
        // A constant offset on a zero reference: δ²/0.01.
        let z = Image::new(3, 3);
        let mut o = Image::new(3, 3);
        o.data.iter_mut().for_each(|v| *v = 0.1);
        let want = (0.1f32 as f64).powi(2) / 0.01;
        assert!((rel_mse(&o, &z) - want).abs() < 1e-12);
    }

    #[test]
    fn means_and_ratio() {
        let mut img = Image::new(2, 1);
        img.set(0, 0, Spectrum::new(1.0, 2.0, 4.0));
        img.set(1, 0, Spectrum::new(3.0, 2.0, 0.0));
        assert_eq!(img.channel_means(), [2.0, 2.0, 2.0]);
        let mut half = img.clone();
        half.data.iter_mut().for_each(|v| *v *= 0.5);
        assert_eq!(half.mean_ratio(&img), [0.5, 0.5, 0.5]);
    }
}
