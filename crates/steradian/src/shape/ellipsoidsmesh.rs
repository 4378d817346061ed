//! # `ellipsoidsmesh`: a cloud of ellipsoids, each a triangle shell
//!
//! Mitsuba plugin `ellipsoidsmesh`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `filename` | string | (required) | PLY file of the ellipsoids (layout in `ellipsoids.rs`) |
//! | `scale_factor` | float | 1 | factor on every ellipsoid's scales |
//! | `extent` | float | 3 | the shell's size in units of the scales |
//! | `extent_adaptive_clamping` | bool | false | scale each `extent` by the ellipsoid's opacity (in `ellipsoids.rs`) |
//! | `shell` | string or nested mesh | `ico_sphere` | the template every ellipsoid's shell is made of: `ico_sphere` (also `default`), `box`, `uv_sphere`, or the triangles of a nested mesh shape |
//! | `flip_normals` | bool | false | flip the shells' normals |
//! | `to_world` | transform | identity | as for `ellipsoids` |
//!
//! **Shells.** A template polyhedron around the origin is scaled, as Mitsuba scales it, so
//! that its nearest vertex and its nearest face centroid lie at distance 1 or more (the one
//! at exactly 1 fixes the scale), and then each ellipsoid's copy is placed by x ↦ c + R·(r ⊙
//! x) with r = `extent` · scale. The named templates are Mitsuba's own vertices and triangles
//! (`ellipsoidsmesh/shells.rs`, read back from Mitsuba 3.9.1 by `scripts/ellipsoid_shells.py`):
//! - `ico_sphere`: the regular icosahedron (20 triangles) with vertices on ±y and two rings
//!   of five at latitudes ±atan(1/2), the upper ring at azimuths 0°, 72°, … and the lower at
//!   36°, 108°, … (azimuth measured from +x towards +z); its inscribed sphere is the unit one.
//! - `box`: the cube, two triangles per face, its half-width 1/|(1/3, 1, 1/3)| = 0.905 (the
//!   face triangles' centroids at distance 1: the unit sphere pokes out of the faces' middles).
//! - `uv_sphere`: poles on ±y, four rings at polar angles 36°, 72°, 108°, 144° of nine
//!   vertices at azimuths −50°, −10°, … (72 triangles), circumradius 1.1036.
//! - a nested `obj`/`ply`/… shape: its triangles, where its own `to_world` put them.
//!
//! The order of each triangle's vertices matters beyond the geometry: a shell has no texture
//! coordinates of its own, so a hit's (u, v) are its barycentric coordinates and ∂p/∂u, ∂p/∂v
//! its triangle's edges, as on any mesh without them. With formula-built templates of the
//! same shape but another vertex order, a normal-mapped conductor on icosahedral shells
//! failed Mitsuba's render-test rule on the same 8 pixels at every seed (0.9967 of the pixels
//! passing); with Mitsuba's order it fails on none but the scene's random fireflies. A
//! checkerboard on the shells of `reference/ellipsoids.xml` passes at 0.9998 of the pixels,
//! and at 0.9964 (a failure) with each triangle's vertices rotated, the same geometry.
//!
//! The shells have flat (face) normals, outward, and no vertex normals or texture
//! coordinates of their own. As in Mitsuba (all its variants), a triangle is hit from its
//! front (outer) side only: a ray from inside a shell leaves it unseen. The culling follows
//! the triangles' winding, so `flip_normals` turns the normals but not the side that is hit.
//! Because of the culling the shells are not triangles of the BVH's fast path but primitives
//! tested by this shape. Glass shells show it: in a test scene of glass shells, Mitsuba
//! 3.9.1's image and steradian's agreed only once steradian culled as well (image means 15 %
//! apart before).
//!
//! **Where steradian differs on purpose.** As for `ellipsoids`. The mesh can neither emit nor
//! carry a sensor (Mitsuba builds no sampling data for it either). `face_normals` is accepted
//! and changes nothing, as in Mitsuba (the shells are flat already).

