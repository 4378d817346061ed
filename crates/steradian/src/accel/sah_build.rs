//! Binned-SAH build of a binary BVH (Wald, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies", 2007), in parallel: subtrees are built with `rayon::join`, and the binning of
//! large nodes is split over threads too.
//!
//! The binary tree is only an intermediate: `wide.rs` collapses it into the 8-wide BVH that is
//! traversed. The SAH cost counts triangles in packets of [`TRI_BLOCK`] (a leaf of 5 triangles
//! costs as much as one of 8, they are stored 4 to a packet), as Embree does. Traversal tests a
//! leaf's packets in pairs, 8 lanes at a time (`simd.rs`), but costing leaves by pairs (blocks
//! of 8) did not change render times on the reference scenes (cornell +0.5 %, materials
//! −3.2 %, veach +0.1 %, within noise; 2026-12-02, AMD EPYC, 2 cores), so the cost stays that
//! of 4-triangle packets.

use glam::Vec3;
use rayon::prelude::*;

use crate::geometry::is_positive;
use crate::geometry::Aabb;

/// Number of SAH bins per axis.
const BINS: usize = 32;
/// Largest leaf, in primitives.
pub(super) const MAX_LEAF: usize = 8;
/// Triangles are stored 4 to a packet.
pub(super) const TRI_BLOCK: usize = 4;
/// Cost of one node visit relative to one triangle-packet test.
const TRAVERSAL_COST: f32 = 1.0;
/// A leaf's refinement that adds triangle packets is kept only where it brings the leaf's
/// expected tests below this fraction of the whole leaf's (see `refined_leaf`).
const REFINE_GROWTH_GAIN: f32 = 0.75;
/// Beyond this depth nodes are split at the object median: the depth stays bounded (and with it
/// the traversal stack) whatever the input.
pub(super) const SAH_MAX_DEPTH: usize = 40;
/// Nodes with more primitives than this are built in parallel.
const PARALLEL_MIN: usize = 4096;
/// Nodes with more primitives than this also bin in parallel.
const PARALLEL_BINNING_MIN: usize = 65536;

/// A primitive as the builder sees it.
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildPrim {
    pub bounds: Aabb,
    pub centroid: Vec3,
    pub shape: u32,
    pub prim: u32,
    /// Triangles are packed 4 to a leaf packet; other primitives are tested one by one.
    pub is_triangle: bool,
}

/// A node of the binary tree. Leaves cover `prims[start..start + count]`, all of one kind.
///
/// A leaf of several primitives also carries `refined`: the SAH's best split of it, itself made
/// of refined leaves. The SAH prices a split at one more node visit, but the collapse to
/// [`WIDTH`](super::wide::WIDTH)-wide nodes tests all children of a wide node at once, so where
/// a wide node has a child slot to spare the split costs no visit at all and lets the box test
/// cull part of the leaf. The collapse uses refinements only there (`wide.rs`).
#[derive(Debug)]
pub(super) enum BinaryNode {
    Leaf {
        bounds: Aabb,
        start: usize,
        count: usize,
        triangles: bool,
        refined: Option<Box<[BinaryNode; 2]>>,
    },
    Inner {
        bounds: Aabb,
        children: Box<[BinaryNode; 2]>,
    },
}

/// When [`sah_split`] may answer that a leaf is cheaper.
#[derive(Clone, Copy, PartialEq, Eq)]
enum SplitPolicy {
    /// The SAH's choice: `None` where a leaf costs less than the best split.
    LeafIfCheaper,
    /// The best split whatever it costs (`None` only where no bin boundary separates the
    /// centroids): the refinement of a leaf.
    Always,
}

impl BinaryNode {
    pub fn bounds(&self) -> &Aabb {
        match self {
            BinaryNode::Leaf { bounds, .. } | BinaryNode::Inner { bounds, .. } => bounds,
        }
    }

    /// An inner node's two children.
    pub fn children(&self) -> Option<&[BinaryNode; 2]> {
        match self {
            BinaryNode::Inner { children, .. } => Some(children),
            BinaryNode::Leaf { .. } => None,
        }
    }

    /// A leaf's refinement.
    pub fn refinement(&self) -> Option<&[BinaryNode; 2]> {
        match self {
            BinaryNode::Leaf { refined, .. } => refined.as_deref(),
            BinaryNode::Inner { .. } => None,
        }
    }
}

/// Builds the tree over `prims`, reordering them so that every leaf is a contiguous range.
pub(super) fn build(prims: &mut [BuildPrim]) -> BinaryNode {
    build_node(prims, 0, 0)
}

