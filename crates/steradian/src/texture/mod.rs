//! Textures: spatially varying quantities (reflectances, radiances) looked up at a surface
//! point. A texture returns values in the unit of the parameter it feeds.

use glam::Vec2;

use crate::Spectrum;

/// A texture. Closed enum: one variant per texture plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// A value that is the same everywhere (Mitsuba's `<rgb>`, `<spectrum>` or `<float>`
    /// given directly as a parameter).
    Constant(Spectrum),
}

impl Texture {
    /// The value at surface coordinates `uv`.
    #[inline]
    pub fn eval(&self, _uv: Vec2) -> Spectrum {
        match self {
            Texture::Constant(v) => *v,
        }
    }

    /// The largest value of any channel anywhere (for energy checks and sampling weights).
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(v) => v.max_element(),
        }
    }

    /// The mean value over the texture's domain.
    pub fn mean(&self) -> Spectrum {
        match self {
            Texture::Constant(v) => *v,
        }
    }
}

impl From<Spectrum> for Texture {
    fn from(v: Spectrum) -> Self {
        Texture::Constant(v)
    }
}