use glam::{Vec2, Vec3};

use super::ellipsoids::{check_extents, Ellipsoid};
use super::{Mesh, MeshData, PositionSample, ShapeError};
use crate::geometry::{intersect_triangle, Aabb, PreliminaryHit, Ray, SurfaceInteraction};

mod shells;

/// The shells of an `ellipsoidsmesh`: a mesh whose triangles are hit from the front only.
#[derive(Clone, Debug)]
pub struct EllipsoidShells {
    mesh: Mesh,
}

impl EllipsoidShells {
    /// `mesh`, as built from [`ellipsoid_shells`] with flat normals.
    pub fn new(mesh: Mesh) -> EllipsoidShells {
        EllipsoidShells { mesh }
    }

    pub fn triangle_count(&self) -> u32 {
        self.mesh.indices.len() as u32
    }

    pub fn bounds(&self) -> Aabb {
        self.mesh.bounds()
    }

    pub fn prim_bounds(&self, prim: u32) -> Aabb {
        self.mesh.prim_bounds(prim)
    }

    /// Ray–triangle test for rays arriving on the triangle's front (by its winding).
    #[inline]
    pub fn intersect_prim(&self, prim: u32, ray: &Ray) -> Option<(f32, Vec2)> {
        let [a, b, c] = self.mesh.triangle(prim);
        if (b - a).cross(c - a).dot(ray.d) >= 0.0 {
            return None;
        }
        intersect_triangle(a, b, c, ray)
    }

    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        self.mesh.interaction(ray, hit)
    }

    /// 0, as for `ellipsoids`: no points are sampled on the shells.
    pub fn surface_area(&self) -> f32 {
        0.0
    }

    /// No points can be sampled (the loader refuses emitters and sensors on the shape).
    pub fn sample_position(&self, _u: Vec2) -> PositionSample {
        PositionSample { p: self.mesh.positions[0], n: Vec3::Z, uv: Vec2::ZERO, pdf_area: 0.0 }
    }
}

/// The template every ellipsoid's shell is a copy of (`shell`).
#[derive(Clone, Debug, PartialEq)]
pub enum Shell {
    /// One of Mitsuba's templates, by name.
    Named(ShellTemplate),
    /// The triangles of a nested mesh.
    Mesh { positions: Vec<Vec3>, indices: Vec<[u32; 3]> },
}

/// Mitsuba's named shell templates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShellTemplate {
    /// The icosahedron.
    IcoSphere,
    Box,
    UvSphere,
}

impl ShellTemplate {
    /// Default `shell` (Mitsuba's).
    pub const DEFAULT: ShellTemplate = ShellTemplate::IcoSphere;
}

impl Shell {
    /// The template's vertices and outward triangles, before scaling.
    fn template(&self) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let table = |v: &[[f32; 3]], f: &[[u32; 3]]| {
            (v.iter().map(|&p| Vec3::from(p)).collect(), f.to_vec())
        };
        match self {
            Shell::Named(ShellTemplate::IcoSphere) => {
                table(&shells::ICO_SPHERE_VERTICES, &shells::ICO_SPHERE_FACES)
            }
            Shell::Named(ShellTemplate::Box) => table(&shells::BOX_VERTICES, &shells::BOX_FACES),
            Shell::Named(ShellTemplate::UvSphere) => {
                table(&shells::UV_SPHERE_VERTICES, &shells::UV_SPHERE_FACES)
            }
            Shell::Mesh { positions, indices } => (positions.clone(), indices.clone()),
        }
    }
}