fn leaf_cost(n: usize, triangles: bool) -> f32 {
    if triangles {
        n.div_ceil(TRI_BLOCK) as f32
    } else {
        n as f32
    }
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: usize,
    /// Non-triangle primitives in the bin (they cost one test each).
    other: usize,
}

const EMPTY_BIN: Bin = Bin { bounds: Aabb::EMPTY, count: 0, other: 0 };

type Bins = [[Bin; BINS]; 3];

fn bin_index(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BINS - 1)
}

fn bin_prims(items: &[BuildPrim], cmin: Vec3, scale: Vec3) -> Box<Bins> {
    let mut bins = Box::new([[EMPTY_BIN; BINS]; 3]);
    for p in items {
        for axis in 0..3 {
            let b = &mut bins[axis][bin_index(p.centroid[axis], cmin[axis], scale[axis])];
            b.bounds = b.bounds.union(&p.bounds);
            b.count += 1;
            b.other += !p.is_triangle as usize;
        }
    }
    bins
}

fn merge_bins(mut a: Box<Bins>, b: Box<Bins>) -> Box<Bins> {
    for axis in 0..3 {
        for i in 0..BINS {
            let (x, y) = (&mut a[axis][i], &b[axis][i]);
            x.bounds = x.bounds.union(&y.bounds);
            x.count += y.count;
            x.other += y.other;
        }
    }
    a
}

/// Cost of `n` primitives of which `other` are not triangles.
fn block_cost(n: usize, other: usize) -> f32 {
    (n - other).div_ceil(TRI_BLOCK) as f32 + other as f32
}

/// The bounds of `prims`, the bounds of their centroids, and how many are triangles.
fn extent(prims: &[BuildPrim]) -> (Aabb, Aabb, usize) {
    let mut bounds = Aabb::EMPTY;
    let mut cbounds = Aabb::EMPTY;
    let mut triangles = 0usize;
    for p in prims {
        bounds = bounds.union(&p.bounds);
        cbounds.grow(p.centroid);
        triangles += p.is_triangle as usize;
    }
    (bounds, cbounds, triangles)
}

