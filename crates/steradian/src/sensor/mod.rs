//! Sensors: what measures the light. Cameras turn a film position into a ray; each sensor
//! owns its film description and its sampler, as in Mitsuba 3.

mod batch;
mod distant;
mod fov;
mod irradiancemeter;
pub mod orthographic;
mod perspective;
mod radiancemeter;
mod thinlens;
mod workplane;

pub use batch::Batch;
pub use distant::{Distant, DistantTarget};
pub use fov::{FieldOfView, FovAxis};
pub use irradiancemeter::IrradianceMeter;
pub use orthographic::Orthographic;
pub use perspective::{LensSample, Perspective, SensorConnection};
pub use radiancemeter::RadianceMeter;
pub use thinlens::ThinLens;
pub use workplane::{Workplane, WorkplaneMode, WorkplaneUnit};

use glam::{IVec2, UVec2, Vec2};

use crate::film::{Film, FilmWindow};
use crate::geometry::{Aabb, Ray};
use crate::sampling::{PixelSampler, Sampler};

/// The sensor models. Closed enum: one variant per sensor plugin.
#[derive(Clone, Debug)]
pub enum SensorKind {
    Perspective(Perspective),
    ThinLens(ThinLens),
    Orthographic(Orthographic),
    RadianceMeter(RadianceMeter),
    IrradianceMeter(IrradianceMeter),
    Batch(Batch),
    Distant(Distant),
    Workplane(Workplane),
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
    /// For cameras, the ray through film position `film_uv` (consuming two dimensions of
    /// `sampler` for the aperture); `None` for meters.
    #[inline]
    pub fn camera_ray(&self, film_uv: Vec2, sampler: &mut PixelSampler) -> Option<Ray> {
        let aperture = sampler.next_2d();
        self.kind.camera_ray_with(film_uv, aperture)
    }

    /// The ray a sample starts with, for cameras (through film position `film_uv`) and
    /// radiance meters; `None` for irradiance meters, whose samples start on a surface.
    #[inline]
    pub fn start_ray(&self, film_uv: Vec2, sampler: &mut PixelSampler) -> Option<Ray> {
        match &self.kind {
            SensorKind::RadianceMeter(m) => Some(m.ray()),
            SensorKind::Distant(m) => Some(m.ray(sampler.next_2d())),
            SensorKind::IrradianceMeter(_) | SensorKind::Workplane(_) => None,
            SensorKind::Perspective(_)
            | SensorKind::ThinLens(_)
            | SensorKind::Orthographic(_)
            | SensorKind::Batch(_) => self.camera_ray(film_uv, sampler),
        }
    }

    /// Tells the sensor the extent of the scene it measures (Mitsuba's `set_scene`): a
    /// `distant` sensor starts its rays outside `bounds`.
    pub fn set_scene(&mut self, bounds: &Aabb) {
        if let SensorKind::Distant(d) = &mut self.kind {
            d.set_scene(bounds);
        }
    }

    /// The point of the camera's lens a light path connects to (particle tracing), from the
    /// uniform sample `u`: the pinhole of `perspective`, a point drawn uniformly on the
    /// aperture of `thinlens`. `None` for the sensors particle tracing cannot connect to
    /// (`orthographic`, as in Mitsuba 3, whose `ptracer` has no connection to it; `batch`,
    /// meters).
    #[inline]
    pub fn sample_lens(&self, u: Vec2) -> Option<LensSample> {
        match &self.kind {
            SensorKind::Perspective(c) => Some(c.lens()),
            SensorKind::ThinLens(c) => Some(c.sample_lens(u)),
            _ => None,
        }
    }

    /// The connection from world point `p` to the camera through lens point `lens` (from
    /// [`Sensor::sample_lens`]) for particle tracing (Mitsuba's `sample_direction`); `None`
    /// outside the camera's view.
    #[inline]
    pub fn sample_direction(&self, lens: &LensSample, p: glam::Vec3) -> Option<SensorConnection> {
        match &self.kind {
            SensorKind::Perspective(c) => c.sample_direction(lens, p),
            SensorKind::ThinLens(c) => c.sample_direction(lens, p),
            _ => None,
        }
    }

    /// [`Sensor::sample_direction`] for light arriving from direction `wi` at infinity.
    #[inline]
    pub fn sample_direction_at_infinity(
        &self,
        lens: &LensSample,
        wi: glam::Vec3,
    ) -> Option<SensorConnection> {
        match &self.kind {
            SensorKind::Perspective(c) => c.sample_direction_at_infinity(lens, wi),
            SensorKind::ThinLens(c) => c.sample_direction_at_infinity(lens, wi),
            _ => None,
        }
    }

    /// What the sensor measures.
    pub fn quantity(&self) -> Quantity {
        match self.kind {
            SensorKind::Perspective(_)
            | SensorKind::ThinLens(_)
            | SensorKind::Orthographic(_)
            | SensorKind::Batch(_)
            | SensorKind::RadianceMeter(_)
            | SensorKind::Distant(_) => Quantity::Radiance,
            SensorKind::IrradianceMeter(_) | SensorKind::Workplane(_) => Quantity::Irradiance,
        }
    }

    /// True for sensors whose samples do not depend on the film position (meters): the film's
    /// reconstruction filter plays no part and every sample has weight 1.
    pub fn is_meter(&self) -> bool {
        matches!(
            self.kind,
            SensorKind::RadianceMeter(_)
                | SensorKind::IrradianceMeter(_)
                | SensorKind::Distant(_)
                | SensorKind::Workplane(_)
        )
    }
}

impl SensorKind {
    /// For cameras, the ray through film position `film_uv` with the 2-D aperture sample
    /// `aperture` (used by a thin lens); `None` for meters.
    #[inline]
    pub fn camera_ray_with(&self, film_uv: Vec2, aperture: Vec2) -> Option<Ray> {
        match self {
            SensorKind::Perspective(c) => Some(c.sample_ray(film_uv)),
            SensorKind::ThinLens(c) => Some(c.sample_ray(film_uv, aperture)),
            SensorKind::Orthographic(c) => Some(c.sample_ray(film_uv)),
            SensorKind::Batch(b) => b.sample_ray(film_uv, aperture),
            SensorKind::RadianceMeter(_)
            | SensorKind::IrradianceMeter(_)
            | SensorKind::Distant(_)
            | SensorKind::Workplane(_) => None,
        }
    }
}

/// Where on the film a camera sample lands: its pixel plus the sampler's first 2-D draw, in
/// pixels (where the film splats it), and the same as a fraction of the camera's full frame
/// (`film_uv`, what [`Sensor::start_ray`] takes; the film is `window` of that frame, all of it
/// unless cropped). The render and the branch-count pilot start every sample here.
#[inline]
pub fn film_position(pixel: UVec2, s: &mut PixelSampler, window: &FilmWindow) -> (Vec2, Vec2) {
    film_position_signed(pixel.as_ivec2(), s, window)
}

/// [`film_position`] for a pixel that may lie outside the film: the margin sampled around it
/// with `sample_border` (`film::SampleBorder`).
#[inline]
pub fn film_position_signed(
    pixel: IVec2,
    s: &mut PixelSampler,
    window: &FilmWindow,
) -> (Vec2, Vec2) {
    let pos = pixel.as_vec2() + s.next_2d();
    (pos, window.frame_uv(pos))
}
