//! Sensors: what measures the light. Cameras turn a film position into a ray; each sensor
//! owns its film description and its sampler, as in Mitsuba 3.

mod fov;
mod perspective;
mod thinlens;

pub use fov::{FovAxis, FieldOfView};
pub use perspective::Perspective;
pub use thinlens::ThinLens;

use glam::Vec2;

use crate::film::Film;
use crate::geometry::Ray;
use crate::sampling::Sampler;

/// The sensor models. Closed enum: one variant per sensor plugin.
#[derive(Clone, Debug)]
pub enum SensorKind {
    Perspective(Perspective),
    ThinLens(ThinLens),
}

/// A sensor with its film and sampler.
#[derive(Clone, Debug)]
pub struct Sensor {
    pub kind: SensorKind,
    pub film: Film,
    pub sampler: Sampler,
    /// The sensor's `id` in the scene file (empty when it has none).
    pub id: String,
}

impl Sensor {
    /// A ray for the film position `film_uv ∈ [0,1]²` ((0,0) = top-left corner of the image)
    /// and aperture sample `aperture_u ∈ [0,1]²`. Cameras have unit importance weight.
    #[inline]
    pub fn sample_ray(&self, film_uv: Vec2, aperture_u: Vec2) -> Ray {
        match &self.kind {
            SensorKind::Perspective(c) => c.sample_ray(film_uv),
            SensorKind::ThinLens(c) => c.sample_ray(film_uv, aperture_u),
        }
    }
}