fn build_node(prims: &mut [BuildPrim], offset: usize, depth: usize) -> BinaryNode {
    let (bounds, cbounds, triangles) = extent(prims);
    let count = prims.len();
    let pure = triangles == count || triangles == 0;
    if count == 1 {
        return BinaryNode::Leaf {
            bounds,
            start: offset,
            count,
            triangles: triangles == count,
            refined: None,
        };
    }
    let mid = match (depth < SAH_MAX_DEPTH)
        .then(|| sah_split(prims, &bounds, &cbounds, count - triangles, SplitPolicy::LeafIfCheaper))
        .flatten()
    {
        Some(mid) => mid,
        None if count <= MAX_LEAF && pure => return refined_leaf(prims, offset, bounds, &cbounds),
        None if count <= MAX_LEAF => {
            // the SAH wants a leaf, but leaves hold one kind: triangles first, then the rest
            let mut i = 0;
            for j in 0..count {
                if prims[j].is_triangle {
                    prims.swap(i, j);
                    i += 1;
                }
            }
            i
        }
        None => {
            // the SAH prefers a leaf (or all centroids coincide) but it would be too big, or
            // the tree is too deep: split at the median along the widest centroid axis
            let axis = cbounds.max_axis();
            let half = count / 2;
            prims
                .select_nth_unstable_by(half, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
            half
        }
    };
    let (left, right) = prims.split_at_mut(mid);
    let (l, r) = if count >= PARALLEL_MIN {
        rayon::join(
            || build_node(left, offset, depth + 1),
            || build_node(right, offset + mid, depth + 1),
        )
    } else {
        (build_node(left, offset, depth + 1), build_node(right, offset + mid, depth + 1))
    };
    BinaryNode::Inner { bounds, children: Box::new([l, r]) }
}

/// A leaf over `prims` (all of one kind, at most [`MAX_LEAF`]; `bounds` and `cbounds` from
/// [`extent`]) with its refinement (see [`BinaryNode`]), reordering `prims` within their range
/// as the refinement splits them.
fn refined_leaf(
    prims: &mut [BuildPrim],
    offset: usize,
    bounds: Aabb,
    cbounds: &Aabb,
) -> BinaryNode {
    let count = prims.len();
    let triangles = prims[0].is_triangle;
    let other = if triangles { 0 } else { count };
    // Only leaves that hold several shapes are refined: those are separate objects the SAH put
    // together (cornell's walls, materials' spheres). The triangles of one mesh in a leaf are a
    // compact patch; refining those too made sphere1m's BVH build 1.3–1.5× longer and its
    // shadow rays 0.67–0.72 of Embree's speed instead of 0.99 (benches/embree, 2 threads;
    // 2026-12-02, AMD EPYC, 2 cores).
    //
    // A refinement is kept where it lowers the expected number of tests (surface area ×
    // packets or analytic primitives; the node visit is free). One that needs more triangle
    // packets than the leaf also costs memory, so it must cut the tests to REFINE_GROWTH_GAIN
    // of the leaf's: a wall and a light pass; overlapping halves do not.
    let cost = |b: &Aabb, n: usize| b.surface_area() * leaf_cost(n, triangles);
    let several_shapes = prims.iter().any(|p| p.shape != prims[0].shape);
    let refined = (count > 1 && several_shapes)
        .then(|| sah_split(prims, &bounds, cbounds, other, SplitPolicy::Always))
        .flatten()
        .and_then(|mid| {
            let (left, right) = prims.split_at_mut(mid);
            let ((lb, lc, _), (rb, rc, _)) = (extent(left), extent(right));
            let split_cost = cost(&lb, mid) + cost(&rb, count - mid);
            let grows = leaf_cost(mid, triangles) + leaf_cost(count - mid, triangles)
                > leaf_cost(count, triangles);
            let gain = if grows && triangles { REFINE_GROWTH_GAIN } else { 1.0 };
            // the halves are refined in turn only where the split is kept
            (split_cost < gain * cost(&bounds, count)).then(|| {
                Box::new([
                    refined_leaf(left, offset, lb, &lc),
                    refined_leaf(right, offset + mid, rb, &rc),
                ])
            })
        });
    BinaryNode::Leaf { bounds, start: offset, count, triangles, refined }
}

/// Binned SAH: partitions `items` and returns the size of the left part, or `None` when a leaf
/// is cheaper under `policy` (or no bin boundary separates the centroids).
fn sah_split(
    items: &mut [BuildPrim],
    bounds: &Aabb,
    cbounds: &Aabb,
    other: usize,
    policy: SplitPolicy,
) -> Option<usize> {
    let count = items.len();
    let extent = cbounds.extent();
    let scale = Vec3::from_array(std::array::from_fn(|a| {
        if is_positive(extent[a]) {
            BINS as f32 / extent[a]
        } else {
            0.0
        }
    }));
    let bins = if count >= PARALLEL_BINNING_MIN {
        items
            .par_chunks(PARALLEL_BINNING_MIN / 4)
            .map(|c| bin_prims(c, cbounds.min, scale))
            .reduce_with(merge_bins)
            .expect("a non-empty node has a chunk")
    } else {
        bin_prims(items, cbounds.min, scale)
    };
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, last bin on the left)
    for axis in 0..3 {
        if scale[axis] == 0.0 {
            continue;
        }
        let bins = &bins[axis];
        // sweep from the right for suffix areas and costs
        let mut right_cost = [0.0f32; BINS];
        let mut acc = Aabb::EMPTY;
        let (mut n, mut o) = (0, 0);
        for i in (1..BINS).rev() {
            acc = acc.union(&bins[i].bounds);
            n += bins[i].count;
            o += bins[i].other;
            right_cost[i] = if n > 0 { acc.surface_area() * block_cost(n, o) } else { f32::NAN };
        }
        let mut acc = Aabb::EMPTY;
        let (mut n, mut o) = (0, 0);
        for i in 0..BINS - 1 {
            acc = acc.union(&bins[i].bounds);
            n += bins[i].count;
            o += bins[i].other;
            if n == 0 || n == count {
                continue;
            }
            let cost = acc.surface_area() * block_cost(n, o) + right_cost[i + 1];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, i));
            }
        }
    }
    let (cost, axis, split) = best?;
    let area = bounds.surface_area();
    let split_cost = if area > 0.0 { TRAVERSAL_COST + cost / area } else { TRAVERSAL_COST };
    let pure = other == 0 || other == count;
    if policy == SplitPolicy::LeafIfCheaper
        && count <= MAX_LEAF
        && pure
        && split_cost >= leaf_cost(count, other == 0)
    {
        return None;
    }
    let (min, s) = (cbounds.min[axis], scale[axis]);
    let in_left = |p: &BuildPrim| bin_index(p.centroid[axis], min, s) <= split;
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
