//! The 8-wide BVH: node and triangle layouts, and the collapse of the binary SAH tree into it.
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
//! The collapse (as in Embree's BVH8 builder) takes a binary node's two children and keeps
//! replacing the interior child of largest surface area by its two children until there are 8
//! or only leaves remain.

use glam::Vec3;

use super::instance::Instance;
use super::sah_build::{self, BinaryNode, BuildPrim};
use crate::geometry::Aabb;
use crate::shape::Shape;

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
    const EMPTY: Node8 = Node8 {
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

/// [`PrimRef::shape`] of an instance (its `prim` indexes [`Accel::instances`]).
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

fn leaf_code(start: usize, count: usize, analytic: bool) -> u32 {
    assert!(
        start + count <= START_MASK as usize,
        "scene too large for the BVH: more than {} triangle packets or analytic primitives",
        START_MASK
    );
    debug_assert!(count >= 1 && count <= COUNT_MASK as usize);
    LEAF | if analytic { ANALYTIC } else { 0 } | (count as u32) << COUNT_SHIFT | start as u32
}

/// The instruction set the traversal kernels use, chosen once when the BVH is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// Portable scalar code.
    Scalar,
    /// x86-64 AVX2: 8 boxes per instruction; 8 triangles (two packets of a leaf) per
    /// instruction, or 4 (a leaf's odd last packet) per SSE instruction (VEX encoded).
    Avx2,
}

impl Isa {
    /// The best kernel set this CPU supports.
    pub fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            return Isa::Avx2;
        }
        Isa::Scalar
    }

    /// Whether this CPU can run the kernels of `self`.
    pub fn is_supported(self) -> bool {
        match self {
            Isa::Scalar => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            Isa::Avx2 => false,
        }
    }
}

/// The scene's acceleration structure: an 8-wide BVH over the primitives of all shapes.
#[derive(Clone, Debug)]
pub struct Accel {
    pub(super) nodes: Vec<Node8>,
    pub(super) tris: Vec<Tri4>,
    /// Parallel to `tris`.
    pub(super) tri_ids: Vec<Tri4Ids>,
    pub(super) others: Vec<PrimRef>,
    /// Instances of shape groups; an entry of `others` with shape [`INSTANCE_REF`] is one.
    pub(super) instances: Vec<Instance>,
    /// Code of the root (a node, a leaf, or [`EMPTY_CHILD`]).
    pub(super) root: u32,
    pub(super) bounds: Aabb,
    pub(super) isa: Isa,
    /// Whether traversal prefetches the children it stacks: only when the hierarchy is larger
    /// than [`PREFETCH_MIN_BYTES`] (a cache-resident one gains nothing from it, and pays the
    /// address arithmetic on every visit).
    pub(super) prefetch: bool,
}

/// Hierarchies smaller than this (nodes and triangle packets) stay in a core's L2 cache: their
/// traversal does not prefetch (the address arithmetic was 2 % of a Cornell box's instructions,
/// 2026-12-01).
const PREFETCH_MIN_BYTES: usize = 1 << 20;

impl Default for Accel {
    fn default() -> Self {
        Accel {
            nodes: Vec::new(),
            tris: Vec::new(),
            tri_ids: Vec::new(),
            others: Vec::new(),
            instances: Vec::new(),
            root: EMPTY_CHILD,
            bounds: Aabb::EMPTY,
            isa: Isa::detect(),
            prefetch: false,
        }
    }
}

/// Sizes of the structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccelStats {
    pub nodes: usize,
    pub triangle_packets: usize,
    pub triangles: usize,
    /// Analytic primitives, instances included.
    pub analytic_prims: usize,
    /// Instances of shape groups (their groups' own hierarchies are not counted here).
    pub instances: usize,
    /// Bytes of nodes, triangle packets and analytic references.
    pub bytes: usize,
}

impl Accel {
    /// Builds the BVH over every primitive of every shape with the best kernels of this CPU.
    /// Primitives with empty or non-finite bounds (degenerate data) are left out.
    pub fn build(shapes: &[Shape]) -> Accel {
        Accel::build_with_isa(shapes, Isa::detect())
    }

