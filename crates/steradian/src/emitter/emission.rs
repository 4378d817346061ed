//! Rays leaving the lights: where particle tracing (`ptracer`) starts its paths.
//!
//! [`Emitter::sample_ray`] draws a ray from the light's emission and returns it with the weight
//! Φ-density ratio `Le·cos/(pdf_A·pdf_ω)` (W, per channel), so that the mean weight of the rays
//! is the light's flux (through the scene's bounding sphere for lights at infinity, as
//! [`Emitter::flux`] counts it):
//!
//! | light | position | direction | weight |
//! |---|---|---|---|
//! | `area` | uniform by area on the shape | cosine-weighted, front side | L·π·A |
//! | `point` | the light | uniform sphere | 4π·I |
//! | `spot` | the light | uniform in the cutoff cone | I(ω)·2π(1 − cos cutoff) |
//! | `luminaire` | the light | the table's flux sampling | I(ω)/p(ω) |
//! | `directional` | uniform on the disk of the bounding sphere's radius R across the beam, a radius upstream of the centre | the beam | π R²·E |
//! | `constant` | as `directional`, across the sampled direction | uniform sphere | 4π·π R²·L |
//! | `envmap` | as `constant` | the map's importance sampling | π R²·L(ω)/pdf(ω) |
//! | `projector` | the pinhole | uniform over the image on the plane z = 1 | I(ω)/p(ω) = π·scale·E(uv)·A (rigid `to_world`) |

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::Emitter;
use crate::geometry::{offset_ray_origin, Frame, Ray};
use crate::sampling::warp;
use crate::shape::Shape;
use crate::texture::TexturePoint;
use crate::Spectrum;

/// A ray leaving a light and its weight (W: flux per unit of the sampling densities).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmittedRay {
    pub ray: Ray,
    pub weight: Spectrum,
}

/// The start of a ray from infinity travelling along `d` (unit) into the bounding sphere
/// (`center`, `radius`): a point uniform on the disk across `d`, a radius upstream, and the
/// disk's area.
fn from_infinity(d: Vec3, center: Vec3, radius: f32, u: Vec2) -> (Ray, f32) {
    let frame = Frame::from_normal(d);
    let disk = warp::square_to_uniform_disk_concentric(u) * radius;
    let o = center + frame.to_world(Vec3::new(disk.x, disk.y, 0.0)) - d * radius;
    (Ray::infinite(o, d), PI * radius * radius)
}

