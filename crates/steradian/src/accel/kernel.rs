//! The interface between traversal (`traverse.rs`) and the instruction-set kernels
//! (`simd.rs`): the per-ray constants every kernel reads ([`TravRay`]) and the node and
//! triangle-packet tests a kernel provides ([`Kernel`]).
//!
//! The box test is robust (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013): each slab's far
//! distance uses the reciprocal direction rounded up by `1 + 8ε` (ε = 2⁻²⁴), which bounds the
//! rounding of `(b − o)·(1/d)` so that a box the ray touches is never culled.

use super::layout::{Node8, Tri4, WIDTH};
use crate::geometry::triangle::WatertightRay;
use crate::geometry::Ray;

/// Rounds the far slab distances up (see the module docs): 1 + 8ε, exactly representable.
const FAR_SCALE: f32 = 1.0 + 8.0 * (f32::EPSILON / 2.0);

/// Everything a kernel needs to know about a ray, computed once per ray.
#[derive(Clone, Copy, Debug)]
pub(super) struct TravRay {
    pub o: [f32; 3],
    pub inv_d: [f32; 3],
    /// `inv_d` rounded up for the far planes.
    pub inv_far: [f32; 3],
    /// Plane index (into [`Node8::bounds`]) of the near and far slab of each axis.
    pub near: [usize; 3],
    pub far: [usize; 3],
    pub t_min: f32,
    pub wt: WatertightRay,
    /// The origin permuted to the watertight frame's axes.
    pub o_k: [f32; 3],
}

impl TravRay {
    #[inline(always)]
    pub fn new(ray: &Ray, t_min: f32) -> TravRay {
        let inv_d = ray.d.recip();
        // branch-free (see `WatertightRay::new`): the slab of each axis the ray enters first
        let near: [usize; 3] =
            std::array::from_fn(|a| a + 3 * inv_d[a].is_sign_negative() as usize);
        let wt = WatertightRay::new(ray.d);
        TravRay {
            o: ray.o.to_array(),
            inv_d: inv_d.to_array(),
            inv_far: (inv_d * FAR_SCALE).to_array(),
            near,
            far: std::array::from_fn(|a| near[a] ^ (a ^ (a + 3))),
            t_min,
            wt,
            o_k: wt.k.map(|k| ray.o[k]),
        }
    }
}

/// A triangle-packet hit: lane, distance, barycentrics (b1, b2).
pub(super) type LaneHit = (usize, f32, f32, f32);

/// The node and triangle tests of one instruction set.
///
/// # Safety
/// Implementations may require CPU features: callers must only use a kernel whose
/// instruction set ([`Isa`]) the running CPU supports.
pub(super) unsafe trait Kernel {
    type Ray: Copy;
    /// # Safety
    /// The CPU supports the kernel's instruction set.
    unsafe fn prepare(r: &TravRay) -> Self::Ray;
    /// Mask of the children whose box the ray enters within `(t_min, t_max)`, and (in `dist`)
    /// their entry distances.
    ///
    /// # Safety
    /// The CPU supports the kernel's instruction set.
    unsafe fn node(n: &Node8, r: &Self::Ray, t_max: f32, dist: &mut [f32; WIDTH]) -> u32;
    /// The closest of the 4 triangles of `p` hit with `t_min < t < t_max`; ties go to the
    /// lowest lane.
    ///
    /// # Safety
    /// The CPU supports the kernel's instruction set.
    unsafe fn tri4(p: &Tri4, r: &Self::Ray, t_max: f32) -> Option<LaneHit>;
    /// Whether any of the 4 triangles of `p` is hit with `t_min < t < t_max`.
    ///
    /// # Safety
    /// The CPU supports the kernel's instruction set.
    unsafe fn tri4_any(p: &Tri4, r: &Self::Ray, t_max: f32) -> bool;
    /// The closest of the 8 triangles of packets `p` (lanes 0–3) and `q` (lanes 4–7) hit with
    /// `t_min < t < t_max`; ties go to the lowest lane.
    ///
    /// # Safety
    /// The CPU supports the kernel's instruction set.
    unsafe fn tri8(p: &Tri4, q: &Tri4, r: &Self::Ray, t_max: f32) -> Option<LaneHit>;
    /// Whether any of the 8 triangles of `p` and `q` is hit with `t_min < t < t_max`.
    ///
    /// # Safety
    /// The CPU supports the kernel's instruction set.
    unsafe fn tri8_any(p: &Tri4, q: &Tri4, r: &Self::Ray, t_max: f32) -> bool;
}