    /// [`Accel::build`] with a given kernel set (falls back to scalar where the CPU lacks it).
    pub fn build_with_isa(shapes: &[Shape], isa: Isa) -> Accel {
        Accel::build_with_instances(shapes, Vec::new(), isa)
    }

    /// The BVH over every primitive of `shapes` and every instance (one primitive each, with
    /// its world bounds); hits on an instance name it in [`PreliminaryHit::instance`](crate::geometry::PreliminaryHit::instance).
    pub fn build_with_instances(shapes: &[Shape], instances: Vec<Instance>, isa: Isa) -> Accel {
        let isa = if isa.is_supported() { isa } else { Isa::Scalar };
        let mut build: Vec<BuildPrim> = Vec::new();
        for (s, shape) in shapes.iter().enumerate() {
            let is_triangle = shape.triangle(0).is_some();
            let n = shape.prim_count();
            let first = build.len();
            build.resize(
                first + n as usize,
                BuildPrim {
                    bounds: Aabb::EMPTY,
                    centroid: Vec3::ZERO,
                    shape: s as u32,
                    prim: 0,
                    is_triangle,
                },
            );
            use rayon::prelude::*;
            build[first..].par_iter_mut().with_min_len(4096).enumerate().for_each(|(p, bp)| {
                bp.prim = p as u32;
                bp.bounds = shape.prim_bounds(p as u32);
                bp.centroid = bp.bounds.center();
            });
        }
        for (i, instance) in instances.iter().enumerate() {
            let bounds = instance.bounds();
            build.push(BuildPrim {
                bounds,
                centroid: bounds.center(),
                shape: INSTANCE_REF,
                prim: i as u32,
                is_triangle: false,
            });
        }
        build.retain(|b| {
            !b.bounds.is_empty() && b.bounds.min.is_finite() && b.bounds.max.is_finite()
        });
        let mut accel = Accel { isa, instances, ..Accel::default() };
        if build.is_empty() {
            return accel;
        }
        let tree = sah_build::build(&mut build);
        accel.bounds = *tree.bounds();
        let mut c = Collapse { shapes, prims: &build, accel: &mut accel };
        let root = c.emit(&tree);
        accel.root = root;
        accel.nodes = on_huge_pages(std::mem::take(&mut accel.nodes));
        accel.tris = on_huge_pages(std::mem::take(&mut accel.tris));
        accel.prefetch = std::mem::size_of_val(accel.nodes.as_slice())
            + std::mem::size_of_val(accel.tris.as_slice())
            >= PREFETCH_MIN_BYTES;
        accel
    }

    /// Instance `i` (as a hit names it in [`PreliminaryHit::instance`]).
    ///
    /// [`PreliminaryHit::instance`]: crate::geometry::PreliminaryHit::instance
    #[inline]
    pub fn instance(&self, i: u32) -> &Instance {
        &self.instances[i as usize]
    }

    /// Bounds of everything in the hierarchy (empty for an empty scene).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The kernel set in use.
    pub fn isa(&self) -> Isa {
        self.isa
    }

    pub fn stats(&self) -> AccelStats {
        let triangles =
            self.tri_ids.iter().flat_map(|p| p.shape).filter(|&s| s != u32::MAX).count();
        AccelStats {
            nodes: self.nodes.len(),
            triangle_packets: self.tris.len(),
            triangles,
            analytic_prims: self.others.len(),
            instances: self.instances.len(),
            bytes: self.nodes.len() * std::mem::size_of::<Node8>()
                + self.tris.len() * (std::mem::size_of::<Tri4>() + std::mem::size_of::<Tri4Ids>())
                + self.others.len() * std::mem::size_of::<PrimRef>(),
        }
    }
}

