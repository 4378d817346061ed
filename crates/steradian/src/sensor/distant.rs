//! `distant`: a meter of the radiance leaving the scene along one direction, averaged over a
//! cross section (Mitsuba 3's distant radiancemeter, the adjoint of a `directional` light).
//!
//! | parameter   | type               | default  | meaning |
//! |-------------|--------------------|----------|---------|
//! | `to_world`  | transform          | identity | the rays travel along its +z; its x and y span the cross section |
//! | `direction` | vector             | —        | alternative to `to_world` (not both): the rays travel along it (normalised) |
//! | `target`    | point or `<shape>` | none     | where the rays aim (below) |
//! | film        | `hdrfilm`          | —        | must be 1×1 (Mitsuba's default 768×576 film is refused, as Mitsuba refuses it) |
//!
//! Every ray travels along d = `to_world`·(0, 0, 1) and starts outside the scene; the value is
//! the mean of the radiance L (W/(m²·sr)) arriving back along −d, i.e. leaving the scene
//! towards a viewer infinitely far away in direction −d. Where the rays aim:
//! - no `target`: uniformly over the disk that is the cross section of the scene's bounding
//!   sphere (centre c, radius R, Mitsuba's sphere of the scene's bounding box, widened by its
//!   ray epsilon); the ray starts at c + R·(x·u + y·v) − R·d, (u, v) uniform on the unit disk.
//!   Rays that miss the scene see the environment (or nothing), so the value depends on the
//!   scene's extent: Mitsuba advises a target.
//! - a point p: every ray aims at p and starts at p − 2R·d;
//! - a shape: at points uniform by area on it (the shape is not part of the scene, it only
//!   places the aim points), each ray starting 2R·d before its point.
//!
//! Every sample has weight 1 (Mitsuba's weight 1/(pdf·area) is 1 for uniform area sampling),
//! and the film's filter plays no part (the film is one pixel; Mitsuba's weighted mean with a
//! filter wider than the pixel has the same expectation).
//!
//! Where steradian differs: d is normalised, so a `to_world` that scales still gives unit
//! directions (Mitsuba traces an unnormalised d, whose hits it measures in units of |d|).

use glam::{Vec2, Vec3};

use crate::geometry::{is_positive, Aabb, Frame, Ray, Transform};
use crate::sampling::warp::square_to_uniform_disk_concentric;
use crate::shape::Shape;

/// Where a distant sensor's rays aim.
#[derive(Clone, Debug)]
pub enum DistantTarget {
    /// The cross section of the scene's bounding sphere.
    BoundingSphere,
    /// One point, m.
    Point(Vec3),
    /// Points uniform by area on a shape that is not rendered.
    Shape(Box<Shape>),
}

#[derive(Clone, Debug)]
pub struct Distant {
    /// Unit direction the rays travel in.
    pub direction: Vec3,
    /// The cross section's axes (`to_world`'s x and y), m per unit of the disk.
    x: Vec3,
    y: Vec3,
    pub target: DistantTarget,
    /// The scene's bounding sphere (centre, radius in m), set by [`Distant::set_scene`].
    center: Vec3,
    radius: f32,
}

/// Mitsuba's ray epsilon for single precision (1500 ulp of 1), by which it widens the scene's
/// bounding sphere.
const RAY_EPSILON: f32 = 1500.0 * f32::EPSILON / 2.0;

impl Distant {
    /// The sensor whose rays travel along `to_world`'s +z.
    pub fn new(to_world: &Transform, target: DistantTarget) -> Result<Distant, String> {
        let d = to_world.vector(Vec3::Z);
        let len = d.length();
        if !is_positive(len) || !len.is_finite() {
            return Err("to_world maps +z to a zero or non-finite direction".into());
        }
        if let DistantTarget::Point(p) = target {
            if !p.is_finite() {
                return Err(format!("target {p} is not finite"));
            }
        }
        Ok(Distant {
            direction: d / len,
            x: to_world.vector(Vec3::X),
            y: to_world.vector(Vec3::Y),
            target,
            center: Vec3::ZERO,
            radius: RAY_EPSILON,
        })
    }

    /// The sensor whose rays travel along `direction` (Mitsuba's `look_at` from the origin
    /// towards it, with the up vector of its coordinate system).
    pub fn along(direction: Vec3, target: DistantTarget) -> Result<Distant, String> {
        let len = direction.length();
        if !is_positive(len) || !len.is_finite() {
            return Err(format!("direction {direction} must be a non-zero finite vector"));
        }
        let d = direction / len;
        let up = Frame::from_normal(d).t;
        let to_world = Transform::look_at(Vec3::ZERO, d, up).map_err(|e| e.to_string())?;
        Distant::new(&to_world, target)
    }

    /// Places the rays' origins outside the scene whose geometry `bounds` encloses.
    pub fn set_scene(&mut self, bounds: &Aabb) {
        let (center, radius) = bounds.bounding_sphere();
        self.center = center;
        self.radius = (radius * (1.0 + RAY_EPSILON)).max(RAY_EPSILON);
    }

    /// The ray for the 2-D sample `u` (which picks the aim point).
    #[inline]
    pub fn ray(&self, u: Vec2) -> Ray {
        let d = self.direction;
        let o = match &self.target {
            DistantTarget::BoundingSphere => {
                let w = square_to_uniform_disk_concentric(u);
                self.center + (self.x * w.x + self.y * w.y - d) * self.radius
            }
            DistantTarget::Point(p) => *p - 2.0 * self.radius * d,
            DistantTarget::Shape(s) => s.sample_position(u).p - 2.0 * self.radius * d,
        };
        Ray::infinite(o, d)
    }
}
