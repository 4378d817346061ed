//! Triangle meshes: the common representation behind `obj`, `ply` and `cube`.
//!
//! Vertices are stored in world space. The geometric normal of a triangle is
//! `normalize((p1 − p0) × (p2 − p0))` (negated by `flip_normals`). Shading normals are the
//! interpolated vertex normals (the file's, transformed with the inverse transpose, or, when
//! the file has none and `face_normals` is false, Mitsuba's smooth angle-weighted vertex
//! normals); with `face_normals` the shading normal is the geometric normal (flat shading).
//! BSDFs and area lights take their front side from the shading normal, as Mitsuba's do, so
//! a file whose normals point against its winding still shines outwards
//! (`tests/mesh_light.rs`); light sampling reaches such a point only where both normals face
//! the receiver, and BSDF sampling finds the rest.
//! Surface coordinates are the interpolated vertex uvs when present, else the barycentrics
//! (b1, b2), as in Mitsuba.

use std::sync::OnceLock;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::{
    area_to_solid_angle, direction_from_position, is_positive_finite, DirectionSample,
    PositionSample, ShapeError,
};
use crate::geometry::{intersect_triangle, trig};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};
use crate::sampling::spherical_triangle::SphericalTriangle;
use crate::sampling::warp;

/// Mesh data as read from a file (object space, before `to_world`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<Vec3>,
    pub normals: Option<Vec<Vec3>>,
    pub uvs: Option<Vec<Vec2>>,
    pub indices: Vec<[u32; 3]>,
}

/// A world-space triangle mesh.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// World-space vertex positions, m.
    pub positions: Vec<Vec3>,
    /// World-space unit vertex normals (already flipped by `flip_normals`); `None` for flat shading.
    pub normals: Option<Vec<Vec3>>,
    /// Vertex surface coordinates.
    pub uvs: Option<Vec<Vec2>>,
    /// Triangles (vertex indices, counter-clockwise around the front normal).
    pub indices: Vec<[u32; 3]>,
    flip_normals: bool,
    area: f32,
    /// Cumulative normalised triangle areas (last entry 1); empty when the area is 0. Made on
    /// first use ([`Mesh::prepare_sampling`]): only emitters sample their surface, and for a
    /// 20-million-triangle mesh the table is 80 MB.
    cdf: OnceLock<Vec<f32>>,
}

/// Vertices or triangles per parallel task.
const PAR_CHUNK: usize = 1 << 14;

impl Mesh {
    /// Default `face_normals` of `obj` and `ply` (Mitsuba's).
    pub const DEFAULT_FACE_NORMALS: bool = false;

