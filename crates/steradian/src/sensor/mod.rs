//! Sensors: what measures the light. Cameras turn a film position into a ray; each sensor
//! owns its film description and its sampler, as in Mitsuba 3.

mod fov;
mod irradiancemeter;
mod perspective;
mod radiancemeter;
mod thinlens;

pub use fov::{FieldOfView, FovAxis};
pub use irradiancemeter::IrradianceMeter;
pub use perspective::Perspective;
pub use radiancemeter::RadianceMeter;
pub use thinlens::ThinLens;

use glam::Vec2;

use crate::film::Film;
use crate::geometry::Ray;
use crate::integrator::{estimate_irradiance, Integrator};
use crate::sampling::{PixelSampler, Sampler};
use crate::scene::Scene;
use crate::Spectrum;

/// The sensor models. Closed enum: one variant per sensor plugin.
#[derive(Clone, Debug)]
pub enum SensorKind {
    Perspective(Perspective),
    ThinLens(ThinLens),
    RadianceMeter(RadianceMeter),
    IrradianceMeter(IrradianceMeter),
}

/// The radiometric quantity a sensor reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// W/(m²·sr)
    Radiance,
    /// W/m²
    Irradiance,
}

impl Quantity {
    pub fn unit(&self) -> &'static str {
        match self {
            Quantity::Radiance => "W/(m²·sr)",
            Quantity::Irradiance => "W/m²",
        }
    }
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
    /// One sample of the sensor's measurement at film position `film_uv ∈ [0,1]²` ((0,0) =
    /// top-left corner of the image): for cameras the radiance arriving along the ray through
    /// that position (the next two dimensions of `sampler` choose the aperture point), for
    /// meters their quantity (film position plays no part).
    #[inline]
    pub fn measure(
        &self,
        scene: &Scene,
        integrator: &Integrator,
        film_uv: Vec2,
        sampler: &mut PixelSampler,
    ) -> Spectrum {
        if let SensorKind::IrradianceMeter(m) = &self.kind {
            let ps = scene.shapes[m.shape as usize].sample_position(sampler.next_2d());
            return estimate_irradiance(scene, integrator, ps.p, ps.n, sampler);
        }
        match self.start_ray(film_uv, sampler) {
            Some(ray) => integrator.li(scene, &ray, sampler),
            None => Spectrum::ZERO,
        }
    }

    /// For cameras, the ray through film position `film_uv` (consuming two dimensions of
    /// `sampler` for the aperture); `None` for meters.
    #[inline]
    pub fn camera_ray(&self, film_uv: Vec2, sampler: &mut PixelSampler) -> Option<Ray> {
        let aperture = sampler.next_2d();
        match &self.kind {
            SensorKind::Perspective(c) => Some(c.sample_ray(film_uv)),
            SensorKind::ThinLens(c) => Some(c.sample_ray(film_uv, aperture)),
            SensorKind::RadianceMeter(_) | SensorKind::IrradianceMeter(_) => None,
        }
    }

    /// The ray a sample starts with, for cameras (through film position `film_uv`) and
    /// radiance meters; `None` for irradiance meters, whose samples start on a surface.
    #[inline]
    pub fn start_ray(&self, film_uv: Vec2, sampler: &mut PixelSampler) -> Option<Ray> {
        match &self.kind {
            SensorKind::RadianceMeter(m) => Some(m.ray()),
            SensorKind::IrradianceMeter(_) => None,
            SensorKind::Perspective(_) | SensorKind::ThinLens(_) => {
                self.camera_ray(film_uv, sampler)
            }
        }
    }

    /// What the sensor measures.
    pub fn quantity(&self) -> Quantity {
        match self.kind {
            SensorKind::Perspective(_) | SensorKind::ThinLens(_) | SensorKind::RadianceMeter(_) => {
                Quantity::Radiance
            }
            SensorKind::IrradianceMeter(_) => Quantity::Irradiance,
        }
    }

    /// True for sensors whose samples do not depend on the film position (meters): the film's
    /// reconstruction filter plays no part and every sample has weight 1.
    pub fn is_meter(&self) -> bool {
        matches!(self.kind, SensorKind::RadianceMeter(_) | SensorKind::IrradianceMeter(_))
    }
}
