//! # `cube`: an axis-aligned box mesh
//!
//! Mitsuba plugin `cube`: the cube [−1, 1]³ as a triangle mesh of 24 vertices (4 per face, so
//! every face has its own flat normal) and 12 triangles, with outward normals and per-face
//! uvs covering [0, 1]². Use `to_world` to size and place it.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `to_world` | transform | identity | places the cube |
//! | `flip_normals` | bool | false | normals point inwards |
//!
//! steradian builds exactly Mitsuba's vertex/triangle layout and treats it as any [`Mesh`].

use glam::{Vec2, Vec3};

use super::Mesh;
use crate::geometry::Transform;

const VERTICES: [[f32; 3]; 24] = [
    [1.0, -1.0, -1.0],
    [1.0, -1.0, 1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, 1.0, 1.0],
    [1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [1.0, 1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [1.0, -1.0, -1.0],
    [-1.0, -1.0, -1.0],
    [-1.0, 1.0, -1.0],
];
const FACE_NORMALS: [[f32; 3]; 6] = [
    [0.0, -1.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0],
    [-1.0, 0.0, 0.0],
    [0.0, 0.0, -1.0],
];
const FACE_UVS: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];

/// Mitsuba's cube mesh, transformed by `to_world`.
pub fn cube(to_world: &Transform, flip_normals: bool) -> Mesh {
    let positions = VERTICES.iter().map(|&v| Vec3::from(v)).collect();
    let normals = (0..24).map(|i| Vec3::from(FACE_NORMALS[i / 4])).collect();
    let uvs = (0..24).map(|i| Vec2::from(FACE_UVS[i % 4])).collect();
    let indices = (0..6u32)
        .flat_map(|f| [[4 * f, 4 * f + 1, 4 * f + 2], [4 * f + 3, 4 * f, 4 * f + 2]])
        .collect();
    Mesh::new(positions, Some(normals), Some(uvs), indices, to_world, flip_normals, false)
        .expect("the cube's built-in data is valid for any finite transform")
}
