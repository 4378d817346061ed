//! Textures: spatially varying quantities (reflectances, radiances, roughnesses, opacities)
//! looked up at a surface point ([`TexturePoint`]: its (u, v), for mesh attributes the
//! triangle and barycentrics, for `volume` textures the world position). Volumes (`volume.rs`:
//! `constvolume`; `gridvolume.rs`) are 3-D textures: media read them by position too.
//! A texture returns values in the unit of the parameter it feeds.
//!
//! Like Mitsuba 3, a texture can be asked for a colour ([`Texture::eval`]) or for one number
//! ([`Texture::eval_1`], used by scalar parameters such as `alpha`, `opacity` or `weight`);
//! the scalar reading of a colour follows Mitsuba per plugin: the channel mean for a constant
//! `<rgb>`, the luminance for a `bitmap`.

mod bitmap;
mod checkerboard;
mod gridvolume;
mod image_file;
mod mesh_attribute;
mod rgbe;
mod volume;

pub use bitmap::{srgb_to_linear, Bitmap, FilterType, UvTransform, WrapMode};
pub use checkerboard::Checkerboard;
pub use gridvolume::{GridVolume, VolumeFilter, VolumeWrap};
pub use image_file::{read_image, ImageFormat, LoadedImage};
pub use mesh_attribute::{AttributeScope, MeshAttribute, MeshAttributeData};
pub use rgbe::decode_rgbe;
pub use volume::{Volume, VolumeData};

use glam::{Vec2, Vec3};

use crate::Spectrum;

/// Where a texture is evaluated: surface coordinates, and the triangle and barycentric
/// coordinates (b1, b2) that `mesh_attribute` interpolates with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturePoint {
    /// Surface (texture) coordinates.
    pub uv: Vec2,
    /// Index of the primitive inside its shape; `u32::MAX` when the point is not on one.
    pub prim: u32,
    /// Barycentric coordinates of vertices 1 and 2 of triangle `prim` (vertex 0 has
    /// 1 − b1 − b2).
    pub bary: Vec2,
    /// World position, m (what `volume` textures look up; the origin where unknown).
    pub p: Vec3,
}

impl TexturePoint {
    /// A point known only by its surface coordinates (no triangle, no position).
    #[inline]
    pub fn at_uv(uv: Vec2) -> Self {
        TexturePoint { uv, prim: u32::MAX, bary: Vec2::ZERO, p: Vec3::ZERO }
    }
}

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
    /// `mesh_attribute`: a per-vertex or per-face attribute of the mesh.
    MeshAttribute(MeshAttribute),
    /// `volume`: a volume (`gridvolume`, `constvolume`) looked up at the world position, a
    /// 3-D texture for surfaces without a meaningful uv (Mitsuba's `volume` texture).
    Volume(std::sync::Arc<Volume>),
}

impl Texture {
    /// The value at point `p`. Always inlined (a constant is then read in place by the BSDF);
    /// the other variants are calls.
    #[inline(always)]
    pub fn eval(&self, p: TexturePoint) -> Spectrum {
        match self {
            Texture::Constant(v) => *v,
            Texture::Bitmap(b) => b.eval(p.uv),
            Texture::Checkerboard(c) => c.eval(p),
            Texture::MeshAttribute(m) => m.eval(p),
            Texture::Volume(v) => v.eval(p.p),
        }
    }

    /// The value as one number, for scalar parameters (Mitsuba's `eval_1`): the channel mean
    /// of a constant, the luminance of a bitmap, the value of a 1-channel mesh attribute.
    #[inline(always)]
    pub fn eval_1(&self, p: TexturePoint) -> f32 {
        match self {
            Texture::Constant(v) => v.element_sum() / 3.0,
            Texture::Bitmap(b) => b.eval_1(p.uv),
            Texture::Checkerboard(c) => c.eval_1(p),
            Texture::MeshAttribute(m) => m.eval_1(p),
            Texture::Volume(v) => v.eval(p.p).element_sum() / 3.0,
        }
    }

    /// The gradient (∂/∂u, ∂/∂v) of [`Texture::eval_1`] (per unit of u, v), for bump maps.
    /// `None` for textures Mitsuba cannot differentiate (`checkerboard`, `mesh_attribute`).
    #[inline]
    pub fn eval_1_grad(&self, p: TexturePoint) -> Option<Vec2> {
        match self {
            Texture::Constant(_) => Some(Vec2::ZERO),
            Texture::Bitmap(b) => Some(b.eval_1_grad(p.uv)),
            Texture::Checkerboard(_) | Texture::MeshAttribute(_) | Texture::Volume(_) => None,
        }
    }

    /// True when [`Texture::eval_1_grad`] is defined (a bump map can use the texture).
    pub fn has_gradient(&self) -> bool {
        !matches!(self, Texture::Checkerboard(_) | Texture::MeshAttribute(_) | Texture::Volume(_))
    }

    /// The number of channels when a scalar reading ([`Texture::eval_1`]) is undefined in
    /// Mitsuba: a 3-channel mesh attribute anywhere in the tree.
    pub fn scalar_reading_refused(&self) -> Option<&str> {
        match self {
            Texture::Constant(_) | Texture::Bitmap(_) | Texture::Volume(_) => None,
            Texture::Checkerboard(c) => {
                c.color0.scalar_reading_refused().or_else(|| c.color1.scalar_reading_refused())
            }
            Texture::MeshAttribute(m) => (m.channels() != 1).then_some(m.name.as_str()),
        }
    }

    /// Whether the texture reads the world position (a `volume` texture, also inside a
    /// `checkerboard`), which only surface shading points carry.
    pub fn reads_position(&self) -> bool {
        match self {
            Texture::Volume(_) => true,
            Texture::Checkerboard(c) => c.color0.reads_position() || c.color1.reads_position(),
            Texture::Constant(_) | Texture::Bitmap(_) | Texture::MeshAttribute(_) => false,
        }
    }

    /// The largest value of any channel anywhere (for energy checks and sampling weights).
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(v) => v.max_element(),
            Texture::Bitmap(b) => b.max_value(),
            Texture::Checkerboard(c) => c.color0.max_value().max(c.color1.max_value()),
            Texture::MeshAttribute(m) => m.max_value(),
            Texture::Volume(v) => v.max(),
        }
    }

    /// The mean value over the texture's domain (the unit square of uv; a mesh attribute's
    /// elements), per channel.
    pub fn mean(&self) -> Spectrum {
        match self {
            Texture::Constant(v) => *v,
            Texture::Bitmap(b) => b.mean(),
            Texture::Checkerboard(c) => 0.5 * (c.color0.mean() + c.color1.mean()),
            Texture::MeshAttribute(m) => m.mean(),
            // the midrange, for sampling weights only
            Texture::Volume(v) => Spectrum::splat(0.5 * (v.max() + v.min())),
        }
    }
}

/// The value of a `volume` texture given no volume (Mitsuba's).
pub const VOLUME_TEXTURE_DEFAULT: f32 = 0.75;

impl From<Spectrum> for Texture {
    fn from(v: Spectrum) -> Self {
        Texture::Constant(v)
    }
}
