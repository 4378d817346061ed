//! Volumes: values over space that a heterogeneous medium reads (`sigma_t`, `albedo`) and the
//! `volume` texture looks up at surface points, each filling the unit cube [0, 1]³ that its
//! `to_world` places: Mitsuba's `gridvolume` (`gridvolume.rs`) and `constvolume` (`value`,
//! spectrum, default 1; `to_world`).

use std::sync::Arc;

use glam::Vec3;

use super::gridvolume::GridVolume;
use crate::geometry::{Aabb, Transform};
use crate::Spectrum;

/// What a volume holds. Closed enum: one variant per Mitsuba volume plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum VolumeData {
    /// `gridvolume` (shared: one grid may serve several media).
    Grid(Arc<GridVolume>),
    /// `constvolume`: the same value everywhere.
    Const(Spectrum),
}

/// A volume placed in the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    pub data: VolumeData,
    /// World to the unit cube.
    to_local: Transform,
    /// The world bounds of the unit cube.
    bounds: Aabb,
}

impl Volume {
    /// Places `data`'s unit cube with `to_world`.
    pub fn new(data: VolumeData, to_world: Transform) -> Volume {
        let bounds = to_world.aabb(&Aabb::new(Vec3::ZERO, Vec3::ONE));
        Volume { data, to_local: to_world.inverse(), bounds }
    }

    /// A constant volume over the unit cube (identity placement).
    pub fn constant(v: Spectrum) -> Volume {
        Volume::new(VolumeData::Const(v), Transform::default())
    }

    /// World to the unit cube.
    #[inline]
    pub fn to_local(&self) -> &Transform {
        &self.to_local
    }

    /// The world bounds of the volume's unit cube.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The value at `p_local` in the unit cube.
    #[inline]
    pub fn eval_local(&self, p_local: Vec3) -> Spectrum {
        match &self.data {
            VolumeData::Grid(g) => g.eval(p_local),
            VolumeData::Const(v) => *v,
        }
    }

    /// The value at world position `p`.
    #[inline]
    pub fn eval(&self, p: Vec3) -> Spectrum {
        match &self.data {
            VolumeData::Grid(g) => g.eval(self.to_local.point(p)),
            VolumeData::Const(v) => *v,
        }
    }

    /// The largest value over the volume and its channels.
    pub fn max(&self) -> f32 {
        match &self.data {
            VolumeData::Grid(g) => g.max(),
            VolumeData::Const(v) => v.max_element(),
        }
    }

    /// The smallest value over the volume and its channels (for the loader's checks).
    pub fn min(&self) -> f32 {
        match &self.data {
            VolumeData::Grid(g) => g.min(),
            VolumeData::Const(v) => v.min_element(),
        }
    }
}