/// Moves a large array to memory the kernel backs with 2 MiB pages where it can (Linux
/// transparent huge pages in `madvise` mode; Embree does the same): random accesses to a
/// BVH of tens of MB otherwise miss the TLB on almost every node.
fn on_huge_pages<T: Copy>(v: Vec<T>) -> Vec<T> {
    const HUGE: usize = 2 << 20;
    let bytes = std::mem::size_of_val(v.as_slice());
    if bytes < 2 * HUGE {
        return v;
    }
    let mut out: Vec<T> = Vec::with_capacity(v.len());
    #[cfg(target_os = "linux")]
    {
        // the 2 MiB-aligned part of the (still untouched) allocation
        let start = (out.as_mut_ptr() as usize).next_multiple_of(HUGE);
        let end = (out.as_mut_ptr() as usize + bytes) / HUGE * HUGE;
        if end > start {
            // SAFETY: madvise only gives the kernel a paging hint for whole pages inside our
            // own allocation; a failure (e.g. THP disabled) leaves ordinary pages.
            unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
        }
    }
    out.extend_from_slice(&v);
    out
}

/// What the collapse may put in place of a node: its two halves, if it has them of this kind.
type Halves = fn(&BinaryNode) -> Option<&[BinaryNode; 2]>;

struct Collapse<'a> {
    shapes: &'a [Shape],
    prims: &'a [BuildPrim],
    accel: &'a mut Accel,
}

impl Collapse<'_> {
    /// Writes the subtree of `n` and returns its child code.
    fn emit(&mut self, n: &BinaryNode) -> u32 {
        match n {
            BinaryNode::Leaf { start, count, triangles: true, .. } => {
                let first = self.accel.tris.len();
                for chunk in self.prims[*start..start + count].chunks(4) {
                    let mut p = Tri4 { v: [[[f32::NAN; 4]; 3]; 3] };
                    let mut ids = Tri4Ids { shape: [u32::MAX; 4], prim: [u32::MAX; 4] };
                    for (lane, bp) in chunk.iter().enumerate() {
                        let tri = self.shapes[bp.shape as usize]
                            .triangle(bp.prim)
                            .expect("triangle leaves hold triangles");
                        for (k, v) in tri.iter().enumerate() {
                            for axis in 0..3 {
                                p.v[k][axis][lane] = v[axis];
                            }
                        }
                        ids.shape[lane] = bp.shape;
                        ids.prim[lane] = bp.prim;
                    }
                    self.accel.tris.push(p);
                    self.accel.tri_ids.push(ids);
                }
                leaf_code(first, self.accel.tris.len() - first, false)
            }
            BinaryNode::Leaf { start, count, triangles: false, .. } => {
                let first = self.accel.others.len();
                self.accel.others.extend(
                    self.prims[*start..start + count]
                        .iter()
                        .map(|bp| PrimRef { shape: bp.shape, prim: bp.prim }),
                );
                leaf_code(first, *count, true)
            }
            BinaryNode::Inner { children, .. } => {
                let mut kids: Vec<&BinaryNode> = vec![&children[0], &children[1]];
                // inner nodes first, the largest first; then, while slots are still free, the
                // leaves' refinements (see `BinaryNode`)
                for halves in [BinaryNode::children as Halves, BinaryNode::refinement] {
                    while kids.len() < WIDTH {
                        let widest = kids
                            .iter()
                            .enumerate()
                            .filter_map(|(i, &k)| {
                                halves(k).map(|h| (i, k.bounds().surface_area(), h))
                            })
                            .max_by(|a, b| a.1.total_cmp(&b.1));
                        let Some((i, _, [left, right])) = widest else { break };
                        kids[i] = left;
                        kids.push(right);
                    }
                }
                let idx = self.accel.nodes.len();
                assert!(
                    idx < ANALYTIC as usize,
                    "scene too large for the BVH: more than 2^30 nodes"
                );
                self.accel.nodes.push(Node8::EMPTY);
                for (lane, k) in kids.iter().enumerate() {
                    let code = self.emit(k);
                    let b = k.bounds();
                    let node = &mut self.accel.nodes[idx];
                    node.child[lane] = code;
                    for axis in 0..3 {
                        node.bounds[axis][lane] = b.min[axis];
                        node.bounds[axis + 3][lane] = b.max[axis];
                    }
                }
                idx as u32
            }
        }
    }
}
