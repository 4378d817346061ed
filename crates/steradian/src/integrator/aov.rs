//! `aov`: arbitrary output variables of the first surface each camera ray hits, written as
//! EXR layers beside the image (Mitsuba 3's aov integrator), e.g. for denoisers and
//! compositing.
//!
//! | parameter  | type        | meaning |
//! |------------|-------------|---------|
//! | `aovs`     | string      | comma-separated `name:type` pairs (required) |
//! | (nested)   | integrator  | optional; each one's radiance becomes layer `<name>.R/G/B` plus `<name>.A` |
//!
//! | type          | channels | value at the first hit (0 where the ray hits nothing) |
//! |---------------|----------|------------------------------------------------------|
//! | `depth`       | `T`      | distance t (m) from the ray origin |
//! | `position`    | `X Y Z`  | the point (m, world space) |
//! | `uv`          | `U V`    | surface coordinates |
//! | `geo_normal`  | `X Y Z`  | geometric normal (world space) |
//! | `sh_normal`   | `X Y Z`  | shading normal (world space) |
//! | `dp_du`, `dp_dv` | `X Y Z` | ∂p/∂u, ∂p/∂v (world space) |
//! | `prim_index`  | `I`      | the primitive (triangle) index within its shape |
//! | `shape_index` | `I`      | the shape's index in the scene, in file order |
//! | `albedo`      | `R G B`  | the BSDF's diffuse reflectance ([`Bsdf::diffuse_reflectance`](crate::bsdf::Bsdf::diffuse_reflectance)) |
//!
//! Layers are filtered like the image (a silhouette pixel mixes both sides, as in Mitsuba).
//! The image is the first nested integrator's radiance, black without one; a nested
//! integrator's `A` is 1 where its camera ray hits a surface or sees an environment light.
//! Where steradian differs on purpose: `shape_index` is the shape's position in the scene
//! (Mitsuba writes an internal object id that depends on its variant); `boundary_test`,
//! `duv_dx` and `duv_dy` (which need ray differentials) are refused by the loader.

use super::Integrator;
use crate::film::AovLayer;
use crate::geometry::Ray;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::Spectrum;

/// One output variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AovField {
    Depth,
    Position,
    Uv,
    GeometricNormal,
    ShadingNormal,
    DpDu,
    DpDv,
    PrimIndex,
    ShapeIndex,
    Albedo,
}

impl AovField {
    /// The field of Mitsuba's type name.
    pub fn parse(s: &str) -> Option<AovField> {
        Some(match s {
            "depth" => AovField::Depth,
            "position" => AovField::Position,
            "uv" => AovField::Uv,
            "geo_normal" => AovField::GeometricNormal,
            "sh_normal" => AovField::ShadingNormal,
            "dp_du" => AovField::DpDu,
            "dp_dv" => AovField::DpDv,
            "prim_index" => AovField::PrimIndex,
            "shape_index" => AovField::ShapeIndex,
            "albedo" => AovField::Albedo,
            _ => return None,
        })
    }

    /// Its EXR channel names.
    pub fn channels(&self) -> Vec<&'static str> {
        match self {
            AovField::Depth => vec!["T"],
            AovField::Uv => vec!["U", "V"],
            AovField::PrimIndex | AovField::ShapeIndex => vec!["I"],
            AovField::Albedo => vec!["R", "G", "B"],
            _ => vec!["X", "Y", "Z"],
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct AovIntegrator {
    /// The output variables with their layer names, in the order of `aovs`.
    pub fields: Vec<(String, AovField)>,
    /// Nested integrators with their layer names.
    pub nested: Vec<(String, Integrator)>,
}

impl AovIntegrator {
    /// Its layers, in Mitsuba's order: each nested integrator's `R G B` and `A`, then the
    /// fields.
    pub fn aov_layers(&self) -> Vec<AovLayer> {
        let nested = self.nested.iter().flat_map(|(n, _)| {
            [
                AovLayer { name: n.clone(), channels: vec!["R", "G", "B"] },
                AovLayer { name: n.clone(), channels: vec!["A"] },
            ]
        });
        let fields =
            self.fields.iter().map(|(n, f)| AovLayer { name: n.clone(), channels: f.channels() });
        nested.chain(fields).collect()
    }

    /// The first nested integrator's radiance (0 without one); `aovs` gets every layer's value
    /// for this camera ray.
    #[inline]
    pub fn li_aovs(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut PixelSampler,
        aovs: &mut [Spectrum],
    ) -> Spectrum {
        let si = scene.intersect(ray);
        let mut first = Spectrum::ZERO;
        let seen = si.is_some() || scene.environment.is_some();
        for (i, (_, integrator)) in self.nested.iter().enumerate() {
            let l = integrator.li(scene, ray, sampler);
            if i == 0 {
                first = l;
            }
            aovs[2 * i] = l;
            aovs[2 * i + 1] = Spectrum::new(if seen { 1.0 } else { 0.0 }, 0.0, 0.0);
        }
        let out = &mut aovs[2 * self.nested.len()..];
        let Some(si) = si else {
            out[..self.fields.len()].fill(Spectrum::ZERO);
            return first;
        };
        let v3 = |v: glam::Vec3| Spectrum::new(v.x, v.y, v.z);
        for ((_, field), o) in self.fields.iter().zip(out.iter_mut()) {
            *o = match field {
                AovField::Depth => Spectrum::new(si.t, 0.0, 0.0),
                AovField::Position => v3(si.p),
                AovField::Uv => Spectrum::new(si.uv.x, si.uv.y, 0.0),
                AovField::GeometricNormal => v3(si.n),
                AovField::ShadingNormal => v3(si.sh_frame.n),
                AovField::DpDu => v3(si.dpdu),
                AovField::DpDv => v3(si.dpdv),
                AovField::PrimIndex => Spectrum::new(si.prim as f32, 0.0, 0.0),
                AovField::ShapeIndex => Spectrum::new(si.shape as f32, 0.0, 0.0),
                AovField::Albedo => {
                    let sp = crate::bsdf::ShadingPoint::new(&si);
                    scene.bsdf(&si).diffuse_reflectance(&sp, si.to_local(si.wo))
                }
            };
        }
        first
    }
}
