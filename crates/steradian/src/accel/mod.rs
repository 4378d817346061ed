//! Ray-tracing acceleration: an 8-wide bounding volume hierarchy over the primitives of all
//! shapes, traversed with SIMD node and triangle tests.
//!
//! - Build: binned SAH (32 bins) over primitive boxes (`sah_build.rs`), taken top-down straight
//!   into 8-wide nodes (`wide_build.rs`), subtrees and large binning passes in parallel with
//!   rayon; the SAH counts triangles in packets of 4. Leaves hold up to 8 primitives, all
//!   triangles or all analytic shapes.
//! - Layout (`layout.rs`): an 8-wide BVH (on AVX2 one 256-bit test covers all children of a
//!   node). Nodes are 256 bytes, boxes in SoA layout; triangles are
//!   copied in leaf order into 4-wide SoA packets of 144 bytes, with the shape and primitive
//!   ids of their lanes in a parallel array (32 bytes per packet), so traversal never reads the
//!   mesh (sizes asserted in `wide.rs`). Rectangles enter as their two triangles
//!   ([`crate::shape::Shape::triangle`]); curved shapes (spheres, disks, cylinders) are a
//!   second leaf kind tested through [`crate::shape::Shape::intersect_prim`].
//! - Instances (`instance.rs`): a shape group has its own BVH; each instance of it is one
//!   primitive of the scene's BVH (a third use of the analytic leaves), traced by taking the
//!   ray into the group's space.
//! - Triangles (`triangle.rs`): the watertight test of Woop, Benthin & Wald (2013).
//! - Traversal (`traverse.rs`): ordered closest hit and first-hit occlusion with a fixed stack,
//!   robust box tests (Ize 2013), kernels (`simd.rs`) chosen once at build time by runtime CPU
//!   feature detection: AVX2 on x86-64, a portable scalar set elsewhere. Both give
//!   bit-identical results.
//!
//! The decisions behind this layout, with their measurements, are in
//! `docs/design/2026-12-01-bvh-layout.md`; the comparison with Embree 3
//! (`benches/embree/run.sh`) in `benches/README.md`.

mod instance;
mod kernel;
mod layout;
mod sah_build;
mod simd;
mod traverse;
mod wide;
mod wide_build;

pub use instance::{Instance, ShapeGroup};
pub use wide::{Accel, AccelStats, Isa};

#[cfg(test)]
mod tests;
