//! Shapes: the surfaces light interacts with.
//!
//! One file per Mitsuba 3 shape plugin (`obj`, `ply`, `serialized`, `cube`, `rectangle`,
//! `disk`, `sphere`, `cylinder`, `linearcurve`, `bsplinecurve`, `sdfgrid`, `ellipsoids`,
//! `ellipsoidsmesh`; `curves.rs` reads curve files). [`Shape`] is a closed enum: every method
//! is one `match`, no dynamic dispatch.
//!
//! Conventions used by every shape:
//! - `n` is the shape's own geometric normal (outward / front side), never flipped towards a
//!   ray; `flip_normals` flips it (and the shading normal).
//! - Area sampling is uniform: `pdf_area = 1 / area` (1/m²).
//! - Solid-angle densities (1/sr) are obtained from area densities as
//!   `pdf = pdf_area · dist² / |cos θ_light|` (0 when the cosine is 0); the sphere seen from
//!   outside samples the cone of directions it subtends instead.

use std::fmt;

use glam::{Vec2, Vec3};

pub(crate) use crate::geometry::{is_positive, is_positive_finite};
use crate::geometry::{Aabb, PreliminaryHit, Ray, SurfaceInteraction, SurfacePoint};

mod bsplinecurve;
mod cube;
mod curves;
mod cylinder;
mod disk;
mod ellipsoids;
mod ellipsoidsmesh;
mod linearcurve;
mod mesh;
mod obj;
mod ply;
mod rectangle;
mod sdfgrid;
pub mod serialized;
mod sphere;

pub use bsplinecurve::BSplineCurve;
pub use cube::cube;
pub use curves::{parse_curves, read_curves};
pub use cylinder::Cylinder;
pub use disk::Disk;
pub use ellipsoids::{
    read_ellipsoids, Ellipsoid, EllipsoidCloud, Ellipsoids, ExtentClamping, DEFAULT_EXTENT,
    DEFAULT_SCALE_FACTOR,
};
pub use ellipsoidsmesh::{ellipsoid_shells, EllipsoidShells, Shell, ShellTemplate};
pub use linearcurve::LinearCurve;
pub use mesh::{Mesh, MeshData};
pub use obj::{read_obj, VertexNormals, DEFAULT_FLIP_TEX_COORDS};
pub use ply::{read_ply, read_ply_table, read_ply_with_attributes, PlyTable};
pub use rectangle::Rectangle;
pub use sdfgrid::{SdfGrid, SdfNormals};
pub use serialized::{read_serialized, SerializedShape};
pub use sphere::Sphere;

/// Default `flip_normals` of every shape (Mitsuba's).
pub const DEFAULT_FLIP_NORMALS: bool = false;

/// Every shape steradian knows.
#[derive(Clone, Debug)]
pub enum Shape {
    Mesh(Mesh),
    Rectangle(Rectangle),
    Disk(Disk),
    Sphere(Sphere),
    Cylinder(Cylinder),
    LinearCurve(LinearCurve),
    BSplineCurve(BSplineCurve),
    SdfGrid(SdfGrid),
    Ellipsoids(Ellipsoids),
    EllipsoidShells(EllipsoidShells),
}

/// A point sampled on a surface, uniformly by area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PositionSample {
    /// Position, m.
    pub p: Vec3,
    /// Normal, unit: the shape's own orientation, or on a mesh with vertex normals the
    /// interpolated shading normal (as Mitsuba's `ps.n`).
    pub n: Vec3,
    /// Surface coordinates.
    pub uv: Vec2,
    /// Density per unit area, 1/m².
    pub pdf_area: f32,
}

/// A point on a surface sampled as seen from a reference point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionSample {
    /// Position, m.
    pub p: Vec3,
    /// Geometric normal (the shape's own orientation), unit.
    pub n: Vec3,
    /// Surface coordinates (zero where [`UvRequest::Skip`] allowed it).
    pub uv: Vec2,
    /// Unit direction from the reference point towards `p`.
    pub wi: Vec3,
    /// Distance from the reference point to `p`, m.
    pub dist: f32,
    /// Density per unit solid angle seen from the reference point, 1/sr.
    pub pdf: f32,
    /// Primitive (triangle) the point lies on; 0 for analytic shapes.
    pub prim: u32,
}

/// Whether a direction sample must carry the point's surface coordinates: where they cost
/// transcendental functions (spheres), uniform emitters skip them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UvRequest {
    Compute,
    /// `uv` may be left at zero.
    Skip,
}

