//! Emitters: where light comes from, each in its own radiometric unit.
//!
//! | plugin        | quantity given            | unit        |
//! |---------------|---------------------------|-------------|
//! | `area`        | radiance L of a surface   | W/(m²·sr)   |
//! | `point`       | radiant intensity I       | W/sr        |
//! | `spot`        | radiant intensity I on axis | W/sr      |
//! | `directional` | irradiance H ⟂ the beam   | W/m²        |
//! | `constant`    | radiance L of the sky     | W/(m²·sr)   |
//! | `envmap`      | radiance L of the sky, per pixel × `scale` | W/(m²·sr) |
//! | `projector`   | irradiance E of an image on the plane z = 1 (× π, × `scale`) | W/m² |
//! | `ciesky`      | luminance of a CIE standard sky (overcast, general types 1–15), as an `envmap` | cd/m² (→ W/(m²·sr) at 683 lm/W) |
//! | `luminaire`   | luminous intensity I(γ, C) of a photometric file | cd (→ W/sr at 683 lm/W) |
//! | `sun`         | direct normal irradiance of the solar disk (or illuminance, lx) | W/m² |
//!
//! `sample_direction` answers "from which direction does this light reach point p, and with
//! what weight?": the returned `weight` is the incident radiance divided by the solid-angle
//! density (for delta lights: the irradiance a surface facing the light receives, I/r² or H).
//! Multiplying by ρ·|cos θ| gives the reflected radiance estimate.

mod area;
mod ciesky;
mod constant;
mod directional;
mod emission;
mod envmap;
mod light_selection;
mod luminaire;
mod luminous_opening;
mod photometric;
mod point;
mod projector;
mod spot;
mod sun;
mod sunsky;

pub use area::AreaLight;
pub use ciesky::{cie_sky, horizontal_illuminance, SkyLevel, SkyModel};
pub use constant::ConstantEnvironment;
pub use directional::DirectionalLight;
pub use emission::EmittedRay;
pub use envmap::EnvironmentMap;
pub use light_selection::LightSelection;
pub use luminaire::{Luminaire, LUMENS_PER_WATT};
pub use luminous_opening::LuminousOpening;
pub use photometric::from_photometric;
pub use point::PointLight;
pub use projector::Projector;
pub use spot::SpotLight;
pub use sun::Sun;
pub use sunsky::{LocationTime, SunModel, SunPosition, SunSky, SunSkyParams};

use glam::{Vec2, Vec3};

use crate::geometry::SurfacePoint;
use crate::shape::Shape;
use crate::Spectrum;

/// Whether a light can be hit by a ray or only reached by sampling it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// Occupies a solid angle (area lights, environments): has a density, MIS applies.
    Extended,
    /// A Dirac delta in position or direction (point, spot, directional).
    Delta,
}

/// A sampled direction towards a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterSample {
    /// Unit direction from the reference point towards the light.
    pub wi: Vec3,
    /// Distance to the sampled point, m (`f32::INFINITY` for lights at infinity).
    pub dist: f32,
    /// Density of `wi` in 1/sr (1 for delta lights).
    pub pdf: f32,
    /// Incident radiance / pdf; for delta lights the irradiance on a surface facing the light
    /// (W/m²).
    pub weight: Spectrum,
    pub support: Support,
}

/// An emitter. Closed enum: one variant per emitter plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Emitter {
    Area(AreaLight),
    Point(PointLight),
    Spot(SpotLight),
    Directional(DirectionalLight),
    Constant(ConstantEnvironment),
    EnvMap(EnvironmentMap),
    /// Mitsuba's `sunsky`: the Hosek–Wilkie sky and sun, an environment (boxed: its model
    /// takes 544 bytes).
    SunSky(Box<SunSky>),
    Projector(Projector),
    Luminaire(Luminaire),
    /// The solar disk (steradian's own), at infinity beside the environment.
    Sun(Sun),
    /// A `luminaire` nested in a flat shape: an area source over its luminous opening.
    LuminousOpening(LuminousOpening),
}

