//! # `mesh_attribute`: a mesh's per-vertex or per-face values as a texture
//!
//! Mitsuba plugin `mesh_attribute`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `name` | string | — | the attribute: `vertex_…` or `face_…` (e.g. `vertex_color`) |
//! | `scale` | float | 1 | factor on the value |
//!
//! The attributes come from the mesh file of the shape whose BSDF holds the texture (steradian
//! reads them from PLY files, with Mitsuba's naming: see `shape::ply`). A `vertex_` attribute is
//! interpolated over each triangle with the hit's barycentric coordinates; a `face_` attribute is
//! constant over a face (a polygon fan-triangulated on load keeps its value on every triangle).
//! Values are used as stored (no colour conversion), in the unit of the parameter the texture
//! feeds. As in Mitsuba, a 1-channel attribute read as a colour gives that value in every
//! channel, and a 3-channel attribute cannot feed a scalar parameter (the loader refuses it).
//!
//! Where steradian differs on purpose: a texture evaluated away from a triangle of its mesh (a
//! point built from `(u, v)` alone) returns the attribute's mean, where Mitsuba has no such
//! query.

use std::sync::Arc;

use glam::Vec2;

use super::TexturePoint;
use crate::Spectrum;

/// Whether an attribute has one value per vertex or one per face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttributeScope {
    /// `vertex_…`: interpolated over each triangle.
    Vertex,
    /// `face_…`: constant per face.
    Face,
}

/// A named attribute as read from a mesh file: `channels` values per vertex or per triangle.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttributeData {
    /// Mitsuba's name, with its `vertex_` or `face_` prefix.
    pub name: String,
    pub scope: AttributeScope,
    /// Values per element (1, 3, or 4 for colours with alpha).
    pub channels: u8,
    /// `channels` values per vertex, or per triangle for [`AttributeScope::Face`].
    pub values: Vec<f32>,
}

/// The `mesh_attribute` texture: one attribute of one mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttribute {
    /// The attribute's name (for messages).
    pub name: String,
    scope: AttributeScope,
    /// 1 or 3.
    channels: u8,
    values: Arc<[f32]>,
    /// The mesh's triangles (vertex indices), for vertex attributes.
    indices: Arc<[[u32; 3]]>,
    /// `scale` applied.
    scale: f32,
    /// Mean over the elements (scaled), for points that are not on the mesh.
    mean: Spectrum,
}

impl MeshAttribute {
    /// Default `scale` (Mitsuba's).
    pub const DEFAULT_SCALE: f32 = 1.0;

