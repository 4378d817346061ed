//! Textures: spatially varying quantities (reflectances, radiances, roughnesses, opacities)
//! looked up at a surface point's (u, v). A texture returns values in the unit of the
//! parameter it feeds.
//!
//! Like Mitsuba 3, a texture can be asked for a colour ([`Texture::eval`]) or for one number
//! ([`Texture::eval_1`], used by scalar parameters such as `alpha`, `opacity` or `weight`);
//! the scalar reading of a colour follows Mitsuba per plugin: the channel mean for a constant
//! `<rgb>`, the luminance for a `bitmap`.

mod bitmap;
mod checkerboard;
mod image_file;
mod rgbe;

pub use bitmap::{srgb_to_linear, Bitmap, FilterType, UvTransform, WrapMode};
pub use checkerboard::Checkerboard;
pub use image_file::{read_image, ImageFormat, LoadedImage};
pub use rgbe::decode_rgbe;

use glam::Vec2;

use crate::Spectrum;

/// A texture. Closed enum: one variant per texture plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// A value that is the same everywhere (Mitsuba's `<rgb>`, `<spectrum>` or `<float>`
    /// given directly as a parameter).
    Constant(Spectrum),
    /// `bitmap`: an image file.
    Bitmap(Bitmap),
    /// `checkerboard`: two alternating textures.
    Checkerboard(Checkerboard),
}

impl Texture {
    /// The value at surface coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Spectrum {
        match self {
            Texture::Constant(v) => *v,
            Texture::Bitmap(b) => b.eval(uv),
            Texture::Checkerboard(c) => c.eval(uv),
        }
    }

    /// The value as one number, for scalar parameters (Mitsuba's `eval_1`): the channel mean
    /// of a constant, the luminance of a bitmap.
    #[inline]
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        match self {
            Texture::Constant(v) => v.element_sum() / 3.0,
            Texture::Bitmap(b) => b.eval_1(uv),
            Texture::Checkerboard(c) => c.eval_1(uv),
        }
    }

    /// The gradient (∂/∂u, ∂/∂v) of [`Texture::eval_1`] (per unit of u, v), for bump maps.
    /// `None` for textures Mitsuba cannot differentiate (`checkerboard`).
    #[inline]
    pub fn eval_1_grad(&self, uv: Vec2) -> Option<Vec2> {
        match self {
            Texture::Constant(_) => Some(Vec2::ZERO),
            Texture::Bitmap(b) => Some(b.eval_1_grad(uv)),
            Texture::Checkerboard(_) => None,
        }
    }

    /// True when [`Texture::eval_1_grad`] is defined (a bump map can use the texture).
    pub fn has_gradient(&self) -> bool {
        !matches!(self, Texture::Checkerboard(_))
    }

    /// The largest value of any channel anywhere (for energy checks and sampling weights).
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(v) => v.max_element(),
            Texture::Bitmap(b) => b.max_value(),
            Texture::Checkerboard(c) => c.color0.max_value().max(c.color1.max_value()),
        }
    }

    /// The mean value over the texture's domain (the unit square of uv), per channel.
    pub fn mean(&self) -> Spectrum {
        match self {
            Texture::Constant(v) => *v,
            Texture::Bitmap(b) => b.mean(),
            Texture::Checkerboard(c) => 0.5 * (c.color0.mean() + c.color1.mean()),
        }
    }
}

impl From<Spectrum> for Texture {
    fn from(v: Spectrum) -> Self {
        Texture::Constant(v)
    }
}