/// The shells of `ellipsoids`, ellipsoid `i`'s scaled by `extents[i]` (none where it is 0):
/// one mesh, each ellipsoid's triangles following the previous one's.
pub fn ellipsoid_shells(
    ellipsoids: &[Ellipsoid],
    extents: &[f32],
    shell: &Shell,
) -> Result<MeshData, ShapeError> {
    let (mut template, faces) = shell.template();
    if faces.is_empty() {
        return Err(ShapeError("ellipsoidsmesh: the shell has no triangles".into()));
    }
    if let Some(bad) = faces.iter().flatten().find(|&&i| i as usize >= template.len()) {
        return Err(ShapeError(format!(
            "ellipsoidsmesh: the shell's triangles name vertex {bad} of {}",
            template.len()
        )));
    }
    // Mitsuba's scale: every vertex and every face centroid at distance ≥ 1
    let nearest = faces.iter().fold(f32::INFINITY, |m, &[a, b, c]| {
        let (pa, pb, pc) = (template[a as usize], template[b as usize], template[c as usize]);
        m.min(pa.length()).min(pb.length()).min(pc.length()).min(((pa + pb + pc) / 3.0).length())
    });
    if !(nearest > 1e-12 && nearest.is_finite()) {
        return Err(ShapeError(
            "ellipsoidsmesh: the shell passes through its centre, so it cannot be scaled \
             around the unit sphere"
                .into(),
        ));
    }
    template.iter_mut().for_each(|p| *p /= nearest);
    check_extents(ellipsoids, extents)?;
    let mut positions = Vec::with_capacity(ellipsoids.len() * template.len());
    let mut indices = Vec::with_capacity(ellipsoids.len() * faces.len());
    // ellipsoids of extent 0 have no shell
    for (e, &extent) in ellipsoids.iter().zip(extents).filter(|(_, &k)| k > 0.0) {
        let base = positions.len() as u32;
        let radii = e.scale * extent;
        positions.extend(template.iter().map(|&x| e.center + e.rotation * (x * radii)));
        indices.extend(faces.iter().map(|f| f.map(|k| base + k)));
    }
    if indices.is_empty() {
        return Err(ShapeError("ellipsoidsmesh: no ellipsoid has a shell".into()));
    }
    Ok(MeshData { positions, normals: None, uvs: None, indices })
}

#[cfg(test)]
mod tests {
    use glam::{Mat3, Quat};

    use super::*;

    /// The scaled template of `shell` (one unit ellipsoid at the origin).
    fn unit(shell: &Shell) -> MeshData {
        let e = Ellipsoid { center: Vec3::ZERO, scale: Vec3::ONE, rotation: Mat3::IDENTITY };
        ellipsoid_shells(&[e], &[1.0], shell).unwrap()
    }

    #[test]
    fn templates_have_their_sizes_and_enclose_the_unit_sphere_as_mitsubas_do() {
        // (shell, triangles, vertices, circumradius: Mitsuba 3.9.1's vertex norms)
        for (shell, faces, verts, radius) in [
            (Shell::Named(ShellTemplate::IcoSphere), 20, 12, 1.25841),
            (Shell::Named(ShellTemplate::Box), 12, 24, 1.56670),
            (Shell::Named(ShellTemplate::UvSphere), 72, 38, 1.10360),
        ] {
            let m = unit(&shell);
            assert_eq!((m.indices.len(), m.positions.len()), (faces, verts), "{shell:?}");
            for p in &m.positions {
                assert!((p.length() - radius).abs() < 1e-4, "{shell:?}: |{p}| ≠ {radius}");
            }
            let mut nearest = f32::INFINITY;
            for &[a, b, c] in &m.indices {
                let v = [a, b, c].map(|i| m.positions[i as usize]);
                let n = (v[1] - v[0]).cross(v[2] - v[0]);
                let centroid = (v[0] + v[1] + v[2]) / 3.0;
                assert!(n.dot(centroid) > 0.0, "{shell:?}: a triangle faces inward");
                nearest = nearest.min(centroid.length());
            }
            assert!((nearest - 1.0).abs() < 1e-5, "{shell:?}: nearest centroid {nearest}");
        }
    }

