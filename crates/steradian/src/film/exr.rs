//! OpenEXR output and input of [`Image`]s.
//!
//! Files are written as one EXR part with lossless compression; the main image is stored in
//! channels `R`, `G`, `B`, and extra layers as `<prefix>.R`, `<prefix>.G`, `<prefix>.B` (e.g.
//! `stderr.R`), the naming Mitsuba and image viewers use for layers. The same image gives the
//! same file byte for byte: chunks are compressed and written in order on one thread (the exr
//! crate's parallel writer stores them in the order its threads finish).

use std::path::Path;

use ::exr::prelude::{
    f16, AnyChannel, AnyChannels, FlatSamples, Image as ExrImage, SmallVec, WritableImage,
};

use super::hdrfilm::ComponentFormat;
use super::image::Image;

/// Writes `image` as float32 RGB (channels R, G, B).
pub fn write_exr(path: &Path, image: &Image) -> Result<(), String> {
    write_exr_layers_as(path, &[("", image)], ComponentFormat::Float32)
}

/// Writes several same-sized images into one float32 EXR: the layer with prefix `""` becomes
/// channels `R`, `G`, `B`, a layer with prefix `p` becomes `p.R`, `p.G`, `p.B`.
pub fn write_exr_layers(path: &Path, layers: &[(&str, &Image)]) -> Result<(), String> {
    write_exr_layers_as(path, layers, ComponentFormat::Float32)
}

/// [`write_exr_layers`] with a choice of float16 or float32 samples.
pub fn write_exr_layers_as(
    path: &Path,
    layers: &[(&str, &Image)],
    format: ComponentFormat,
) -> Result<(), String> {
    let layers: Vec<ExrLayer> = layers
        .iter()
        .map(|&(prefix, image)| ExrLayer { prefix, channels: &["R", "G", "B"], image })
        .collect();
    write_exr_channels(path, &layers, format)
}

/// One layer of an EXR file: the first one to three channels of `image`, named
/// `<prefix>.<channel>` (just `<channel>` for the prefix `""`).
#[derive(Clone, Copy, Debug)]
pub struct ExrLayer<'a> {
    pub prefix: &'a str,
    pub channels: &'a [&'a str],
    pub image: &'a Image,
}

/// Writes same-sized layers with their own channel names (e.g. an AOV's `X`, `Y`, `Z`).
pub fn write_exr_channels(
    path: &Path,
    layers: &[ExrLayer],
    format: ComponentFormat,
) -> Result<(), String> {
    let err = |msg: String| format!("cannot write EXR {}: {msg}", path.display());
    let Some(first) = layers.first() else {
        return Err(err("no image to write".into()));
    };
    let (w, h) = (first.image.width, first.image.height);
    if w == 0 || h == 0 {
        return Err(err(format!("empty image {w}x{h}")));
    }
    let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
    let mut names: Vec<String> = Vec::new();
    for &ExrLayer { prefix, channels: layer_channels, image: img } in layers {
        if img.width != w || img.height != h || img.data.len() != 3 * w as usize * h as usize {
            return Err(err(format!(
                "layer \"{prefix}\" is {}x{}, the first layer is {w}x{h}",
                img.width, img.height
            )));
        }
        if layer_channels.is_empty() || layer_channels.len() > 3 {
            return Err(err(format!("layer \"{prefix}\" must have 1 to 3 channels")));
        }
        for (c, ch) in layer_channels.iter().enumerate() {
            let name = if prefix.is_empty() { ch.to_string() } else { format!("{prefix}.{ch}") };
            if names.contains(&name) {
                return Err(err(format!("duplicate channel {name}")));
            }
            let values = img.data.iter().skip(c).step_by(3).copied();
            let samples = match format {
                ComponentFormat::Float32 => FlatSamples::F32(values.collect()),
                ComponentFormat::Float16 => FlatSamples::F16(values.map(f16::from_f32).collect()),
                ComponentFormat::UInt32 => FlatSamples::U32(values.map(to_uint32).collect()),
            };
            channels.push(AnyChannel::new(name.as_str(), samples));
            names.push(name);
        }
    }
    let image = ExrImage::from_channels((w as usize, h as usize), AnyChannels::sort(channels));
    image.write().non_parallel().to_file(path).map_err(|e| err(e.to_string()))
}

