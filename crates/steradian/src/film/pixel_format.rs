//! `hdrfilm`'s `pixel_format`: which channels the image file holds.
//!
//! | value             | channels written      |
//! |-------------------|-----------------------|
//! | `rgb` (default)   | `R`, `G`, `B`         |
//! | `rgba`            | `R`, `G`, `B`, `A`    |
//! | `luminance`       | `Y`                   |
//! | `luminance_alpha` | `Y`, `A`              |
//! | `xyz`             | `X`, `Y`, `Z`         |
//! | `xyza`            | `X`, `Y`, `Z`, `A`    |
//!
//! The film always accumulates linear sRGB radiance; `Y` and `X`, `Y`, `Z` are converted from
//! it when the file is written, with Mitsuba 3's `srgb_to_xyz` (so `Y` is
//! [`luminance`](crate::spectrum::luminance)). Returned arrays (Python) and the PNG stay RGB.
//!
//! **Alpha** (checked against Mitsuba 3.9.1's `path`, `volpath`, `direct` and `depth`):
//! each camera sample carries a coverage value, developed like the radiance (Σw·a/Σw):
//! - `path`, `volpath` and the `prb` family: the probability that the camera ray's path
//!   meets something that is not a null crossing. The ray passes `null` surfaces, a
//!   `mask`'s transparent share and media by their transmittance (steradian's shadow-ray
//!   transmittance, the mean of the three channels); what it passes with probability T
//!   leaves an alpha of 1 − T, or 1 where the escaped ray sees an environment (`envmap`,
//!   `constant`, `sun`) that `hide_emitters` does not hide. Mitsuba draws this 0-or-1 value
//!   along the path it samples; steradian takes its expectation along the camera ray, after
//!   the radiance, so the image is the same bit for bit as with `rgb`.
//! - `direct`, `depth`, `aov` (and `moment` after its first integrator): 1 where the camera
//!   ray hits any surface, `null` ones included, else 0, as Mitsuba's.
//! - `ptracer`: refused with `rgba`: Mitsuba's alpha channel there counts light-path splats,
//!   not coverage.
//! - Irradiance maps and meters write no alpha.

/// The channels of the image file (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelFormat {
    #[default]
    Rgb,
    Rgba,
    Luminance,
    LuminanceAlpha,
    Xyz,
    Xyza,
}

/// How the radiance of a pixel becomes the colour channels of the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorChannels {
    Rgb,
    Luminance,
    Xyz,
}

impl PixelFormat {
    /// Mitsuba's names, in the order of its documentation.
    pub const NAMES: [(&'static str, PixelFormat); 6] = [
        ("luminance", PixelFormat::Luminance),
        ("luminance_alpha", PixelFormat::LuminanceAlpha),
        ("rgb", PixelFormat::Rgb),
        ("rgba", PixelFormat::Rgba),
        ("xyz", PixelFormat::Xyz),
        ("xyza", PixelFormat::Xyza),
    ];

    /// Parses Mitsuba's `pixel_format` string.
    pub fn parse(s: &str) -> Result<PixelFormat, String> {
        Self::NAMES.iter().find(|(name, _)| *name == s).map(|&(_, f)| f).ok_or_else(|| {
            let names: Vec<String> = Self::NAMES.iter().map(|(n, _)| format!("\"{n}\"")).collect();
            format!("unsupported pixel_format \"{s}\" (expected one of {})", names.join(", "))
        })
    }

    /// Whether the file has an `A` channel.
    pub fn has_alpha(self) -> bool {
        matches!(self, PixelFormat::Rgba | PixelFormat::LuminanceAlpha | PixelFormat::Xyza)
    }

    /// The colour channels, without alpha.
    pub fn color(self) -> ColorChannels {
        match self {
            PixelFormat::Rgb | PixelFormat::Rgba => ColorChannels::Rgb,
            PixelFormat::Luminance | PixelFormat::LuminanceAlpha => ColorChannels::Luminance,
            PixelFormat::Xyz | PixelFormat::Xyza => ColorChannels::Xyz,
        }
    }
}

impl ColorChannels {
    /// The channel names in the file.
    pub fn names(self) -> &'static [&'static str] {
        match self {
            ColorChannels::Rgb => &["R", "G", "B"],
            ColorChannels::Luminance => &["Y"],
            ColorChannels::Xyz => &["X", "Y", "Z"],
        }
    }

    /// The image's pixels in these channels (the first `names().len()` of each pixel's three
    /// values; the rest 0).
    pub fn convert(self, image: &super::Image) -> super::Image {
        use crate::spectrum::{luminance, srgb_to_xyz};
        let mut out = image.clone();
        for px in out.data.chunks_exact_mut(3) {
            let rgb = crate::Spectrum::new(px[0], px[1], px[2]);
            let v = match self {
                ColorChannels::Rgb => rgb,
                ColorChannels::Luminance => crate::Spectrum::new(luminance(rgb), 0.0, 0.0),
                ColorChannels::Xyz => srgb_to_xyz(rgb),
            };
            px.copy_from_slice(&v.to_array());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Image;

    #[test]
    fn names_parse_and_unknown_ones_are_listed() {
        for (name, f) in PixelFormat::NAMES {
            assert_eq!(PixelFormat::parse(name), Ok(f));
        }
        let e = PixelFormat::parse("spectrum").unwrap_err();
        assert!(e.contains("\"spectrum\"") && e.contains("\"xyza\""), "{e}");
        assert!(PixelFormat::Rgba.has_alpha() && !PixelFormat::Xyz.has_alpha());
        assert_eq!(PixelFormat::LuminanceAlpha.color(), ColorChannels::Luminance);
    }

    /// White (1, 1, 1) is D65 white: Y = 1 and X, Z its chromaticity's (0.9505, 1.089), and a
    /// pure green's Y is its luminance weight.
    #[test]
    fn conversions_follow_mitsubas_srgb_to_xyz() {
        let img = Image { width: 2, height: 1, data: vec![1.0, 1.0, 1.0, 0.0, 2.0, 0.0] };
        let xyz = ColorChannels::Xyz.convert(&img);
        for (v, want) in xyz.data[..3].iter().zip([0.950456, 1.0, 1.088754]) {
            assert!((v - want).abs() < 1e-5, "{:?}", xyz.data);
        }
        let y = ColorChannels::Luminance.convert(&img);
        assert!((y.data[3] - 2.0 * 0.715160).abs() < 1e-6 && y.data[4] == 0.0, "{:?}", y.data);
        assert_eq!(ColorChannels::Rgb.convert(&img), img);
    }
}
