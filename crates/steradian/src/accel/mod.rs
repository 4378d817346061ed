//! Ray-tracing acceleration: an 8-wide bounding volume hierarchy over the primitives of all
//! shapes, traversed with SIMD node and triangle tests.
//!
//! Design (measured against Embree 3 with `benches/embree/run.sh`, see `benches/README.md`):
//! - Build (`sah_build.rs`): binned SAH (32 bins) over primitive boxes, subtrees and large
//!   binning passes in parallel with rayon; the SAH counts triangles in packets of 4. Leaves
//!   hold up to 8 primitives, all triangles or all analytic shapes.
//! - Layout (`wide.rs`): the binary tree is collapsed to an 8-wide BVH (BVH8 beats BVH4 on
//!   AVX2 machines: one 256-bit test covers all children). Nodes are 256 bytes, boxes in SoA
//!   layout; triangles are copied in leaf order into 4-wide SoA packets (176 bytes per 4
//!   triangles) so traversal never reads the mesh; rectangles enter as their two triangles
//!   ([`crate::shape::Shape::triangle`]); curved shapes (spheres, disks, cylinders) are a
//!   second leaf kind tested through [`crate::shape::Shape::intersect_prim`].
//! - Triangles (`triangle.rs`): the watertight test of Woop, Benthin & Wald (2013).
//! - Traversal (`traverse.rs`): ordered closest hit and first-hit occlusion with a fixed stack,
//!   robust box tests (Ize 2013), kernels (`simd.rs`) chosen once at build time by runtime CPU
//!   feature detection: AVX2 on x86-64, a portable scalar set elsewhere. Both give
//!   bit-identical results.

mod kernel;
mod sah_build;
mod simd;
mod traverse;
mod wide;

pub use wide::{Accel, AccelStats, Isa};

#[cfg(test)]
mod tests;
