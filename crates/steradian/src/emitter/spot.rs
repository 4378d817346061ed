//! `spot`: a point light emitting into a cone, with a smooth fall-off at its edge.
//!
//! | parameter      | type     | default             | unit |
//! |----------------|----------|---------------------|------|
//! | `intensity`    | spectrum | 1                   | W/sr on the axis |
//! | `cutoff_angle` | float    | 20                  | degrees: no light beyond it |
//! | `beam_width`   | float    | 3/4 · cutoff_angle  | degrees: full intensity within it |
//! | `to_world`     | transform| identity            | the light sits at the origin and shines along +z |
//! | `texture`      | texture  | none                | a factor projected along the beam (e.g. a `bitmap` slide) |
//! | `luminous_intensity` | float | — | cd on the axis, instead of `intensity` (steradian's own; with `color`, `photometric.rs`) |
//! | `color` | spectrum | 1 (white) | the colour of a photometric light |
//!
//! Intensity at angle θ from the axis: I·f(θ)·τ(uv) with Mitsuba 3's fall-off f = 1 for
//! θ ≤ beam_width, (cutoff − θ)/(cutoff − beam_width) up to the cutoff, 0 beyond. With a
//! `texture`, τ is read as Mitsuba reads it: the direction d in the light's frame (through the
//! inverse of `to_world`, normalised) gives uv = ½ + ½·(d_x, d_y)/(d_z tan cutoff), so the image
//! spans the square that circumscribes the cutoff cone at unit distance; without one, τ = 1.
//! The flux used to choose among lights ignores τ (any positive choice is unbiased).

use glam::{Vec2, Vec3};

use super::{EmitterSample, Support};
use crate::geometry::{Frame, Transform};
use crate::param::ParamError;
use crate::texture::{Texture, TexturePoint};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    pub position: Vec3,
    /// Axis frame: `frame.n` is the beam direction.
    pub frame: Frame,
    pub intensity: Spectrum,
    /// Radians.
    pub cutoff: f32,
    /// Radians.
    pub beam_width: f32,
    cos_cutoff: f32,
    cos_beam_width: f32,
    /// The projected texture, when the scene gives one (boxed: it is large, and untextured
    /// spots keep the emitter enum small).
    pub slide: Option<Box<Slide>>,
}

/// A texture projected along a spot light's beam.
#[derive(Clone, Debug, PartialEq)]
pub struct Slide {
    pub texture: Texture,
    /// World → light frame (the inverse of `to_world`).
    to_local: Transform,
    /// tan(cutoff): the half-width of the image at unit distance along the axis.
    uv_factor: f32,
}

impl SpotLight {
    /// Default `intensity` on the axis (W/sr; Mitsuba's).
    pub const DEFAULT_INTENSITY: f32 = 1.0;
    /// Default `cutoff_angle`, in degrees as the scene gives it (Mitsuba's).
    pub const DEFAULT_CUTOFF_ANGLE: f32 = 20.0;
    /// Default `beam_width` as a fraction of `cutoff_angle` (Mitsuba's 3/4).
    pub const DEFAULT_BEAM_WIDTH_RATIO: f32 = 0.75;

    /// `cutoff` and `beam_width` in radians.
    pub fn new(
        to_world: &Transform,
        intensity: Spectrum,
        cutoff: f32,
        beam_width: f32,
    ) -> Result<Self, ParamError> {
        if !(cutoff > 0.0 && cutoff <= std::f32::consts::PI) {
            return Err(ParamError::new(
                "cutoff_angle",
                format!("cutoff_angle must lie in (0°, 180°], got {}°", cutoff.to_degrees()),
            ));
        }
        if !(beam_width > 0.0 && beam_width <= cutoff) {
            let reason = format!(
                "beam_width must lie in (0°, cutoff_angle = {}°], got {}°",
                cutoff.to_degrees(),
                beam_width.to_degrees()
            );
            return Err(ParamError::new("beam_width", reason).with_related("cutoff_angle"));
        }
        let axis = to_world.vector(Vec3::Z).normalize();
        Ok(SpotLight {
            position: to_world.point(Vec3::ZERO),
            frame: Frame::from_normal_tangent(axis, to_world.vector(Vec3::X)),
            intensity,
            cutoff,
            beam_width,
            cos_cutoff: cutoff.cos(),
            cos_beam_width: beam_width.cos(),
            slide: None,
        })
    }

    /// The light with `texture` projected along its beam (`to_world` as given to [`new`]).
    ///
    /// [`new`]: SpotLight::new
    pub fn with_texture(mut self, to_world: &Transform, texture: Texture) -> Self {
        let to_local = to_world.inverse();
        self.slide = Some(Box::new(Slide { texture, to_local, uv_factor: self.cutoff.tan() }));
        self
    }

    /// The intensity (W/sr) leaving the light along the unit direction `d` (world space):
    /// I·f(θ)·τ(uv).
    #[inline]
    pub fn intensity_towards(&self, d: Vec3) -> Spectrum {
        let f = self.falloff(d);
        if f <= 0.0 {
            return Spectrum::ZERO;
        }
        let i = self.intensity * f;
        match &self.slide {
            None => i,
            Some(slide) => {
                let l = slide.to_local.vector(d).normalize();
                let k = 0.5 / (l.z * slide.uv_factor);
                i * slide.texture.eval(TexturePoint::at_uv(Vec2::new(0.5 + l.x * k, 0.5 + l.y * k)))
            }
        }
    }

    /// cos(cutoff): directions at a larger angle from the axis get no light.
    #[inline]
    pub fn cos_cutoff(&self) -> f32 {
        self.cos_cutoff
    }

    /// The fall-off factor for a unit direction `d` leaving the light (world space).
    #[inline]
    pub fn falloff(&self, d: Vec3) -> f32 {
        let cos_t = d.dot(self.frame.n);
        if cos_t <= self.cos_cutoff {
            0.0
        } else if cos_t >= self.cos_beam_width {
            1.0
        } else {
            (self.cutoff - cos_t.clamp(-1.0, 1.0).acos()) / (self.cutoff - self.beam_width)
        }
    }

    /// ∫ f(θ) dω over the sphere, sr: flux = I·this.
    pub fn solid_angle_factor(&self) -> f32 {
        // full-intensity cap plus the linear ramp, integrated numerically (not hot).
        let n = 1024;
        let mut acc = 2.0 * std::f64::consts::PI * (1.0 - (self.beam_width as f64).cos());
        let (a, b) = (self.beam_width as f64, self.cutoff as f64);
        let h = (b - a) / n as f64;
        for i in 0..n {
            let t = a + (i as f64 + 0.5) * h;
            acc += 2.0 * std::f64::consts::PI * t.sin() * (b - t) / (b - a) * h;
        }
        acc as f32
    }

    #[inline]
    pub fn sample_direction(&self, p: Vec3) -> Option<EmitterSample> {
        let (wi, dist, dist2) = super::towards(self.position, p)?;
        let i = self.intensity_towards(-wi);
        if i == Spectrum::ZERO {
            return None;
        }
        Some(EmitterSample { wi, dist, pdf: 1.0, weight: i / dist2, support: Support::Delta })
    }
}