/// A value as Mitsuba 3.9.1 writes it in a `uint32` file: clamped to [0, 1] and scaled to
/// 2³² − 1, in single precision (so 1 becomes 4294967040, the largest f32 below 2³²).
fn to_uint32(v: f32) -> u32 {
    const LARGEST: f32 = 4_294_967_040.0;
    if v.is_nan() {
        return 0;
    }
    (v.clamp(0.0, 1.0) * 4_294_967_295.0).min(LARGEST) as u32
}

/// Reads the RGB channels (`R`, `G`, `B`, float16, float32 or uint32; any compression) of an
/// EXR file. The first layer (part) holding all three is used; an error if none does.
pub fn read_exr(path: &Path) -> Result<Image, String> {
    read_exr_channels(path, &["R", "G", "B"])
}

/// Reads one to three named channels (e.g. a `moment` AOV's `m2_path.X`, `m2_path.Y`,
/// `m2_path.Z`) of an EXR file into the first channels of an [`Image`] (the others 0), from
/// the first layer (part) holding all of them.
pub fn read_exr_channels(path: &Path, names: &[&str]) -> Result<Image, String> {
    let err = |msg: String| format!("cannot read EXR {}: {msg}", path.display());
    if names.is_empty() || names.len() > 3 {
        return Err(err(format!("1 to 3 channels can be read, not {}", names.len())));
    }
    let image =
        ::exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| err(e.to_string()))?;
    for layer in &image.layer_data {
        let find = |name: &&str| layer.channel_data.list.iter().find(|c| c.name.eq(name));
        let Some(found) = names.iter().map(find).collect::<Option<Vec<_>>>() else {
            continue;
        };
        let (w, h) = (layer.size.width(), layer.size.height());
        let n = w * h;
        let mut data = vec![0.0f32; 3 * n];
        for (c, ch) in found.into_iter().enumerate() {
            if ch.sample_data.len() != n {
                return Err(err(format!(
                    "channel {} has {} samples, expected {n} (subsampled channels are not supported)",
                    ch.name,
                    ch.sample_data.len()
                )));
            }
            for (i, v) in ch.sample_data.values_as_f32().enumerate() {
                data[3 * i + c] = v;
            }
        }
        return Image::from_data(w as u32, h as u32, data).map_err(err);
    }
    Err(err(format!("no layer with the channels {}", names.join(", "))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;
    use crate::testkit::temp_dir;

    fn random_image(w: u32, h: u32, seed: u64) -> Image {
        let mut rng = Pcg32::new(seed, 7);
        // Include values that f16 cannot represent exactly and a wide dynamic range.
        let data = (0..w * h * 3)
            .map(|i| (rng.next_f32() * 2.0 - 0.2) * 10f32.powi((i % 7) as i32 - 3))
            .collect();
        Image::from_data(w, h, data).unwrap()
    }

    #[test]
    fn the_same_image_gives_the_same_file() {
        // 300 x 200 pixels: 4 x 4 tiles of 64, enough chunks for a parallel writer to reorder
        let dir = temp_dir("film-exr-same-bytes");
        let img = random_image(300, 200, 11);
        let bytes = |name: &str| {
            let p = dir.join(name);
            write_exr_layers(&p, &[("", &img), ("stderr", &img)]).unwrap();
            std::fs::read(&p).unwrap()
        };
        let first = bytes("a.exr");
        for k in 0..4 {
            assert!(bytes(&format!("b{k}.exr")) == first, "write {k} differs");
        }
    }

    #[test]
    fn exr_round_trip_f32_exact() {
        let dir = temp_dir("film-exr-exr-round-trip-f32-exact");
        let img = random_image(13, 7, 1);
        let p = dir.join("rt.exr");
        write_exr(&p, &img).unwrap();
        let back = read_exr(&p).unwrap();
        assert_eq!(back.width, 13);
        assert_eq!(back.height, 7);
        assert_eq!(back.data, img.data); // bit-exact, including layout
        std::fs::remove_file(&p).ok();
    }

    /// `uint32` files hold Mitsuba's integers: values clamped to [0, 1], times 2³² − 1 (the
    /// figures Mitsuba 3.9.1 wrote for 0.40000007, 3.7 and 12345.6).
    #[test]
    fn exr_uint32_as_mitsuba_writes_it() {
        assert_eq!(to_uint32(0.400_000_07), 1_717_987_200);
        assert_eq!(to_uint32(3.7), 4_294_967_040);
        assert_eq!(to_uint32(1.0), 4_294_967_040);
        assert_eq!((to_uint32(-2.0), to_uint32(f32::NAN), to_uint32(0.0)), (0, 0, 0));
        let dir = temp_dir("film-exr-uint32");
        let img = Image::from_data(2, 1, vec![0.5, 0.25, 2.0, 0.0, 1.0, 0.125]).unwrap();
        let p = dir.join("u32.exr");
        write_exr_layers_as(&p, &[("", &img)], ComponentFormat::UInt32).unwrap();
        let back = read_exr(&p).unwrap();
        let expected: Vec<f32> = img.data.iter().map(|&v| to_uint32(v) as f32).collect();
        assert_eq!(back.data, expected);
    }

    #[test]
    fn exr_f16_round_trip_within_half_precision() {
        let dir = temp_dir("film-exr-exr-f16-round-trip-within-half-precision");
        let img = random_image(5, 4, 2);
        let p = dir.join("rt16.exr");
        write_exr_layers_as(&p, &[("", &img)], ComponentFormat::Float16).unwrap();
        let back = read_exr(&p).unwrap();
        for (a, b) in back.data.iter().zip(&img.data) {
            assert_eq!(*a, f16::from_f32(*b).to_f32());
            assert!((a - b).abs() <= b.abs() * 1e-3 + 1e-7);
        }
        std::fs::remove_file(&p).ok();
    }

    #[test]
    fn exr_layers_readable() {
        let dir = temp_dir("film-exr-exr-layers-readable");
        let main = random_image(6, 5, 3);
        let err = random_image(6, 5, 4);
        let p = dir.join("layers.exr");
        write_exr_layers(&p, &[("", &main), ("stderr", &err)]).unwrap();
        // The main RGB is read back.
        assert_eq!(read_exr(&p).unwrap().data, main.data);
        // The extra layer's channels are there with their values.
        let raw = ::exr::prelude::read_all_flat_layers_from_file(&p).unwrap();
        let chans = &raw.layer_data[0].channel_data.list;
        let names: Vec<String> = chans.iter().map(|c| c.name.to_string()).collect();
        for n in ["R", "G", "B", "stderr.R", "stderr.G", "stderr.B"] {
            assert!(names.iter().any(|x| x == n), "missing {n} in {names:?}");
        }
        let sg = chans.iter().find(|c| c.name.eq("stderr.G")).unwrap();
        let got: Vec<f32> = sg.sample_data.values_as_f32().collect();
        let want: Vec<f32> = err.data.iter().skip(1).step_by(3).copied().collect();
        assert_eq!(got, want);
        // Mismatched sizes are refused.
        let small = Image::new(2, 2);
        assert!(write_exr_layers(&p, &[("", &main), ("x", &small)]).is_err());
        std::fs::remove_file(&p).ok();
    }

    #[test]
    fn exr_read_errors() {
        let dir = temp_dir("film-exr-exr-read-errors");
        let missing = dir.join("does-not-exist.exr");
        let e = read_exr(&missing).unwrap_err();
        assert!(e.contains("does-not-exist.exr"), "{e}");
        let corrupt = dir.join("corrupt.exr");
        std::fs::write(&corrupt, b"this is not an OpenEXR file at all").unwrap();
        let e = read_exr(&corrupt).unwrap_err();
        assert!(e.contains("corrupt.exr"), "{e}");
        // Truncated valid file.
        let p = dir.join("trunc.exr");
        write_exr(&p, &random_image(16, 16, 5)).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        std::fs::write(&p, &bytes[..bytes.len() / 2]).unwrap();
        assert!(read_exr(&p).is_err());
        // A file without R, G, B.
        let q = dir.join("noRGB.exr");
        let img = ExrImage::from_channels(
            (2usize, 2usize),
            AnyChannels::sort(SmallVec::from_vec(vec![AnyChannel::new(
                "Y",
                FlatSamples::F32(vec![1.0; 4]),
            )])),
        );
        img.write().to_file(&q).unwrap();
        let e = read_exr(&q).unwrap_err();
        assert!(e.contains("the channels R, G, B"), "{e}");
        for f in [corrupt, p, q] {
            std::fs::remove_file(f).ok();
        }
    }
}
