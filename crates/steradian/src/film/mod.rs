//! The film: reconstruction filters, per-thread image blocks with f64 accumulation, developed
//! images, image metrics (Mitsuba's Z-test among them), and EXR/PNG input/output.

pub mod exr;
pub mod falsecolor;
pub mod filter;
mod hdrfilm;
mod image;
mod image_block;
pub mod isolux;
mod pixel_format;
pub mod png;
mod splat_block;
mod ztest;

pub use self::exr::{
    read_exr, read_exr_channels, write_exr, write_exr_channels, write_exr_layers,
    write_exr_layers_as, ExrLayer,
};
pub use self::png::{encode_png_rgb8, read_png_rgb8, srgb_encode_u8, write_png};
pub use falsecolor::{false_color, false_color_png};
pub use filter::{
    BoxFilter, CatmullRomFilter, GaussianFilter, LanczosFilter, MitchellFilter,
    ReconstructionFilter, TentFilter,
};
pub use hdrfilm::{AovLayer, ComponentFormat, Film, FilmWindow, SampleBorder, MAX_FILM_SIZE};
pub use image::{mse, rel_mse, Image};
pub use image_block::{ImageBlock, PixelAccum};
pub use isolux::isolux_png;
pub use pixel_format::{ColorChannels, PixelFormat};
pub use splat_block::SplatBlock;
pub use ztest::{erfc, z_test, ZTest, ZTEST_ALPHA, ZTEST_MIN_VARIANCE, ZTEST_PASS_FRACTION};
