//! Binned-SAH BVH build.
//!
//! Layout (kept simple so that a later 4/8-wide BVH can replace it):
//! - `nodes`: flattened 32-byte nodes in depth-first order; the two children of an interior
//!   node are adjacent (`left = offset`, `right = offset + 1`).
//! - `prims`: primitive references `(shape, prim)` in leaf order; a leaf covers
//!   `prims[offset .. offset + count]`.
//! - `tris`: a compact copy of the world-space vertices of every triangle, in leaf order, so
//!   that traversal never goes through [`Shape::Mesh`]; analytic shapes are tested with
//!   [`Shape::intersect_prim`].

use glam::Vec3;

use crate::geometry::Aabb;
use crate::shape::{is_positive, Shape};

/// A flattened BVH node (32 bytes).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(super) struct Node {
    pub min: [f32; 3],
    /// Interior: index of the left child (the right one follows it). Leaf: first primitive.
    pub offset: u32,
    pub max: [f32; 3],
    /// Leaf: number of primitives (> 0). Interior: 0.
    pub count: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 32);

/// Marks a primitive that is not a triangle (tested through its shape).
pub(super) const NOT_A_TRIANGLE: u32 = u32::MAX;

/// A primitive as stored in leaf order.
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimRef {
    pub shape: u32,
    pub prim: u32,
    /// Index into `tris`, or [`NOT_A_TRIANGLE`].
    pub tri: u32,
}

/// The scene's acceleration structure.
#[derive(Clone, Debug, Default)]
pub struct Accel {
    pub(super) nodes: Vec<Node>,
    pub(super) prims: Vec<PrimRef>,
    pub(super) tris: Vec<[Vec3; 3]>,
}

const BINS: usize = 16;
const MAX_LEAF: usize = 8;
/// Cost of a node traversal relative to one primitive test.
const TRAVERSAL_COST: f32 = 1.0;

#[derive(Clone, Copy)]
struct BuildPrim {
    bounds: Aabb,
    centroid: Vec3,
    shape: u32,
    prim: u32,
}

impl Accel {
    /// Builds the BVH over every primitive of every shape. Primitives with empty or
    /// non-finite bounds (degenerate data) are left out.
    pub fn build(shapes: &[Shape]) -> Accel {
        let mut build: Vec<BuildPrim> = Vec::new();
        for (s, shape) in shapes.iter().enumerate() {
            for p in 0..shape.prim_count() {
                let b = shape.prim_bounds(p);
                if b.is_empty() || !b.min.is_finite() || !b.max.is_finite() {
                    continue;
                }
                build.push(BuildPrim { bounds: b, centroid: b.center(), shape: s as u32, prim: p });
            }
        }
        let mut accel = Accel::default();
        if build.is_empty() {
            return accel;
        }
        accel.nodes.reserve(2 * build.len() / MAX_LEAF.max(1) + 1);
        accel.nodes.push(Node { min: [0.0; 3], offset: 0, max: [0.0; 3], count: 0 });
        let n = build.len();
        accel.build_node(0, &mut build, 0, n);
        accel.prims = build
            .iter()
            .map(|b| {
                let tri = match &shapes[b.shape as usize] {
                    Shape::Mesh(m) => {
                        accel.tris.push(m.triangle(b.prim));
                        (accel.tris.len() - 1) as u32
                    }
                    _ => NOT_A_TRIANGLE,
                };
                PrimRef { shape: b.shape, prim: b.prim, tri }
            })
            .collect();
        accel
    }

