//! `radiancemeter`: measures the radiance arriving along one ray.
//!
//! | parameter   | type      | default  | meaning |
//! |-------------|-----------|----------|---------|
//! | `origin`    | point     | —        | where the meter sits, m |
//! | `direction` | vector    | —        | where it looks (normalised) |
//! | `to_world`  | transform | identity | alternative to origin/direction: the meter sits at the origin and looks along +z |
//! | film        | `hdrfilm` | 1×1      | must be 1×1 |
//!
//! The value is the radiance L (W/(m²·sr)) arriving at `origin` from `direction`, i.e. leaving
//! the first surface hit towards the meter. There is no jitter: every sample traces the same
//! ray, and the film's filter plays no part.

use glam::Vec3;

use crate::geometry::is_positive;
use crate::geometry::{Ray, Transform};

#[derive(Clone, Debug)]
pub struct RadianceMeter {
    pub origin: Vec3,
    /// Unit direction the meter looks in.
    pub direction: Vec3,
}

impl RadianceMeter {
    pub fn new(origin: Vec3, direction: Vec3) -> Result<Self, String> {
        let len = direction.length();
        if !is_positive(len) || !len.is_finite() || !origin.is_finite() {
            return Err("origin must be finite and direction a non-zero finite vector".into());
        }
        Ok(RadianceMeter { origin, direction: direction / len })
    }

    /// The meter at `to_world`'s origin looking along its +z.
    pub fn from_transform(to_world: &Transform) -> Result<Self, String> {
        Self::new(to_world.point(Vec3::ZERO), to_world.vector(Vec3::Z))
    }

    #[inline]
    pub fn ray(&self) -> Ray {
        Ray::infinite(self.origin, self.direction)
    }
}
