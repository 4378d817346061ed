//! `area`: a surface that emits light. Attach it to a shape: nest it in the `<shape>`, or
//! declare it at the scene level with an `id` and `<ref>` it from one shape (from two, it is
//! an error, as in Mitsuba).
//!
//! | parameter  | type             | default | unit       |
//! |------------|------------------|---------|------------|
//! | `radiance` | spectrum/texture | 1       | W/(m²·sr)  |
//! | `luminance` | float | — | cd/m², instead of `radiance` (steradian's own; with `color`, `photometric.rs`) |
//! | `color` | spectrum | 1 (white) | the colour of a photometric light |
//!
//! The surface emits a constant radiance L from its **front** side only (the side its normal
//! points to; on a mesh with vertex normals, its shading normal), as in Mitsuba 3; its flux
//! is Φ = π·L·A. Directions are sampled with the shape's own strategy (solid angle for
//! spheres, area otherwise).
//!
//! Where steradian differs on purpose: light sampling on a mesh converts a point's area
//! density to solid angle with the face's cosine, the true measure. Mitsuba 3.9.1 uses the
//! interpolated vertex normal's, which biases its light samples where vertex normals tilt
//! away from the faces: a triangle light with tilted normals (`scripts/mitsuba_diff`,
//! `obj_light_shading_normals` without the sky) under `direct` reads 0.7392 in Mitsuba with
//! light samples only against 0.7640 with BSDF samples only; steradian 0.7632 and 0.7640.

use glam::{Vec2, Vec3};

use super::{EmitterSample, Support};
use crate::geometry::is_positive;
use crate::geometry::SurfacePoint;
use crate::shape::{Shape, UvRequest};
use crate::texture::{Texture, TexturePoint};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    /// Index of the emitting shape in the scene.
    pub shape: u32,
    pub radiance: Texture,
}

impl AreaLight {
    /// Default `radiance` (W/(m²·sr); Mitsuba's).
    pub const DEFAULT_RADIANCE: f32 = 1.0;

    pub fn new(shape: u32, radiance: Texture) -> Self {
        AreaLight { shape, radiance }
    }

    /// Radiance leaving towards `wo` a point with shading normal `n` (the side the light
    /// emits to, as Mitsuba's area emitter takes it from the shading frame).
    #[inline]
    pub fn radiance(&self, wo: Vec3, n: Vec3, uv: Vec2) -> Spectrum {
        if n.dot(wo) > 0.0 {
            self.radiance.eval(TexturePoint::at_uv(uv))
        } else {
            Spectrum::ZERO
        }
    }

    #[inline]
    pub fn sample_direction(&self, shapes: &[Shape], p: Vec3, u: Vec2) -> Option<EmitterSample> {
        // a uniform emitter needs no surface coordinates
        let uv = if matches!(self.radiance, Texture::Constant(_)) {
            UvRequest::Skip
        } else {
            UvRequest::Compute
        };
        let ds = shapes[self.shape as usize].sample_direction(p, u, uv)?;
        // one-sided: the sampled point must face the reference point, by its geometric normal
        // (as `pdf_direction` decides) and by its shading normal (as `radiance` does: a mesh's
        // vertex normals may point away from its winding)
        let shape = &shapes[self.shape as usize];
        if ds.n.dot(ds.wi) >= 0.0
            || !is_positive(ds.pdf)
            || !shape.shading_faces(ds.prim, ds.p, -ds.wi)
        {
            return None;
        }
        Some(EmitterSample {
            wi: ds.wi,
            dist: ds.dist,
            pdf: ds.pdf,
            weight: self.radiance.eval(TexturePoint::at_uv(ds.uv)) / ds.pdf,
            support: Support::Extended,
        })
    }

    #[inline]
    pub fn pdf_direction(&self, shapes: &[Shape], p: Vec3, wi: Vec3, light: &SurfacePoint) -> f32 {
        if light.n.dot(wi) >= 0.0 {
            return 0.0;
        }
        shapes[self.shape as usize].pdf_direction(p, light)
    }
}
