use glam::{Vec2, Vec3};

use super::{Frame, Ray};

/// What a ray–primitive test returns before any shading data is computed: the distance and
/// the primitive's own parameters (barycentrics for triangles, (u, v) for analytic shapes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreliminaryHit {
    /// Distance along the (unit) ray direction, m.
    pub t: f32,
    /// Shape-specific surface parameters (triangle barycentrics b1, b2; analytic uv, which a
    /// shape may leave at zero and compute in its `interaction` instead).
    pub uv: Vec2,
    /// Index of the shape in the scene.
    pub shape: u32,
    /// Index of the primitive inside the shape (triangle index; 0 for analytic shapes).
    pub prim: u32,
    /// Index of the instance the shape was reached through ([`NO_INSTANCE`] for the scene's
    /// own shapes); `shape` is then the member's index in the instance's group.
    pub instance: u32,
}

/// [`PreliminaryHit::instance`] and [`SurfaceInteraction::instance`] of a shape that is not
/// instanced.
pub const NO_INSTANCE: u32 = u32::MAX;

/// A point on a surface with everything shading needs.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceInteraction {
    /// Position, m.
    pub p: Vec3,
    /// Distance from the ray origin, m.
    pub t: f32,
    /// Geometric normal in the shape's own orientation (outward / front side; not flipped
    /// towards the ray). Unit length.
    pub n: Vec3,
    /// Shading frame; `sh_frame.n` is the (possibly interpolated) shading normal. For meshes
    /// it is the interpolated vertex normal as the file gives it, which faces away from `n`
    /// where the file's normals oppose its winding (as in Mitsuba: BSDFs and area lights take
    /// their sides from it).
    pub sh_frame: Frame,
    /// Surface (texture) coordinates.
    pub uv: Vec2,
    /// ∂p/∂u and ∂p/∂v, world space (m per unit of u or v; not normalised). Bump and normal
    /// maps build their perturbed frames from them, as Mitsuba's `dp_du`, `dp_dv`.
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    /// Direction back towards the ray origin (= −ray.d), world space.
    pub wo: Vec3,
    /// Index of the shape hit.
    pub shape: u32,
    /// Index of the primitive inside the shape.
    pub prim: u32,
    /// Barycentric coordinates (b1, b2) of the hit on triangle `prim` (mesh attributes are
    /// interpolated with them); the shape's own (u, v) for other shapes.
    pub bary: Vec2,
    /// The instance the shape was reached through, or [`NO_INSTANCE`] (then `shape` indexes
    /// the scene's shapes; otherwise the instance's group's).
    pub instance: u32,
}

/// Offset for spawned rays, relative to the magnitude of the coordinates: floating-point
/// positions carry an error of a few ulps of max|p|, so the origin is pushed that far off the
/// surface along the geometric normal (to the side the new ray leaves through).
pub const RAY_EPSILON: f32 = 1e-4;

/// Pushes `p` off the surface with geometric normal `n` to the side of direction `d`.
#[inline]
pub fn offset_ray_origin(p: Vec3, n: Vec3, d: Vec3) -> Vec3 {
    let mag = (1.0 + p.abs().max_element()) * RAY_EPSILON;
    let offset = n * mag;
    if n.dot(d) >= 0.0 {
        p + offset
    } else {
        p - offset
    }
}

impl SurfaceInteraction {
    /// `w` (world) in the local shading frame.
    #[inline]
    pub fn to_local(&self, w: Vec3) -> Vec3 {
        self.sh_frame.to_local(w)
    }

    #[inline]
    pub fn to_world(&self, w: Vec3) -> Vec3 {
        self.sh_frame.to_world(w)
    }

    /// The point as density queries need it (position, geometric normal, primitive).
    #[inline]
    pub fn surface_point(&self) -> SurfacePoint {
        SurfacePoint { p: self.p, n: self.n, prim: self.prim }
    }

    /// A ray leaving this point in direction `d` (unit), offset to avoid self-intersection.
    #[inline]
    pub fn spawn_ray(&self, d: Vec3) -> Ray {
        Ray::infinite(offset_ray_origin(self.p, self.n, d), d)
    }

    /// A shadow ray from this point towards `target` that stops just short of it.
    #[inline]
    pub fn spawn_ray_to(&self, target: Vec3) -> Ray {
        let d = target - self.p;
        let o = offset_ray_origin(self.p, self.n, d);
        let d = target - o;
        let dist = d.length();
        Ray::new(o, d / dist, dist * (1.0 - SHADOW_EPSILON))
    }
}

/// Relative shortening of shadow rays so that they stop before the surface they aim at.
pub const SHADOW_EPSILON: f32 = 1e-3;

/// A point on a shape's surface, as density queries need it: where it is, its geometric
/// normal, and the primitive it lies on (the density of solid-angle sampling depends on the
/// triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position, m.
    pub p: Vec3,
    /// Geometric normal (the shape's own orientation), unit.
    pub n: Vec3,
    /// Primitive index inside the shape.
    pub prim: u32,
}

impl SurfacePoint {
    /// Stands for "at infinity" where an environment emitter is hit (its density ignores it).
    pub const AT_INFINITY: SurfacePoint = SurfacePoint { p: Vec3::ZERO, n: Vec3::ZERO, prim: 0 };
}