    /// Builds a world-space mesh from object-space data.
    ///
    /// Fails when an index is out of range, a position is not finite, or the normal/uv arrays
    /// do not have one entry per vertex.
    pub fn new(
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
        indices: Vec<[u32; 3]>,
        to_world: &Transform,
        flip_normals: bool,
        face_normals: bool,
    ) -> Result<Mesh, ShapeError> {
        let nv = positions.len();
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(ShapeError(format!(
                "mesh vertex {i} has a non-finite position {}",
                positions[i]
            )));
        }
        if let Some(n) = &normals {
            if n.len() != nv {
                return Err(ShapeError(format!("mesh has {} normals for {nv} vertices", n.len())));
            }
        }
        if let Some(uv) = &uvs {
            if uv.len() != nv {
                return Err(ShapeError(format!(
                    "mesh has {} texture coordinates for {nv} vertices",
                    uv.len()
                )));
            }
        }
        for (f, tri) in indices.iter().enumerate() {
            if let Some(&bad) = tri.iter().find(|&&i| i as usize >= nv) {
                return Err(ShapeError(format!(
                    "mesh face {f} refers to vertex {bad}, but there are only {nv} vertices"
                )));
            }
        }
        let mut positions = positions;
        if !to_world.is_identity() {
            positions.par_iter_mut().with_min_len(PAR_CHUNK).for_each(|p| *p = to_world.point(*p));
        }
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(ShapeError(format!("mesh vertex {i} is not finite after to_world")));
        }
        let sign = if flip_normals { -1.0 } else { 1.0 };
        let normals = match (face_normals, normals) {
            (true, _) => None,
            (false, Some(mut ns)) => {
                ns.par_iter_mut()
                    .with_min_len(PAR_CHUNK)
                    .for_each(|n| *n = to_world.normal(*n).normalize_or_zero() * sign);
                Some(ns)
            }
            (false, None) => {
                let mut ns = smooth_normals(&positions, &indices);
                if flip_normals {
                    ns.par_iter_mut().with_min_len(PAR_CHUNK).for_each(|n| *n = -*n);
                }
                Some(ns)
            }
        };
        let area = indices.iter().map(|&tri| triangle_area(&positions, tri)).sum::<f64>() as f32;
        Ok(Mesh { positions, normals, uvs, indices, flip_normals, area, cdf: OnceLock::new() })
    }

    /// [`Mesh::new`] from [`MeshData`].
    pub fn from_data(
        data: MeshData,
        to_world: &Transform,
        flip_normals: bool,
        face_normals: bool,
    ) -> Result<Mesh, ShapeError> {
        Mesh::new(
            data.positions,
            data.normals,
            data.uvs,
            data.indices,
            to_world,
            flip_normals,
            face_normals,
        )
    }

    /// Makes the table of [`Mesh::sample_position`] and [`Mesh::sample_direction`] now rather
    /// than at their first call (the scene does so for its emitters before rendering).
    pub fn prepare_sampling(&self) {
        self.cdf();
    }

    /// The triangles' cumulative normalised areas.
    #[inline]
    fn cdf(&self) -> &[f32] {
        self.cdf.get_or_init(|| {
            // the f64 running sum of `Mesh::new`'s area, normalised
            let areas = || self.indices.iter().map(|&tri| triangle_area(&self.positions, tri));
            let total: f64 = areas().sum();
            if total.is_nan() || total <= 0.0 {
                return Vec::new();
            }
            let mut acc = 0.0f64;
            let mut cdf: Vec<f32> = areas()
                .map(|a| {
                    acc += a;
                    (acc / total) as f32
                })
                .collect();
            // entries after the last non-degenerate triangle must be exactly 1
            let last = cdf.iter().rposition(|&c| c < 1.0).map_or(0, |i| i + 1);
            for c in &mut cdf[last..] {
                *c = 1.0;
            }
            cdf
        })
    }

    #[inline]
    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        self.indices[prim as usize].map(|i| self.positions[i as usize])
    }

    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for tri in &self.indices {
            for &i in tri {
                b.grow(self.positions[i as usize]);
            }
        }
        b
    }

    pub fn prim_bounds(&self, prim: u32) -> Aabb {
        let [a, b, c] = self.triangle(prim);
        let mut bb = Aabb::from_point(a);
        bb.grow(b);
        bb.grow(c);
        bb
    }

    #[inline]
    pub fn intersect_prim(&self, prim: u32, ray: &Ray) -> Option<(f32, Vec2)> {
        let [a, b, c] = self.triangle(prim);
        intersect_triangle(a, b, c, ray)
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    /// Geometric normal of a triangle (flipped by `flip_normals`); zero for degenerate ones.
    fn face_normal(&self, prim: u32) -> Vec3 {
        let [a, b, c] = self.triangle(prim);
        let n = (b - a).cross(c - a).normalize_or_zero();
        if self.flip_normals {
            -n
        } else {
            n
        }
    }

    /// Whether point `p` of triangle `prim` faces direction `w` by the interpolated vertex
    /// normal there (true without vertex normals: the geometric normal then decides).
    pub fn shading_faces(&self, prim: u32, p: Vec3, w: Vec3) -> bool {
        let [p0, p1, p2] = self.triangle(prim);
        let (b, det) = plane_barycentrics(p1 - p0, p2 - p0, p - p0);
        // a degenerate triangle has no interior to interpolate over: the geometric side stands
        if det.is_nan() || det <= 0.0 {
            return true;
        }
        match self.interpolated_normal(prim, 1.0 - b.x - b.y, b.x, b.y) {
            Some(n) => n.dot(w) > 0.0,
            None => true,
        }
    }

    /// The vertex normals of triangle `prim` weighted by barycentrics (b0, b1, b2), not
    /// normalised; `None` for a mesh without vertex normals.
    #[inline(always)]
    fn interpolated_normal(&self, prim: u32, b0: f32, b1: f32, b2: f32) -> Option<Vec3> {
        let ns = self.normals.as_ref()?;
        let [i0, i1, i2] = self.indices[prim as usize];
        Some(ns[i0 as usize] * b0 + ns[i1 as usize] * b1 + ns[i2 as usize] * b2)
    }

    /// The unit shading normal at barycentrics (b0, b1, b2) of triangle `prim`; `None` without
    /// vertex normals or where they cancel (the face's normal then stands).
    #[inline(always)]
    fn shading_normal(&self, prim: u32, b0: f32, b1: f32, b2: f32) -> Option<Vec3> {
        let n = self.interpolated_normal(prim, b0, b1, b2)?.normalize_or_zero();
        (n != Vec3::ZERO).then_some(n)
    }

    fn uv_at(&self, prim: u32, b: Vec2) -> Vec2 {
        match &self.uvs {
            Some(uvs) => {
                let [i0, i1, i2] = self.indices[prim as usize];
                uvs[i0 as usize] * (1.0 - b.x - b.y)
                    + uvs[i1 as usize] * b.x
                    + uvs[i2 as usize] * b.y
            }
            None => b,
        }
    }

    #[inline(always)]
    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        let prim = hit.prim;
        let [i0, i1, i2] = self.indices[prim as usize];
        let [p0, p1, p2] = self.triangle(prim);
        let (b1, b2) = (hit.uv.x, hit.uv.y);
        let b0 = 1.0 - b1 - b2;
        let p = p0 * b0 + p1 * b1 + p2 * b2;
        let mut n = self.face_normal(prim);
        if n == Vec3::ZERO {
            n = -ray.d;
        }
        let e1 = p1 - p0;
        let e2 = p2 - p0;
        // ∂p/∂u, ∂p/∂v from the uv parametrisation of the triangle (solving
        // e1 = Δu1·dpdu + Δv1·dpdv, e2 = Δu2·dpdu + Δv2·dpdv); without uvs (or with degenerate
        // ones) the barycentrics (b1, b2) are the parameters: dpdu = e1, dpdv = e2.
        let (dpdu, dpdv) = match &self.uvs {
            Some(uvs) => {
                let (uv0, uv1, uv2) = (uvs[i0 as usize], uvs[i1 as usize], uvs[i2 as usize]);
                let d1 = uv1 - uv0;
                let d2 = uv2 - uv0;
                let det = d1.x * d2.y - d1.y * d2.x;
                let dpdu = (e1 * d2.y - e2 * d1.y) / det;
                let dpdv = (e2 * d1.x - e1 * d2.x) / det;
                if det != 0.0 && dpdu.is_finite() && dpdv.is_finite() {
                    (dpdu, dpdv)
                } else {
                    (e1, e2)
                }
            }
            None => (e1, e2),
        };
        let ns = self.shading_normal(prim, b0, b1, b2).unwrap_or(n);
        SurfaceInteraction {
            p,
            t: hit.t,
            n,
            sh_frame: Frame::from_normal_tangent(ns, dpdu),
            uv: self.uv_at(prim, hit.uv),
            dpdu,
            dpdv,
            wo: -ray.d,
            shape: hit.shape,
            prim,
            bary: hit.uv,
            instance: hit.instance,
        }
    }

    /// Picks a triangle with probability proportional to its area; returns it, its
    /// probability, and `u` with the part of the sample used for the choice rescaled to [0, 1).
    #[inline]
    fn pick_triangle(&self, u: Vec2) -> Option<(u32, f32, Vec2)> {
        let cdf = self.cdf();
        if cdf.is_empty() {
            return None;
        }
        let idx = cdf.partition_point(|&c| c <= u.x).min(cdf.len() - 1);
        let (lo, pmf) = cdf_interval(cdf, idx);
        let ux = ((u.x - lo) / pmf).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        Some((idx as u32, pmf, Vec2::new(ux, u.y)))
    }

    /// Uniform by area: picks a triangle with probability proportional to its area (the
    /// sample's x is reused after the choice), then a uniform point on it.
    pub fn sample_position(&self, u: Vec2) -> PositionSample {
        let Some((prim, _, u)) = self.pick_triangle(u) else {
            let p = self.positions.first().copied().unwrap_or(Vec3::ZERO);
            return PositionSample { p, n: Vec3::Z, uv: Vec2::ZERO, pdf_area: 0.0 };
        };
        let (mut ps, b) = self.sample_on_triangle(prim, u);
        // Mitsuba's `ps.n`: the interpolated vertex normal where the mesh has them, so that a
        // mesh light emits, and a meter on a mesh faces, by its shading normal
        if let Some(ns) = self.shading_normal(prim, 1.0 - b.x - b.y, b.x, b.y) {
            ps.n = ns;
        }
        ps
    }

    /// A uniform point on triangle `prim`, with the whole mesh's area density 1/area and the
    /// face's normal, and its barycentrics (b1, b2).
    fn sample_on_triangle(&self, prim: u32, u: Vec2) -> (PositionSample, Vec2) {
        let b = warp::square_to_uniform_triangle(u);
        let [p0, p1, p2] = self.triangle(prim);
        let p = p0 * (1.0 - b.x - b.y) + p1 * b.x + p2 * b.y;
        let ps = PositionSample {
            p,
            n: self.face_normal(prim),
            uv: self.uv_at(prim, b),
            pdf_area: 1.0 / self.area,
        };
        (ps, b)
    }

    /// Triangle `prim` as seen from `reference`, when solid-angle sampling applies there.
    #[inline]
    fn spherical(&self, reference: Vec3, prim: u32) -> Option<SphericalTriangle> {
        let [p0, p1, p2] = self.triangle(prim);
        SphericalTriangle::new(reference, p0, p1, p2)
            .filter(|st| SphericalTriangle::USEFUL.contains(&st.solid_angle()))
    }

    /// A point seen from `reference`: a triangle chosen by area, then a direction uniform in
    /// the solid angle it subtends (a uniform point by area where that solid angle is tiny or
    /// nearly a hemisphere). The density per steradian is pmf(triangle)/Ω.
    pub fn sample_direction(&self, reference: Vec3, u: Vec2) -> Option<DirectionSample> {
        let (prim, pmf, u) = self.pick_triangle(u)?;
        let Some(st) = self.spherical(reference, prim) else {
            return direction_from_position(reference, &self.sample_on_triangle(prim, u).0, prim);
        };
        let wi = st.sample(u);
        // the point where wi meets the triangle's plane, and its barycentrics
        let [p0, p1, p2] = self.triangle(prim);
        let (e1, e2) = (p1 - p0, p2 - p0);
        let ng = e1.cross(e2);
        let dist = ng.dot(p0 - reference) / ng.dot(wi);
        let pdf = pmf / st.solid_angle() as f32;
        if !is_positive_finite(dist) || !is_positive_finite(pdf) {
            return None;
        }
        let p = reference + wi * dist;
        let b = plane_barycentrics(e1, e2, p - p0).0.clamp(Vec2::ZERO, Vec2::ONE);
        Some(DirectionSample {
            p,
            n: self.face_normal(prim),
            uv: self.uv_at(prim, b),
            wi,
            dist,
            pdf,
            prim,
        })
    }

    /// Density per solid angle of [`Mesh::sample_direction`] for the point `p` (normal `n`) of
    /// triangle `prim`.
    pub fn pdf_direction(&self, reference: Vec3, p: Vec3, n: Vec3, prim: u32) -> f32 {
        let cdf = self.cdf();
        if cdf.is_empty() || prim as usize >= self.indices.len() {
            return 0.0;
        }
        match self.spherical(reference, prim) {
            Some(st) => cdf_interval(cdf, prim as usize).1 / st.solid_angle() as f32,
            None => area_to_solid_angle(1.0 / self.area, reference, p, n),
        }
    }
}

