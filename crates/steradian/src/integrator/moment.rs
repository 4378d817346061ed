//! `moment`: wraps one or more integrators and records, beside the image, each one's
//! per-pixel mean and second moment of its samples in CIE XYZ (Mitsuba 3's moment
//! integrator, which its render tests use for variance images).
//!
//! | parameter        | type        | meaning |
//! |------------------|-------------|---------|
//! | (nested)         | integrator  | one or more; each is sampled once per camera sample, in order |
//!
//! The image is the first nested integrator's. For nested integrator `n` (its XML `name`, or
//! Mitsuba's `_arg_<i>` for the i-th unnamed child) the EXR gets AOV layers `n.X`, `n.Y`,
//! `n.Z` (the filtered mean of its samples' XYZ) and, after all of those, `m2_n.X`, `m2_n.Y`,
//! `m2_n.Z` (the filtered mean of their squares), so that the per-sample variance is
//! m2 − m1². steradian's `path` normally averages several paths per camera sample
//! (`branches`, integrator/path.rs); inside `moment` it traces one unless `branches` is
//! given, so that a sample is one path, as in Mitsuba, and m2 means what Mitsuba's means.

use super::Integrator;
use crate::film::AovLayer;
use crate::geometry::Ray;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::spectrum::srgb_to_xyz;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct MomentIntegrator {
    /// The nested integrators, each with the name of its AOV layers.
    pub nested: Vec<(String, Integrator)>,
}

impl MomentIntegrator {
    /// The AOV layers it writes: every integrator's mean, then every one's second moment.
    pub fn aov_layers(&self) -> Vec<AovLayer> {
        let xyz = vec!["X", "Y", "Z"];
        let means =
            self.nested.iter().map(|(n, _)| AovLayer { name: n.clone(), channels: xyz.clone() });
        let m2 = self
            .nested
            .iter()
            .map(|(n, _)| AovLayer { name: format!("m2_{n}"), channels: xyz.clone() });
        means.chain(m2).collect()
    }

    /// The first integrator's radiance; `aovs` (2 per nested integrator) gets each one's XYZ
    /// and its square.
    #[inline]
    pub fn li_aovs(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut PixelSampler,
        aovs: &mut [Spectrum],
    ) -> Spectrum {
        let n = self.nested.len();
        let mut first = Spectrum::ZERO;
        for (i, (_, integrator)) in self.nested.iter().enumerate() {
            let l = integrator.li(scene, ray, sampler);
            if i == 0 {
                first = l;
            }
            let xyz = srgb_to_xyz(l);
            aovs[i] = xyz;
            aovs[n + i] = xyz * xyz;
        }
        first
    }
}