impl Emitter {
    /// Samples a direction from `p` towards the light (no visibility test).
    #[inline]
    pub fn sample_direction(&self, shapes: &[Shape], p: Vec3, u: Vec2) -> Option<EmitterSample> {
        match self {
            Emitter::Area(e) => e.sample_direction(shapes, p, u),
            Emitter::Point(e) => e.sample_direction(p),
            Emitter::Luminaire(e) => e.sample_direction(p),
            Emitter::Spot(e) => e.sample_direction(p),
            Emitter::Directional(e) => e.sample_direction(p),
            Emitter::Constant(e) => e.sample_direction(p, u),
            Emitter::EnvMap(e) => e.sample_direction(u),
            Emitter::SunSky(e) => e.sample_direction(u),
            Emitter::Projector(e) => e.sample_direction(p),
            Emitter::Sun(e) => e.sample_direction(u),
            Emitter::LuminousOpening(e) => e.sample_direction(shapes, p, u),
        }
    }

    /// Solid-angle density with which `sample_direction` from `p` proposes the point `light`
    /// seen in direction `wi` (0 for delta lights).
    #[inline]
    pub fn pdf_direction(&self, shapes: &[Shape], p: Vec3, wi: Vec3, light: &SurfacePoint) -> f32 {
        match self {
            Emitter::Area(e) => e.pdf_direction(shapes, p, wi, light),
            Emitter::Constant(e) => e.pdf_direction(wi),
            Emitter::EnvMap(e) => e.pdf_direction(wi),
            Emitter::SunSky(e) => e.pdf_direction(wi),
            Emitter::Sun(e) => e.radiance_and_pdf(wi).1,
            Emitter::LuminousOpening(e) => e.pdf_direction(shapes, p, wi, light),
            Emitter::Point(_)
            | Emitter::Luminaire(_)
            | Emitter::Spot(_)
            | Emitter::Directional(_)
            | Emitter::Projector(_) => 0.0,
        }
    }

    /// Radiance arriving along a ray that ends on this light: for area lights the radiance
    /// leaving the surface point with shading normal `n` towards `wo` (away from the light), for
    /// environments the radiance from direction `-wo`.
    #[inline]
    pub fn radiance(&self, wo: Vec3, n: Vec3, uv: Vec2) -> Spectrum {
        match self {
            Emitter::Area(e) => e.radiance(wo, n, uv),
            Emitter::Constant(e) => e.radiance(),
            Emitter::EnvMap(e) => e.radiance(-wo),
            Emitter::SunSky(e) => e.radiance(-wo),
            Emitter::Sun(e) => e.radiance_and_pdf(-wo).0,
            Emitter::LuminousOpening(e) => e.radiance(wo, n),
            Emitter::Point(_)
            | Emitter::Luminaire(_)
            | Emitter::Spot(_)
            | Emitter::Directional(_)
            | Emitter::Projector(_) => Spectrum::ZERO,
        }
    }

    /// For lights at infinity: the radiance arriving from world direction `d` (towards the
    /// sky) and the solid-angle density with which `sample_direction` proposes `d`, found with
    /// one lookup; (0, 0) for other lights.
    #[inline]
    pub fn radiance_and_pdf_from(&self, d: Vec3) -> (Spectrum, f32) {
        match self {
            Emitter::Constant(e) => (e.radiance(), e.pdf_direction(d)),
            Emitter::EnvMap(e) => e.radiance_and_pdf(d),
            Emitter::SunSky(e) => e.radiance_and_pdf(d),
            Emitter::Sun(e) => e.radiance_and_pdf(d),
            Emitter::Area(_)
            | Emitter::LuminousOpening(_)
            | Emitter::Point(_)
            | Emitter::Luminaire(_)
            | Emitter::Spot(_)
            | Emitter::Directional(_)
            | Emitter::Projector(_) => (Spectrum::ZERO, 0.0),
        }
    }