    /// The texture of attribute `data` on a mesh with triangles `indices`. `data` must have 1
    /// or 3 channels and one entry per vertex referenced by `indices` (vertex scope) or per
    /// triangle (face scope); the error says what is wrong.
    pub fn new(
        data: &MeshAttributeData,
        indices: Arc<[[u32; 3]]>,
        scale: f32,
    ) -> Result<MeshAttribute, String> {
        let ch = data.channels as usize;
        if ch != 1 && ch != 3 {
            return Err(format!(
                "attribute \"{}\" has {ch} channels; a texture needs 1 or 3",
                data.name
            ));
        }
        let elements = data.values.len() / ch;
        match data.scope {
            AttributeScope::Vertex => {
                if let Some(bad) = indices.iter().flatten().find(|&&i| i as usize >= elements) {
                    return Err(format!(
                        "attribute \"{}\" has {elements} values for a mesh using vertex {bad}",
                        data.name
                    ));
                }
            }
            AttributeScope::Face => {
                if elements != indices.len() {
                    return Err(format!(
                        "attribute \"{}\" has {elements} values for {} triangles",
                        data.name,
                        indices.len()
                    ));
                }
            }
        }
        let mut sum = [0.0f64; 3];
        for e in data.values.chunks_exact(ch) {
            for (k, s) in sum.iter_mut().enumerate() {
                *s += e[if ch == 1 { 0 } else { k }] as f64;
            }
        }
        let n = elements.max(1) as f64;
        let mean =
            Spectrum::new((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32) * scale;
        Ok(MeshAttribute {
            name: data.name.clone(),
            scope: data.scope,
            channels: data.channels,
            values: data.values.as_slice().into(),
            indices,
            scale,
            mean,
        })
    }

    /// Number of channels (1 or 3).
    pub fn channels(&self) -> u8 {
        self.channels
    }

    /// Channel values of element `e` as a colour (a single channel splatted), unscaled.
    #[inline]
    fn element(&self, e: usize) -> Option<Spectrum> {
        if self.channels == 1 {
            self.values.get(e).map(|&v| Spectrum::splat(v))
        } else {
            let v = self.values.get(3 * e..3 * e + 3)?;
            Some(Spectrum::new(v[0], v[1], v[2]))
        }
    }

    /// The value at `p`: interpolated (vertex) or constant (face), times `scale`. Out of line:
    /// inlined, it made [`Texture::eval`](super::Texture::eval) too large to inline into the
    /// BSDFs of scenes without mesh attributes.
    #[inline(never)]
    pub fn eval(&self, p: TexturePoint) -> Spectrum {
        let value = match self.scope {
            AttributeScope::Face => self.element(p.prim as usize),
            AttributeScope::Vertex => self.indices.get(p.prim as usize).and_then(|t| {
                let Vec2 { x: b1, y: b2 } = p.bary;
                let b0 = 1.0 - b1 - b2;
                Some(
                    self.element(t[0] as usize)? * b0
                        + self.element(t[1] as usize)? * b1
                        + self.element(t[2] as usize)? * b2,
                )
            }),
        };
        match value {
            Some(v) => v * self.scale,
            None => self.mean,
        }
    }

    /// One number: the (only) channel. Three-channel attributes are refused by the loader
    /// for scalar parameters, as Mitsuba refuses them; should one get here, its mean channel.
    #[inline(never)]
    pub fn eval_1(&self, p: TexturePoint) -> f32 {
        let v = self.eval(p);
        if self.channels == 1 {
            v.x
        } else {
            v.element_sum() / 3.0
        }
    }

    /// The largest value of any channel (times `scale`, for non-negative scales).
    pub fn max_value(&self) -> f32 {
        let m = self.values.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        let lo = self.values.iter().copied().fold(f32::INFINITY, f32::min);
        if self.values.is_empty() {
            0.0
        } else {
            (m * self.scale).max(lo * self.scale)
        }
    }

    /// Mean over the mesh's elements (not area-weighted), times `scale`.
    pub fn mean(&self) -> Spectrum {
        self.mean
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Arc<[[u32; 3]]> {
        vec![[0, 1, 2], [2, 1, 3]].into()
    }

    fn at(prim: u32, b1: f32, b2: f32) -> TexturePoint {
        TexturePoint { uv: Vec2::ZERO, prim, bary: Vec2::new(b1, b2), p: glam::Vec3::ZERO }
    }

    #[test]
    fn vertex_colours_interpolate_barycentrically_and_scale() {
        let data = MeshAttributeData {
            name: "vertex_color".into(),
            scope: AttributeScope::Vertex,
            channels: 3,
            values: vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        };
        let t = MeshAttribute::new(&data, tri(), 2.0).unwrap();
        // at a corner, the corner's colour
        assert_eq!(t.eval(at(0, 0.0, 0.0)), Spectrum::new(2.0, 0.0, 0.0));
        assert_eq!(t.eval(at(1, 0.0, 1.0)), Spectrum::new(2.0, 2.0, 2.0));
        // b = (0.2, 0.3, 0.5) on triangle (2, 1, 3): 0.2·blue + 0.3·green + 0.5·white, × 2
        let v = t.eval(at(1, 0.3, 0.5));
        assert!((v - Spectrum::new(1.0, 1.6, 1.4)).abs().max_element() < 1e-6, "{v}");
    }

    #[test]
    fn face_scalars_are_constant_and_splat_as_colours() {
        let data = MeshAttributeData {
            name: "face_weight".into(),
            scope: AttributeScope::Face,
            channels: 1,
            values: vec![0.25, 0.75],
        };
        let t = MeshAttribute::new(&data, tri(), 1.0).unwrap();
        assert_eq!(t.eval(at(1, 0.1, 0.8)), Spectrum::splat(0.75));
        assert_eq!(t.eval_1(at(0, 0.9, 0.0)), 0.25);
        // off the mesh: the mean
        assert_eq!(t.eval(TexturePoint::at_uv(Vec2::ZERO)), Spectrum::splat(0.5));
        assert_eq!(t.max_value(), 0.75);
    }

    #[test]
    fn mismatched_sizes_and_channel_counts_are_refused() {
        let mut data = MeshAttributeData {
            name: "face_color".into(),
            scope: AttributeScope::Face,
            channels: 3,
            values: vec![0.5; 3],
        };
        let e = MeshAttribute::new(&data, tri(), 1.0).unwrap_err();
        assert!(e.contains("1 values for 2 triangles"), "{e}");
        data.channels = 4;
        data.values = vec![0.5; 8];
        let e = MeshAttribute::new(&data, tri(), 1.0).unwrap_err();
        assert!(e.contains("4 channels"), "{e}");
        data.channels = 1;
        data.scope = AttributeScope::Vertex;
        data.values = vec![0.5; 3];
        let e = MeshAttribute::new(&data, tri(), 1.0).unwrap_err();
        assert!(e.contains("vertex 3"), "{e}");
    }
}