/// Why a shape could not be built. The message only; the scene loader adds file and line.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeError(pub String);

impl fmt::Display for ShapeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ShapeError {}

impl Shape {
    /// World-space bounds.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Mesh(s) => s.bounds(),
            Shape::Rectangle(s) => s.bounds(),
            Shape::Disk(s) => s.bounds(),
            Shape::Sphere(s) => s.bounds(),
            Shape::Cylinder(s) => s.bounds(),
            Shape::LinearCurve(s) => s.bounds(),
            Shape::BSplineCurve(s) => s.bounds(),
            Shape::SdfGrid(s) => s.bounds(),
            Shape::Ellipsoids(s) => s.bounds(),
            Shape::EllipsoidShells(s) => s.bounds(),
        }
    }

    /// Number of primitives: triangles for meshes and rectangles (2), segments of linear
    /// curves, pieces of B-spline curves, the voxels an SDF grid's surface may cross,
    /// ellipsoids, the triangles of ellipsoid shells, 1 for other analytic shapes.
    pub fn prim_count(&self) -> u32 {
        match self {
            Shape::Mesh(s) => s.indices.len() as u32,
            Shape::Rectangle(_) => 2,
            Shape::LinearCurve(s) => s.segment_count(),
            Shape::BSplineCurve(s) => s.piece_count_total(),
            Shape::SdfGrid(s) => s.voxel_count(),
            Shape::Ellipsoids(s) => s.count(),
            Shape::EllipsoidShells(s) => s.triangle_count(),
            _ => 1,
        }
    }

    /// World-space bounds of one primitive.
    pub fn prim_bounds(&self, prim: u32) -> Aabb {
        match self {
            Shape::Mesh(s) => s.prim_bounds(prim),
            Shape::Rectangle(s) => {
                let [a, b, c] = s.triangle(prim);
                let mut bb = Aabb::from_point(a);
                bb.grow(b);
                bb.grow(c);
                bb
            }
            Shape::LinearCurve(s) => s.prim_bounds(prim),
            Shape::BSplineCurve(s) => s.prim_bounds(prim),
            Shape::SdfGrid(s) => s.prim_bounds(prim),
            Shape::Ellipsoids(s) => s.prim_bounds(prim),
            Shape::EllipsoidShells(s) => s.prim_bounds(prim),
            _ => self.bounds(),
        }
    }

    /// The triangle that ray queries test for primitive `prim`, for shapes made of triangles
    /// (meshes, and rectangles as two triangles); `None` for curved shapes.
    #[inline]
    pub fn triangle(&self, prim: u32) -> Option<[Vec3; 3]> {
        match self {
            Shape::Mesh(s) => Some(s.triangle(prim)),
            Shape::Rectangle(s) => Some(s.triangle(prim)),
            Shape::Disk(_)
            | Shape::Sphere(_)
            | Shape::Cylinder(_)
            | Shape::LinearCurve(_)
            | Shape::BSplineCurve(_)
            | Shape::SdfGrid(_)
            | Shape::Ellipsoids(_)
            | Shape::EllipsoidShells(_) => None,
        }
    }

    /// Ray–primitive test: `(t, uv)` with `0 < t < ray.t_max`. `uv` holds the triangle
    /// barycentrics (b1, b2) for meshes and rectangles and the surface coordinates for other
    /// analytic shapes.
    #[inline]
    pub fn intersect_prim(&self, prim: u32, ray: &Ray) -> Option<(f32, Vec2)> {
        match self {
            Shape::Mesh(s) => s.intersect_prim(prim, ray),
            Shape::Rectangle(s) => s.intersect_prim(prim, ray),
            Shape::Disk(s) => s.intersect(ray),
            Shape::Sphere(s) => s.intersect(ray),
            Shape::Cylinder(s) => s.intersect(ray),
            Shape::LinearCurve(s) => s.intersect_prim(prim, ray),
            Shape::BSplineCurve(s) => s.intersect_prim(prim, ray),
            Shape::SdfGrid(s) => s.intersect_prim(prim, ray),
            Shape::Ellipsoids(s) => s.intersect_prim(prim, ray),
            Shape::EllipsoidShells(s) => s.intersect_prim(prim, ray),
        }
    }

    /// Full surface data at a hit found by [`Shape::intersect_prim`]. Inlined into the
    /// scene's ray query (one call site in the hot path; instances call it from a cold one).
    #[inline(always)]
    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        match self {
            Shape::Mesh(s) => s.interaction(ray, hit),
            Shape::Rectangle(s) => s.interaction(ray, hit),
            Shape::Disk(s) => s.interaction(ray, hit),
            Shape::Sphere(s) => s.interaction(ray, hit),
            Shape::Cylinder(s) => s.interaction(ray, hit),
            Shape::LinearCurve(s) => s.interaction(ray, hit),
            Shape::BSplineCurve(s) => s.interaction(ray, hit),
            Shape::SdfGrid(s) => s.interaction(ray, hit),
            Shape::Ellipsoids(s) => s.interaction(ray, hit),
            Shape::EllipsoidShells(s) => s.interaction(ray, hit),
        }
    }

    /// Makes the tables that sampling points on the surface needs (a mesh's area CDF, made
    /// otherwise at the first sample): the scene calls it for the shapes that emit.
    pub fn prepare_sampling(&self) {
        match self {
            Shape::Mesh(m) => m.prepare_sampling(),
            Shape::Rectangle(_)
            | Shape::Disk(_)
            | Shape::Sphere(_)
            | Shape::Cylinder(_)
            | Shape::LinearCurve(_)
            | Shape::BSplineCurve(_)
            | Shape::SdfGrid(_)
            | Shape::Ellipsoids(_)
            | Shape::EllipsoidShells(_) => {}
        }
    }

    /// Surface area, m².
    pub fn surface_area(&self) -> f32 {
        match self {
            Shape::Mesh(s) => s.surface_area(),
            Shape::Rectangle(s) => s.surface_area(),
            Shape::Disk(s) => s.surface_area(),
            Shape::Sphere(s) => s.surface_area(),
            Shape::Cylinder(s) => s.surface_area(),
            Shape::LinearCurve(s) => s.surface_area(),
            Shape::BSplineCurve(s) => s.surface_area(),
            Shape::SdfGrid(s) => s.surface_area(),
            Shape::Ellipsoids(s) => s.surface_area(),
            Shape::EllipsoidShells(s) => s.surface_area(),
        }
    }

    /// Whether point `p` of primitive `prim` faces direction `w` by its shading normal: the
    /// interpolated vertex normal of a mesh that has them (which may disagree with the
    /// winding); every other shape's shading normal is its geometric one, which the caller
    /// has checked already. Area lights emit on this side, as Mitsuba's.
    #[inline]
    pub fn shading_faces(&self, prim: u32, p: Vec3, w: Vec3) -> bool {
        match self {
            Shape::Mesh(s) => s.shading_faces(prim, p, w),
            Shape::Rectangle(_)
            | Shape::Disk(_)
            | Shape::Sphere(_)
            | Shape::Cylinder(_)
            | Shape::LinearCurve(_)
            | Shape::BSplineCurve(_)
            | Shape::SdfGrid(_)
            | Shape::Ellipsoids(_)
            | Shape::EllipsoidShells(_) => true,
        }
    }

    /// A point uniformly distributed by area; `pdf_area = 1 / area` (0 for curves, which
    /// cannot be sampled: no caller takes such a sample).
    pub fn sample_position(&self, u: Vec2) -> PositionSample {
        match self {
            Shape::Mesh(s) => s.sample_position(u),
            Shape::Rectangle(s) => s.sample_position(u),
            Shape::Disk(s) => s.sample_position(u),
            Shape::Sphere(s) => s.sample_position(u),
            Shape::Cylinder(s) => s.sample_position(u),
            Shape::LinearCurve(s) => s.sample_position(u),
            Shape::BSplineCurve(s) => s.sample_position(u),
            Shape::SdfGrid(s) => s.sample_position(u),
            Shape::Ellipsoids(s) => s.sample_position(u),
            Shape::EllipsoidShells(s) => s.sample_position(u),
        }
    }

    /// A point on the surface as seen from `reference`, with its density per solid angle.
    /// `None` when that density would be 0 or not finite. `uv` says whether the caller needs
    /// the point's surface coordinates (a textured emitter does, a uniform one does not).
    pub fn sample_direction(
        &self,
        reference: Vec3,
        u: Vec2,
        uv: UvRequest,
    ) -> Option<DirectionSample> {
        match self {
            Shape::Sphere(s) => s.sample_direction(reference, u, uv),
            Shape::Rectangle(s) => s.sample_direction(reference, u),
            Shape::Mesh(s) => s.sample_direction(reference, u),
            Shape::Disk(_)
            | Shape::Cylinder(_)
            | Shape::LinearCurve(_)
            | Shape::BSplineCurve(_)
            | Shape::SdfGrid(_)
            | Shape::Ellipsoids(_)
            | Shape::EllipsoidShells(_) => {
                direction_from_position(reference, &self.sample_position(u), 0)
            }
        }
    }

    /// Whether [`Shape::sample_direction`] from `reference` gives every sample a bounded weight
    /// (emitted radiance × cosine at `reference` / density, at most a fixed multiple of the
    /// radiance) for a Lambertian receiver there: then light sampling alone, without the BSDF
    /// sample that multiple importance sampling adds, has no fireflies. True for spheres seen
    /// from outside and for rectangles no nearer than √area; false for the shapes sampled by
    /// area everywhere (meshes, disks, cylinders), where 1/d² is unbounded near the surface.
    pub fn light_sampling_bounded(&self, reference: Vec3) -> bool {
        match self {
            Shape::Sphere(s) => s.light_sampling_bounded(reference),
            Shape::Rectangle(s) => s.light_sampling_bounded(reference),
            Shape::Mesh(_)
            | Shape::Disk(_)
            | Shape::Cylinder(_)
            | Shape::LinearCurve(_)
            | Shape::BSplineCurve(_)
            | Shape::SdfGrid(_)
            | Shape::Ellipsoids(_)
            | Shape::EllipsoidShells(_) => false,
        }
    }

    /// The density per solid angle (1/sr) that [`Shape::sample_direction`] gives for the surface
    /// point `q`, seen from `reference`.
    pub fn pdf_direction(&self, reference: Vec3, q: &SurfacePoint) -> f32 {
        let (p, n) = (q.p, q.n);
        match self {
            Shape::Sphere(s) => s.pdf_direction(reference, p, n),
            Shape::Rectangle(s) => s.pdf_direction(reference, p, n),
            Shape::Mesh(s) => s.pdf_direction(reference, p, n, q.prim),
            Shape::LinearCurve(_)
            | Shape::BSplineCurve(_)
            | Shape::SdfGrid(_)
            | Shape::Ellipsoids(_)
            | Shape::EllipsoidShells(_) => 0.0,
            Shape::Disk(_) | Shape::Cylinder(_) => {
                let area = self.surface_area();
                if area > 0.0 {
                    area_to_solid_angle(1.0 / area, reference, p, n)
                } else {
                    0.0
                }
            }
        }
    }
}

