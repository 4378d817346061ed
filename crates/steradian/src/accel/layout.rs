//! The 8-wide BVH's memory layout: nodes, triangle packets, analytic references and child codes.
//!
//! - [`Node8`] (256 bytes, 4 cache lines): the boxes of up to 8 children in SoA layout
//!   (`bounds[plane][lane]`, planes min x, y, z then max x, y, z) and one 32-bit code per child.
//!   Unused lanes hold the empty box (min +∞, max −∞), which no ray enters.
//! - A child code is a node index, or a leaf: bit 31 set, bit 30 set for a leaf of analytic
//!   primitives, bits 26–29 the number of items, bits 0–25 the first item.
//! - Triangle leaves are runs of [`Tri4`] packets: 4 triangles' vertices in SoA layout, in leaf
//!   order, so traversal never reads the mesh (144 bytes: the tests read only vertices; the
//!   shape and primitive index of each lane are in a parallel array read once per hit).
//!   Empty lanes hold NaN vertices, which never hit.
//! - Analytic leaves list `(shape, prim)` pairs tested through [`Shape::intersect_prim`].
//!

use glam::Vec3;

use crate::geometry::Aabb;

/// Children per node.
pub(super) const WIDTH: usize = 8;

/// An 8-wide node: the children's boxes in SoA layout and the children's codes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct Node8 {
    /// `bounds[plane][lane]`: planes 0–2 are min x, y, z, planes 3–5 max x, y, z.
    pub bounds: [[f32; WIDTH]; 6],
    pub child: [u32; WIDTH],
}

const _: () = assert!(std::mem::size_of::<Node8>() == 256);

impl Node8 {
    pub(super) const EMPTY: Node8 = Node8 {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [EMPTY_CHILD; WIDTH],
    };

    /// The box of child slot `lane`.
    pub(super) fn child_bounds(&self, lane: usize) -> Aabb {
        let b = &self.bounds;
        Aabb::new(
            Vec3::new(b[0][lane], b[1][lane], b[2][lane]),
            Vec3::new(b[3][lane], b[4][lane], b[5][lane]),
        )
    }

    /// Sets the box of child slot `lane`.
    pub(super) fn set_child_bounds(&mut self, lane: usize, b: &Aabb) {
        for axis in 0..3 {
            self.bounds[axis][lane] = b.min[axis];
            self.bounds[axis + 3][lane] = b.max[axis];
        }
    }
}

/// Four triangles in SoA layout (144 bytes).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub(super) struct Tri4 {
    /// `v[vertex][axis][lane]`, world space, m.
    pub v: [[[f32; 4]; 3]; 3],
}

const _: () = assert!(std::mem::size_of::<Tri4>() == 144);

/// Shape and primitive index of each lane of a [`Tri4`] (`u32::MAX` for empty lanes).
#[derive(Clone, Copy, Debug)]
pub(super) struct Tri4Ids {
    pub shape: [u32; 4],
    pub prim: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<Tri4Ids>() == 32);

/// An analytic primitive in an analytic leaf.
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimRef {
    pub shape: u32,
    pub prim: u32,
}

/// [`PrimRef::shape`] of an instance (its `prim` indexes [`Accel::instances`](super::Accel)).
pub(super) const INSTANCE_REF: u32 = u32::MAX;

pub(super) const LEAF: u32 = 1 << 31;
pub(super) const ANALYTIC: u32 = 1 << 30;
const COUNT_SHIFT: u32 = 26;
const COUNT_MASK: u32 = 0xF;
const START_MASK: u32 = (1 << COUNT_SHIFT) - 1;
/// The code of an unused child slot (never entered: its box is empty) and of an empty tree.
pub(super) const EMPTY_CHILD: u32 = u32::MAX;

/// First item and item count of a leaf code.
#[inline(always)]
pub(super) fn leaf_range(code: u32) -> std::ops::Range<usize> {
    let start = (code & START_MASK) as usize;
    start..start + ((code >> COUNT_SHIFT) & COUNT_MASK) as usize
}

pub(super) fn leaf_code(start: usize, count: usize, analytic: bool) -> u32 {
    assert!(
        start + count <= START_MASK as usize,
        "scene too large for the BVH: more than {} triangle packets or analytic primitives",
        START_MASK
    );
    debug_assert!(count >= 1 && count <= COUNT_MASK as usize);
    LEAF | if analytic { ANALYTIC } else { 0 } | (count as u32) << COUNT_SHIFT | start as u32
}

/// An empty array with room for `capacity` items, in memory the kernel backs with 2 MiB pages
/// where it can (Linux transparent huge pages in `madvise` mode; Embree does the same): random
/// accesses to a BVH of tens of MB otherwise miss the TLB on almost every node.
pub(super) fn with_huge_pages<T>(capacity: usize) -> Vec<T> {
    const HUGE: usize = 2 << 20;
    let mut out: Vec<T> = Vec::with_capacity(capacity);
    let bytes = capacity * std::mem::size_of::<T>();
    #[cfg(target_os = "linux")]
    if bytes >= 2 * HUGE {
        // the 2 MiB-aligned part of the (still untouched) allocation
        let start = (out.as_mut_ptr() as usize).next_multiple_of(HUGE);
        let end = (out.as_mut_ptr() as usize + bytes) / HUGE * HUGE;
        if end > start {
            // SAFETY: madvise only gives the kernel a paging hint for whole pages inside our
            // own allocation; a failure (e.g. THP disabled) leaves ordinary pages.
            unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = bytes;
    out
}