    /// Fills node `idx` with the primitives `prims[start..end]` (reordered in place).
    fn build_node(&mut self, idx: usize, prims: &mut [BuildPrim], start: usize, end: usize) {
        let items = &mut prims[start..end];
        let mut bounds = Aabb::EMPTY;
        let mut cbounds = Aabb::EMPTY;
        for p in items.iter() {
            bounds = bounds.union(&p.bounds);
            cbounds.grow(p.centroid);
        }
        let count = items.len();
        let make_leaf = |nodes: &mut Vec<Node>| {
            nodes[idx] = Node { min: bounds.min.to_array(), offset: start as u32, max: bounds.max.to_array(), count: count as u32 };
        };
        if count == 1 {
            make_leaf(&mut self.nodes);
            return;
        }
        let mid = match sah_split(items, &bounds, &cbounds) {
            Some(split) => split,
            None if count <= MAX_LEAF => {
                make_leaf(&mut self.nodes);
                return;
            }
            None => {
                // SAH prefers a leaf (or all centroids coincide) but the leaf would be too big:
                // split at the median along the widest centroid axis.
                let axis = cbounds.max_axis();
                let half = count / 2;
                items.select_nth_unstable_by(half, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
                half
            }
        };
        let left = self.nodes.len();
        self.nodes.push(Node { min: [0.0; 3], offset: 0, max: [0.0; 3], count: 0 });
        self.nodes.push(Node { min: [0.0; 3], offset: 0, max: [0.0; 3], count: 0 });
        self.nodes[idx] = Node { min: bounds.min.to_array(), offset: left as u32, max: bounds.max.to_array(), count: 0 };
        self.build_node(left, prims, start, start + mid);
        self.build_node(left + 1, prims, start + mid, end);
    }
}

/// Binned SAH: partitions `items` and returns the size of the left part, or `None` when a
/// leaf is cheaper (or no split separates the centroids).
fn sah_split(items: &mut [BuildPrim], bounds: &Aabb, cbounds: &Aabb) -> Option<usize> {
    let count = items.len();
    let extent = cbounds.extent();
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, split bin)
    for axis in 0..3 {
        if !is_positive(extent[axis]) {
            continue;
        }
        let scale = BINS as f32 / extent[axis];
        let bin_of = |c: Vec3| (((c[axis] - cbounds.min[axis]) * scale) as usize).min(BINS - 1);
        let mut bin_bounds = [Aabb::EMPTY; BINS];
        let mut bin_count = [0usize; BINS];
        for p in items.iter() {
            let b = bin_of(p.centroid);
            bin_bounds[b] = bin_bounds[b].union(&p.bounds);
            bin_count[b] += 1;
        }
        // sweep from the right to get suffix areas
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0usize; BINS];
        let mut acc = Aabb::EMPTY;
        let mut n = 0;
        for i in (1..BINS).rev() {
            acc = acc.union(&bin_bounds[i]);
            n += bin_count[i];
            right_area[i] = acc.surface_area();
            right_count[i] = n;
        }
        let mut acc = Aabb::EMPTY;
        let mut n = 0;
        for i in 0..BINS - 1 {
            acc = acc.union(&bin_bounds[i]);
            n += bin_count[i];
            let (nl, nr) = (n, right_count[i + 1]);
            if nl == 0 || nr == 0 {
                continue;
            }
            let cost = acc.surface_area() * nl as f32 + right_area[i + 1] * nr as f32;
            if best.is_none() || best.is_some_and(|(c, _, _)| cost < c) {
                best = Some((cost, axis, i));
            }
        }
    }
    let (cost, axis, split) = best?;
    let area = bounds.surface_area();
    let split_cost = if area > 0.0 { TRAVERSAL_COST + cost / area } else { TRAVERSAL_COST };
    if split_cost >= count as f32 && count <= MAX_LEAF {
        return None;
    }
    let scale = BINS as f32 / extent[axis];
    let in_left = |p: &BuildPrim| ((((p.centroid[axis] - cbounds.min[axis]) * scale) as usize).min(BINS - 1)) <= split;
    // in-place partition
    let mut i = 0;
    for j in 0..count {
        if in_left(&items[j]) {
            items.swap(i, j);
            i += 1;
        }
    }
    (i > 0 && i < count).then_some(i)
}