/// Converts an area density at `p` (normal `n`) to a solid-angle density seen from
/// `reference`: `pdf_area · dist² / |cos θ|`, 0 when the cosine is 0 or the result is not finite.
#[inline]
pub(crate) fn area_to_solid_angle(pdf_area: f32, reference: Vec3, p: Vec3, n: Vec3) -> f32 {
    let d = p - reference;
    let dist2 = d.length_squared();
    if !is_positive(dist2) {
        return 0.0;
    }
    let cos = n.dot(d).abs() / dist2.sqrt();
    if !is_positive(cos) {
        return 0.0;
    }
    let pdf = pdf_area * dist2 / cos;
    if pdf.is_finite() {
        pdf
    } else {
        0.0
    }
}

/// Turns an area sample (on primitive `prim`) into a direction sample seen from `reference`.
pub(crate) fn direction_from_position(
    reference: Vec3,
    ps: &PositionSample,
    prim: u32,
) -> Option<DirectionSample> {
    let d = ps.p - reference;
    let dist = d.length();
    if !is_positive_finite(dist) {
        return None;
    }
    let pdf = area_to_solid_angle(ps.pdf_area, reference, ps.p, ps.n);
    if !is_positive_finite(pdf) {
        return None;
    }
    Some(DirectionSample { p: ps.p, n: ps.n, uv: ps.uv, wi: d / dist, dist, pdf, prim })
}

/// φ / 2π in [0, 1) for a local point.
#[inline]
pub(crate) fn azimuth01(x: f32, y: f32) -> f32 {
    let mut v = crate::geometry::trig::atan2(y, x) * (0.5 * std::f32::consts::FRAC_1_PI);
    if v < 0.0 {
        v += 1.0;
    }
    if v >= 1.0 {
        v = 0.0;
    }
    v
}

#[cfg(test)]
pub(crate) mod test_util;

#[cfg(test)]
mod tests;

#[cfg(test)]
mod io_tests;