    // The polyhedra the manual describes, built from their definitions (vertex order aside).
    /// A point on the unit sphere at polar angle `theta` from +y and azimuth `phi` from +x
    /// towards +z, in degrees.
    fn on_sphere(theta: f32, phi: f32) -> Vec3 {
        let (theta, phi) = (theta.to_radians(), phi.to_radians());
        Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
    }

    /// Triangles `tris` turned to face away from the origin.
    fn outward(v: &[Vec3], tris: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
        tris.into_iter()
            .map(|[a, b, c]| {
                let (pa, pb, pc) = (v[a as usize], v[b as usize], v[c as usize]);
                if (pb - pa).cross(pc - pa).dot(pa + pb + pc) < 0.0 {
                    [a, c, b]
                } else {
                    [a, b, c]
                }
            })
            .collect()
    }

    fn icosahedron() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let lat = 90.0 - 0.5f32.atan().to_degrees();
        let mut v = vec![on_sphere(0.0, 0.0), on_sphere(180.0, 0.0)];
        v.extend((0..5).map(|k| on_sphere(lat, 72.0 * k as f32))); // 2..7: upper ring
        v.extend((0..5).map(|k| on_sphere(180.0 - lat, 36.0 + 72.0 * k as f32))); // 7..12: lower
        let (up, lo) = (|k: u32| 2 + k % 5, |k: u32| 7 + k % 5);
        let mut tris = Vec::with_capacity(20);
        for k in 0..5 {
            tris.push([0, up(k), up(k + 1)]);
            tris.push([1, lo(k), lo(k + 1)]);
            tris.push([up(k), up(k + 1), lo(k)]);
            tris.push([lo(k), lo(k + 1), up(k + 1)]);
        }
        let tris = outward(&v, tris);
        (v, tris)
    }

    fn cube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let v: Vec<Vec3> = (0..8)
            .map(|i| {
                let s = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
                Vec3::new(s(1), s(2), s(4))
            })
            .collect();
        // each face: the four corners with one coordinate fixed, as two triangles
        let mut tris = Vec::with_capacity(12);
        for axis in [1u32, 2, 4] {
            let (a, b) = match axis {
                1 => (2, 4),
                2 => (1, 4),
                _ => (1, 2),
            };
            for side in [0, axis] {
                let q = [side, side | a, side | a | b, side | b];
                tris.push([q[0], q[1], q[2]]);
                tris.push([q[0], q[2], q[3]]);
            }
        }
        let tris = outward(&v, tris);
        (v, tris)
    }

    fn uv_sphere() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        const RINGS: u32 = 4;
        const SEGMENTS: u32 = 9;
        let mut v = vec![on_sphere(0.0, 0.0), on_sphere(180.0, 0.0)];
        for j in 1..=RINGS {
            for k in 0..SEGMENTS {
                v.push(on_sphere(36.0 * j as f32, -50.0 + 40.0 * k as f32));
            }
        }
        let at = |j: u32, k: u32| 2 + (j - 1) * SEGMENTS + k % SEGMENTS;
        let mut tris = Vec::with_capacity(72);
        for k in 0..SEGMENTS {
            tris.push([0, at(1, k), at(1, k + 1)]);
            tris.push([1, at(RINGS, k), at(RINGS, k + 1)]);
            for j in 1..RINGS {
                tris.push([at(j, k), at(j, k + 1), at(j + 1, k)]);
                tris.push([at(j, k + 1), at(j + 1, k + 1), at(j + 1, k)]);
            }
        }
        let tris = outward(&v, tris);
        (v, tris)
    }

    #[test]
    fn the_tables_are_the_polyhedra_the_manual_describes() {
        for (shell, (vertices, faces)) in [
            (ShellTemplate::IcoSphere, icosahedron()),
            (ShellTemplate::Box, cube()),
            (ShellTemplate::UvSphere, uv_sphere()),
        ] {
            let built = Shell::Mesh { positions: vertices, indices: faces };
            let (a, b) = (unit(&Shell::Named(shell)), unit(&built));
            for p in &a.positions {
                let nearest =
                    b.positions.iter().map(|q| (*p - *q).length()).fold(f32::MAX, f32::min);
                assert!(nearest < 1e-4, "{shell:?}: vertex {p} is not the definition's");
            }
            assert_eq!(a.indices.len(), b.indices.len(), "{shell:?}");
        }
    }

    #[test]
    fn the_icosahedron_is_regular() {
        let m = unit(&Shell::Named(ShellTemplate::IcoSphere));
        let edge = |a: u32, b: u32| (m.positions[a as usize] - m.positions[b as usize]).length();
        let first = edge(m.indices[0][0], m.indices[0][1]);
        for &[a, b, c] in &m.indices {
            for l in [edge(a, b), edge(b, c), edge(c, a)] {
                assert!((l - first).abs() < 1e-4, "edge {l} against {first}");
            }
        }
    }

    #[test]
    fn each_ellipsoid_gets_its_own_placed_copy() {
        let rotation = Mat3::from_quat(Quat::from_rotation_y(0.6));
        let e = [
            Ellipsoid {
                center: Vec3::new(1.0, 2.0, 3.0),
                scale: Vec3::new(0.1, 0.2, 0.3),
                rotation,
            },
            Ellipsoid { center: Vec3::ZERO, scale: Vec3::ONE, rotation: Mat3::IDENTITY },
        ];
        let m = ellipsoid_shells(&e, &[2.0, 1.0], &Shell::Named(ShellTemplate::Box)).unwrap();
        assert_eq!((m.positions.len(), m.indices.len()), (48, 24));
        assert!(m.indices[12..].iter().flatten().all(|&i| i >= 24));
        let a = 1.0 / Vec3::new(1.0 / 3.0, 1.0, 1.0 / 3.0).length();
        for p in &m.positions[..24] {
            let local = rotation.transpose() * (*p - e[0].center) / (e[0].scale * 2.0);
            assert!((local.abs() - Vec3::splat(a)).abs().max_element() < 1e-5, "{local}");
        }
    }

    #[test]
    fn shells_are_hit_from_outside_only() {
        use crate::geometry::{Transform, NO_INSTANCE};
        let e = Ellipsoid { center: Vec3::ZERO, scale: Vec3::ONE, rotation: Mat3::IDENTITY };
        let data = ellipsoid_shells(&[e], &[1.0], &Shell::Named(ShellTemplate::IcoSphere)).unwrap();
        for flip in [false, true] {
            let mesh = Mesh::from_data(data.clone(), &Transform::default(), flip, true).unwrap();
            let shells = EllipsoidShells::new(mesh);
            let first_hit = |ray: &Ray| {
                (0..shells.triangle_count())
                    .filter_map(|k| shells.intersect_prim(k, ray).map(|(t, uv)| (t, uv, k)))
                    .min_by(|a, b| a.0.total_cmp(&b.0))
            };
            for d in [Vec3::X, Vec3::Y, Vec3::new(0.3, -0.5, 0.8).normalize()] {
                assert!(first_hit(&Ray::new(Vec3::ZERO, d, f32::INFINITY)).is_none());
                let ray = Ray::new(d * 5.0, -d, f32::INFINITY);
                let (t, uv, prim) = first_hit(&ray).expect("hit from outside");
                assert!(t > 3.5 && t < 4.0, "t = {t}");
                let hit = PreliminaryHit { t, uv, shape: 0, prim, instance: NO_INSTANCE };
                let n = shells.interaction(&ray, &hit).n;
                assert_eq!(n.dot(d) > 0.0, !flip, "flip {flip}: normal {n} seen along {d}");
            }
        }
    }

    #[test]
    fn a_shell_through_its_centre_is_refused() {
        let flat =
            Shell::Mesh { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], indices: vec![[0, 1, 2]] };
        let e = Ellipsoid { center: Vec3::ZERO, scale: Vec3::ONE, rotation: Mat3::IDENTITY };
        assert!(ellipsoid_shells(&[e], &[1.0], &flat).is_err());
    }
}
