//! `projector`: a pinhole that projects an image into the scene, the reciprocal of the
//! `perspective` camera (same field-of-view parameters and pixel-to-direction map).
//!
//! | parameter      | type           | default   | meaning |
//! |----------------|----------------|-----------|---------|
//! | `irradiance`   | texture/spectrum | required | E(uv): the image, as irradiance (W/m², up to π, see below) on the plane z = 1 |
//! | `scale`        | float          | 1         | factor on `irradiance` |
//! | `to_world`     | transform      | identity  | the pinhole sits at the origin and looks along +z |
//! | `fov`, `fov_axis`, `focal_length` | | 50 mm | as `perspective`, with the image's aspect ratio |
//!
//! A point p, at p_l = (x, y, z) in the projector's frame (z > 0), sees the image at
//! uv = (½ − ½·x/(z tan φx), ½ − ½·y/(z tan φy)) (outside [0, 1]² it is dark), φx, φy the half
//! fields of view (tan φy = tan φx / aspect, aspect = the image's width/height), and receives
//! along the direction to the pinhole the delta-light value
//! π·scale·E(uv)/(z²·cos θ), θ between the axis and the direction towards p: Mitsuba 3's
//! value, which makes the irradiance on the plane z = 1 exactly π·scale·E(uv) (cos θ of the
//! plane times dist² cos³θ = z² cos θ). Its flux, for choosing among lights, is π·scale·Ē
//! times the image's area 4 tan φx tan φy on that plane.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{EmitterSample, Support};
use crate::geometry::{is_positive, Transform};
use crate::texture::{Texture, TexturePoint};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Projector {
    position: Vec3,
    /// to_world applied to +z (not normalised, as Mitsuba takes it).
    axis: Vec3,
    to_world: Transform,
    to_local: Transform,
    /// The image (boxed: untextured lights keep the emitter enum small).
    pub irradiance: Box<Texture>,
    pub scale: f32,
    /// tan φx, tan φy.
    tan_half: Vec2,
}

impl Projector {
    /// Default `scale` (Mitsuba's).
    pub const DEFAULT_SCALE: f32 = 1.0;

    /// `x_fov` in radians for the image's aspect ratio `aspect` (width/height).
    pub fn new(
        to_world: &Transform,
        irradiance: Texture,
        scale: f32,
        x_fov: f32,
        aspect: f32,
    ) -> Self {
        let tx = (x_fov / 2.0).tan();
        Projector {
            position: to_world.point(Vec3::ZERO),
            axis: to_world.vector(Vec3::Z),
            to_world: *to_world,
            to_local: to_world.inverse(),
            irradiance: Box::new(irradiance),
            scale,
            tan_half: Vec2::new(tx, tx / aspect),
        }
    }

    /// The image coordinates that the point `p_l` (projector frame, z > 0) sees.
    #[inline]
    fn image_uv(&self, p_l: Vec3) -> Vec2 {
        Vec2::new(
            0.5 - 0.5 * p_l.x / (p_l.z * self.tan_half.x),
            0.5 - 0.5 * p_l.y / (p_l.z * self.tan_half.y),
        )
    }

    #[inline]
    pub fn sample_direction(&self, p: Vec3) -> Option<EmitterSample> {
        let p_l = self.to_local.point(p);
        if p_l.z <= 0.0 {
            return None;
        }
        let uv = self.image_uv(p_l);
        if !(uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()) {
            return None;
        }
        let (wi, dist, _) = super::towards(self.position, p)?;
        let cos = -self.axis.dot(wi);
        let e = self.irradiance.eval(TexturePoint::at_uv(uv));
        if !is_positive(cos) || e == Spectrum::ZERO {
            return None;
        }
        let weight = e * (PI * self.scale / (p_l.z * p_l.z * cos));
        Some(EmitterSample { wi, dist, pdf: 1.0, weight, support: Support::Delta })
    }

    /// Where the pinhole is.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// A direction of the light leaving the pinhole, for particle tracing: the image point
    /// uniform on the plane z = 1 (area A = 4 tan φx tan φy, density 1/A), and the weight
    /// I(ω)/p(ω), I the intensity [`sample_direction`](Self::sample_direction) gives at unit
    /// distance and p(ω) = |q|²/(A·|a × b|·|n·ω|) the density of the direction through world
    /// point q (a, b the images of the plane's axes, n its world normal): π·scale·E(uv)·A for
    /// a rigid `to_world`, so that the rays' mean weight is [`flux`](Self::flux).
    pub fn sample_emission(&self, u: Vec2) -> Option<(Vec3, Spectrum)> {
        let t = self.tan_half;
        let q = Vec3::new((1.0 - 2.0 * u.x) * t.x, (1.0 - 2.0 * u.y) * t.y, 1.0);
        let w = self.to_world.vector(q);
        let dist2 = w.length_squared();
        let d = w / dist2.sqrt();
        let plane = self.to_world.vector(Vec3::X).cross(self.to_world.vector(Vec3::Y));
        let area = 4.0 * t.x * t.y;
        let pdf = dist2 / (area * plane.dot(d).abs());
        let s = self.sample_direction(self.position + d)?;
        let weight = s.weight / pdf;
        (is_positive(pdf) && weight.is_finite()).then_some((d, weight))
    }

    /// Φ = π·scale·Ē·4 tan φx tan φy (W, per channel).
    pub fn flux(&self) -> Spectrum {
        let area = 4.0 * self.tan_half.x * self.tan_half.y;
        self.irradiance.mean() * (PI * self.scale * area)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant image lights the plane z = 1 (facing the projector) with irradiance
    /// π·scale·E everywhere inside the image and nothing outside.
    #[test]
    fn constant_image_gives_constant_irradiance_on_the_unit_plane() {
        let to_world = Transform::translate(Vec3::new(1.0, 2.0, 3.0));
        let e = Spectrum::new(0.5, 1.0, 2.0);
        let pr = Projector::new(&to_world, Texture::Constant(e), 3.0, 60f32.to_radians(), 1.5);
        let tx = 30f32.to_radians().tan();
        for (x, y) in [(0.0, 0.0), (0.9 * tx, 0.0), (-0.5 * tx, 0.6 * tx / 1.5)] {
            let p = Vec3::new(1.0 + x, 2.0 + y, 4.0);
            let s = pr.sample_direction(p).expect("lit");
            // the plane's normal (0, 0, −1) faces the pinhole
            let irradiance = s.weight * -s.wi.z;
            let expect = e * (PI * 3.0);
            assert!(
                (irradiance - expect).abs().max_element() < 1e-4 * expect.max_element(),
                "{irradiance} vs {expect}"
            );
        }
        assert!(pr.sample_direction(Vec3::new(1.0 + 1.1 * tx, 2.0, 4.0)).is_none());
        assert!(pr.sample_direction(Vec3::new(1.0, 2.0, 2.0)).is_none(), "behind the pinhole");
    }
}
