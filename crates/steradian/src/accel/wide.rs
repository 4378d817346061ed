//! The scene's acceleration structure: [`Accel`], built from the shapes' primitives, with the
//! kernel set chosen for this CPU, and its statistics.
//!
//! The nodes are built top-down by `wide_build.rs`, which also writes the triangle packets'
//! lane ids and frees the primitive array before laying out the nodes; the packets' vertices
//! are then filled here in parallel. So the build's peak memory is the mesh, the primitive
//! array and the unplaced nodes, or the mesh and the finished hierarchy, never both (a
//! 20-million-triangle sphere: 1.74 GB at peak, 1.73 GB at the end).

use rayon::prelude::*;

use super::instance::Instance;
use super::layout::{
    leaf_range, with_huge_pages, Node8, PrimRef, Tri4, Tri4Ids, EMPTY_CHILD, INSTANCE_REF, LEAF,
    WIDTH,
};
use super::sah_build::BuildPrim;
use super::wide_build;
use crate::geometry::Aabb;
use crate::shape::Shape;

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
        let total: usize = shapes.iter().map(|s| s.prim_count() as usize).sum();
        let mut build: Vec<BuildPrim> = Vec::with_capacity(total + instances.len());
        for (s, shape) in shapes.iter().enumerate() {
            let is_triangle = shape.triangle(0).is_some();
            build.par_extend(
                (0..shape.prim_count())
                    .into_par_iter()
                    .with_min_len(4096)
                    .map(|p| BuildPrim::new(&shape.prim_bounds(p), s as u32, p, is_triangle)),
            );
        }
        for (i, instance) in instances.iter().enumerate() {
            build.push(BuildPrim::new(&instance.bounds(), INSTANCE_REF, i as u32, false));
        }
        build.retain(BuildPrim::is_valid);
        let layout = wide_build::build(build);
        release_freed_memory();
        let mut tris = with_huge_pages::<Tri4>(layout.tri_ids.len());
        tris.par_extend(layout.tri_ids.par_iter().with_min_len(1024).map(|ids| {
            let mut p = Tri4 { v: [[[f32::NAN; 4]; 3]; 3] };
            for lane in 0..4 {
                if ids.shape[lane] == u32::MAX {
                    continue;
                }
                let tri = shapes[ids.shape[lane] as usize]
                    .triangle(ids.prim[lane])
                    .expect("triangle leaves hold triangles");
                for (k, v) in tri.iter().enumerate() {
                    for axis in 0..3 {
                        p.v[k][axis][lane] = v[axis];
                    }
                }
            }
            p
        }));
        let prefetch = std::mem::size_of_val(layout.nodes.as_slice())
            + std::mem::size_of_val(tris.as_slice())
            >= PREFETCH_MIN_BYTES;
        Accel {
            nodes: layout.nodes,
            tris,
            tri_ids: layout.tri_ids,
            others: layout.others,
            instances,
            root: layout.root,
            bounds: layout.bounds,
            isa,
            prefetch,
        }
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

    /// The tree's surface-area cost: the expected number of node visits plus triangle-packet
    /// and analytic-primitive tests of a ray that crosses the root box, each box entered with
    /// probability (its area / the root's), as the build's SAH prices them. A walk of the
    /// whole tree, for benchmarks (not part of [`Accel::stats`], which every render prints).
    pub fn sah_cost(&self) -> f64 {
        let root_area = self.bounds.surface_area() as f64;
        if self.root == EMPTY_CHILD || root_area.is_nan() || root_area <= 0.0 {
            return 0.0;
        }
        let mut cost = 0.0;
        let mut todo = vec![(self.root, root_area)];
        while let Some((code, area)) = todo.pop() {
            if code & LEAF != 0 {
                cost += area * leaf_range(code).len() as f64;
                continue;
            }
            cost += area;
            let n = &self.nodes[code as usize];
            for lane in 0..WIDTH {
                if n.child[lane] != EMPTY_CHILD {
                    todo.push((n.child[lane], n.child_bounds(lane).surface_area() as f64));
                }
            }
        }
        cost / root_area
    }
}

/// Hands memory the allocator holds free back to the system. The build's chunks of nodes are
/// many small allocations in the threads' arenas, freed once laid out; without this the
/// process keeps them (about 300 MB for a 20-million-triangle mesh) under the finished
/// hierarchy.
fn release_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free pages of glibc's heaps to the kernel.
    unsafe {
        libc::malloc_trim(0);
    }
}