impl Emitter {
    /// A ray leaving the light: `u_pos` picks its start, `u_dir` its direction (see the
    /// module documentation); `(center, radius)` bound the scene. `None` when the light emits
    /// nothing there or cannot be sampled so.
    #[inline]
    pub fn sample_ray(
        &self,
        shapes: &[Shape],
        (center, radius): (Vec3, f32),
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmittedRay> {
        let emitted = match self {
            Emitter::Area(e) => {
                let ps = shapes[e.shape as usize].sample_position(u_pos);
                if !crate::geometry::is_positive(ps.pdf_area) {
                    return None;
                }
                let local = warp::square_to_cosine_hemisphere(u_dir);
                let d = Frame::from_normal(ps.n).to_world(local);
                let le = e.radiance.eval(TexturePoint::at_uv(ps.uv));
                EmittedRay {
                    ray: Ray::infinite(offset_ray_origin(ps.p, ps.n, d), d),
                    weight: le * (PI / ps.pdf_area),
                }
            }
            Emitter::Point(e) => EmittedRay {
                ray: Ray::infinite(e.position, warp::square_to_uniform_sphere(u_dir)),
                weight: e.intensity * (4.0 * PI),
            },
            Emitter::Luminaire(e) => {
                let (d, weight) = e.sample_emission(u_dir)?;
                EmittedRay { ray: Ray::infinite(e.position, d), weight }
            }
            Emitter::Spot(e) => {
                let one_minus = 1.0 - e.cos_cutoff();
                let d = e.frame.to_world(warp::square_to_uniform_cone(u_dir, one_minus));
                EmittedRay {
                    ray: Ray::infinite(e.position, d),
                    weight: e.intensity_towards(d) * (2.0 * PI * one_minus),
                }
            }
            Emitter::Directional(e) => {
                let (ray, area) = from_infinity(e.direction, center, radius, u_pos);
                EmittedRay { ray, weight: e.irradiance * area }
            }
            Emitter::Constant(e) => {
                let d = warp::square_to_uniform_sphere(u_dir);
                let (ray, area) = from_infinity(d, center, radius, u_pos);
                EmittedRay { ray, weight: e.radiance * (area / warp::UNIFORM_SPHERE_PDF) }
            }
            Emitter::EnvMap(e) => {
                let s = e.sample_direction(u_dir)?;
                let (ray, area) = from_infinity(-s.wi, center, radius, u_pos);
                EmittedRay { ray, weight: s.weight * area }
            }
            Emitter::SunSky(e) => {
                let s = e.sample_direction(u_dir)?;
                let (ray, area) = from_infinity(-s.wi, center, radius, u_pos);
                EmittedRay { ray, weight: s.weight * area }
            }
            Emitter::LuminousOpening(e) => {
                let ps = shapes[e.shape as usize].sample_position(u_pos);
                let (d, weight) = e.sample_emission(ps.n, ps.pdf_area, u_dir)?;
                EmittedRay { ray: Ray::infinite(offset_ray_origin(ps.p, ps.n, d), d), weight }
            }
            Emitter::Sun(e) => {
                let s = e.sample_direction(u_dir)?;
                let (ray, area) = from_infinity(-s.wi, center, radius, u_pos);
                EmittedRay { ray, weight: s.weight * area }
            }
            Emitter::Projector(e) => {
                let (d, weight) = e.sample_emission(u_dir)?;
                EmittedRay { ray: Ray::infinite(e.position(), d), weight }
            }
        };
        (emitted.weight != Spectrum::ZERO && emitted.weight.is_finite()).then_some(emitted)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emitter::{AreaLight, ConstantEnvironment, PointLight, SpotLight};
    use crate::geometry::Transform;
    use crate::sampling::Pcg32;
    use crate::shape::Rectangle;
    use crate::texture::Texture;

    /// The mean weight of the rays is the light's flux ([`Emitter::flux`]), within 4
    /// standard errors, for the lights whose flux has a closed form.
    #[test]
    fn mean_ray_weight_is_the_flux() {
        let shapes = vec![Shape::Rectangle(Rectangle::new(
            &Transform::scale(Vec3::new(2.0, 0.5, 1.0)).unwrap(),
            false,
        ))];
        let spot = SpotLight::new(
            &Transform::IDENTITY,
            Spectrum::splat(3.0),
            30f32.to_radians(),
            20f32.to_radians(),
        )
        .unwrap();
        // a projector whose image is brighter at one corner, aimed along a tilted axis
        // (nearest lookups: the mean over the image is the pixels' mean, as `flux` takes it)
        use crate::texture::{Bitmap, FilterType, ImageFormat, LoadedImage, UvTransform, WrapMode};
        let data = vec![4.0, 1.0, 1.0, 0.25];
        let img = LoadedImage { width: 2, height: 2, channels: 1, data, format: ImageFormat::Exr };
        let image = Bitmap::new(
            "e",
            img,
            true,
            FilterType::Nearest,
            WrapMode::Clamp,
            UvTransform::IDENTITY,
        )
        .unwrap();
        let projector = crate::emitter::Projector::new(
            &Transform::look_at(Vec3::ONE, Vec3::new(0.3, -1.0, 0.2), Vec3::Y).unwrap(),
            Texture::Bitmap(image),
            1.5,
            50f32.to_radians(),
            2.0,
        );
        let lights = [
            Emitter::Projector(projector),
            Emitter::Area(AreaLight::new(0, Texture::Constant(Spectrum::splat(2.0)))),
            Emitter::Point(PointLight::new(Vec3::ONE, Spectrum::splat(1.5))),
            Emitter::Spot(spot),
            Emitter::Constant(ConstantEnvironment::new(Spectrum::splat(0.7))),
        ];
        let sphere = (Vec3::ZERO, 3.0);
        for light in &lights {
            let mut rng = Pcg32::new(11, 2);
            let n = 100_000;
            let (mut sum, mut sum2) = (0.0f64, 0.0f64);
            for _ in 0..n {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let v = Vec2::new(rng.next_f32(), rng.next_f32());
                let w = light.sample_ray(&shapes, sphere, u, v).map_or(0.0, |r| r.weight.x as f64);
                sum += w;
                sum2 += w * w;
            }
            let mean = sum / n as f64;
            let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt().max(1e-9);
            let flux = light.flux(&shapes, sphere.1).x as f64;
            assert!(
                (mean - flux).abs() < 4.0 * se + 1e-4 * flux,
                "{light:?}: {mean} ± {se} vs {flux}"
            );
        }
    }
}