/// Start of triangle `idx`'s interval in the area CDF `cdf`, and its probability (the
/// interval's length). `cdf` must not be empty.
#[inline]
fn cdf_interval(cdf: &[f32], idx: usize) -> (f32, f32) {
    let lo = if idx == 0 { 0.0 } else { cdf[idx - 1] };
    (lo, cdf[idx] - lo)
}

/// The area of triangle `tri`, m², in f64; 0 where it is not finite (degenerate data).
fn triangle_area(positions: &[Vec3], tri: [u32; 3]) -> f64 {
    let [a, b, c] = tri.map(|i| positions[i as usize]);
    let area = 0.5 * (b - a).cross(c - a).length() as f64;
    if area.is_finite() {
        area
    } else {
        0.0
    }
}

/// Mitsuba's vertex normals: each face adds its unit normal weighted by its angle at the vertex.
///
/// The angle at a corner between edges `e0`, `e1` is atan2(|e0 × e1|, e0 · e1), where
/// |e0 × e1| is the same at the three corners (twice the triangle's area): one cross product
/// per triangle and no normalised edges; the third angle is π minus the other two. Mitsuba
/// takes acos of the normalised edges' dot product; the angles agree to 4·10⁻⁷ rad
/// (`geometry::trig`). (With libm's `acosf` per corner, the normals were 3.6 % of loading a
/// 2-million-triangle PLY.)
///
/// Threads share the work by vertex: each walks all faces and adds the corners of its own
/// vertices, in face order, so every sum is the sequential one whatever the thread count.
fn smooth_normals(positions: &[Vec3], indices: &[[u32; 3]]) -> Vec<Vec3> {
    let mut ns = vec![Vec3::ZERO; positions.len()];
    let per_thread = positions.len().div_ceil(rayon::current_num_threads()).max(PAR_CHUNK);
    ns.par_chunks_mut(per_thread).enumerate().for_each(|(t, ns)| {
        let lo = (t * per_thread) as u32;
        let hi = lo + ns.len() as u32;
        let mine = |i: u32| (lo..hi).contains(&i);
        for tri in indices {
            if !tri.iter().any(|&i| mine(i)) {
                continue;
            }
            let v = tri.map(|i| positions[i as usize]);
            let cross = (v[1] - v[0]).cross(v[2] - v[0]);
            let twice_area = cross.length();
            if !is_positive_finite(twice_area) {
                continue;
            }
            let n = cross / twice_area;
            let a0 = trig::atan2(twice_area, (v[1] - v[0]).dot(v[2] - v[0]));
            let a1 = trig::atan2(twice_area, (v[2] - v[1]).dot(v[0] - v[1]));
            let angles = [a0, a1, (std::f32::consts::PI - a0 - a1).max(0.0)];
            for (&i, angle) in tri.iter().zip(angles) {
                if mine(i) {
                    ns[(i - lo) as usize] += n * angle;
                }
            }
        }
        for n in ns {
            *n = n.normalize_or_zero();
        }
    });
    ns
}

/// Barycentrics (b1, b2) of the point p0 + `q` in the plane of a triangle with edges `e1`,
/// `e2` from p0 (by least squares: a point off the plane lands on its projection), and the
/// Gram determinant they divide by (0 for a degenerate triangle).
#[inline]
fn plane_barycentrics(e1: Vec3, e2: Vec3, q: Vec3) -> (Vec2, f32) {
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (q1, q2) = (q.dot(e1), q.dot(e2));
    let det = d11 * d22 - d12 * d12;
    (Vec2::new((q1 * d22 - q2 * d12) / det, (q2 * d11 - q1 * d12) / det), det)
}