    #[inline]
    pub fn support(&self) -> Support {
        match self {
            Emitter::Area(_)
            | Emitter::LuminousOpening(_)
            | Emitter::Constant(_)
            | Emitter::EnvMap(_)
            | Emitter::SunSky(_)
            | Emitter::Sun(_) => Support::Extended,
            Emitter::Point(_)
            | Emitter::Luminaire(_)
            | Emitter::Spot(_)
            | Emitter::Directional(_)
            | Emitter::Projector(_) => Support::Delta,
        }
    }

    /// Whether light sampling alone estimates this light at a Lambertian point `p` with bounded
    /// weights (see [`Shape::light_sampling_bounded`]). Delta lights: yes (no ray can hit them,
    /// so a BSDF sample adds nothing); environments: no (their uniform directions waste the
    /// half below the horizon and ignore the cosine).
    #[inline]
    pub fn light_sampling_bounded(&self, shapes: &[Shape], p: Vec3) -> bool {
        match self {
            Emitter::Area(e) => shapes[e.shape as usize].light_sampling_bounded(p),
            Emitter::Point(_)
            | Emitter::Luminaire(_)
            | Emitter::Spot(_)
            | Emitter::Directional(_)
            | Emitter::Projector(_) => true,
            // uniform in a small cone: the weight L·Ω·cos is bounded
            Emitter::Sun(_) => true,
            // I(ω)/(A cos θ) grows towards grazing angles where the table does not vanish
            Emitter::Constant(_)
            | Emitter::EnvMap(_)
            | Emitter::SunSky(_)
            | Emitter::LuminousOpening(_) => false,
        }
    }

    /// True for the environment (the sky around the scene: at most one per scene), which
    /// rays escaping the scene see. The sun, at infinity too, is not one: it goes beside it.
    #[inline]
    pub fn is_environment(&self) -> bool {
        matches!(self, Emitter::Constant(_) | Emitter::EnvMap(_) | Emitter::SunSky(_))
    }

    /// Total emitted flux Φ in W (per channel); for lights at infinity, the flux through the
    /// scene's bounding sphere of radius `scene_radius`.
    pub fn flux(&self, shapes: &[Shape], scene_radius: f32) -> Spectrum {
        use std::f32::consts::PI;
        match self {
            Emitter::Area(e) => e.radiance.mean() * PI * shapes[e.shape as usize].surface_area(),
            Emitter::Point(e) => e.intensity * 4.0 * PI,
            Emitter::Luminaire(e) => e.flux(),
            Emitter::Spot(e) => e.intensity * e.solid_angle_factor(),
            Emitter::Directional(e) => e.irradiance * PI * scene_radius * scene_radius,
            Emitter::Constant(e) => e.radiance * 4.0 * PI * PI * scene_radius * scene_radius,
            Emitter::EnvMap(e) => e.integral() * PI * scene_radius * scene_radius,
            Emitter::SunSky(e) => e.integral() * PI * scene_radius * scene_radius,
            Emitter::Projector(e) => e.flux(),
            Emitter::Sun(e) => e.irradiance * PI * scene_radius * scene_radius,
            Emitter::LuminousOpening(e) => e.flux(),
        }
    }

    /// The shape an emitting surface belongs to (`area`, a nested `luminaire`); `None` for
    /// lights without one.
    #[inline]
    pub fn shape(&self) -> Option<u32> {
        match self {
            Emitter::Area(e) => Some(e.shape),
            Emitter::LuminousOpening(e) => Some(e.shape),
            _ => None,
        }
    }
}

/// The unit direction from `p` towards a light at `position`, the distance and its square
/// (m, m²); `None` when the two coincide.
#[inline]
pub(crate) fn towards(position: Vec3, p: Vec3) -> Option<(Vec3, f32, f32)> {
    let d = position - p;
    let dist2 = d.length_squared();
    if !crate::geometry::is_positive(dist2) {
        return None;
    }
    let dist = dist2.sqrt();
    Some((d / dist, dist, dist2))
}

#[cfg(test)]
mod tests;
