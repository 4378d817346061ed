//! Node and triangle-packet kernels: a portable scalar set and an x86-64 AVX2 set.
//!
//! Both compute the same thing with the same floating-point operations in the same order (no
//! FMA), so they return bit-identical distances and barycentrics; `tests.rs` checks both against
//! brute force. The AVX2 node test handles the 8 boxes of a [`Node8`] in one 256-bit register
//! per plane; the triangle test handles the 4 triangles of a [`Tri4`] in 128-bit registers.

use super::traverse::{Kernel, LaneHit, TravRay};
use super::triangle::{edge_functions_f64, watertight_core};
use super::wide::{Node8, Tri4, WIDTH};

/// Portable kernels (the compiler may still vectorise the lane loops).
#[derive(Debug)]
pub(super) struct Scalar;

// SAFETY: the scalar kernels need no CPU feature.
unsafe impl Kernel for Scalar {
    type Ray = TravRay;

    #[inline(always)]
    unsafe fn prepare(r: &TravRay) -> TravRay {
        *r
    }

    #[inline(always)]
    unsafe fn node(n: &Node8, r: &TravRay, t_max: f32, dist: &mut [f32; WIDTH]) -> u32 {
        let mut mask = 0;
        for (lane, d) in dist.iter_mut().enumerate() {
            let mut t_near = r.t_min;
            let mut t_far = t_max;
            for a in 0..3 {
                // f32::max/min ignore NaN (0·∞ when the origin lies on the slab of a parallel ray)
                t_near = ((n.bounds[r.near[a]][lane] - r.o[a]) * r.inv_d[a]).max(t_near);
                t_far = ((n.bounds[r.far[a]][lane] - r.o[a]) * r.inv_far[a]).min(t_far);
            }
            *d = t_near;
            mask |= ((t_near <= t_far) as u32) << lane;
        }
        mask
    }

    #[inline(always)]
    unsafe fn tri4(p: &Tri4, r: &TravRay, mut t_max: f32) -> Option<LaneHit> {
        let mut best = None;
        for lane in 0..4 {
            if let Some((t, b1, b2)) = scalar_lane(p, r, lane, t_max) {
                t_max = t;
                best = Some((lane, t, b1, b2));
            }
        }
        best
    }

    #[inline(always)]
    unsafe fn tri4_any(p: &Tri4, r: &TravRay, t_max: f32) -> bool {
        (0..4).any(|lane| scalar_lane(p, r, lane, t_max).is_some())
    }
}

#[inline(always)]
fn scalar_lane(p: &Tri4, r: &TravRay, lane: usize, t_max: f32) -> Option<(f32, f32, f32)> {
    let k = r.wt.k;
    let rel = |v: usize| [0, 1, 2].map(|i| p.v[v][k[i]][lane] - r.o_k[i]);
    watertight_core(rel(0), rel(1), rel(2), r.wt.s, r.t_min, t_max)
}

#[cfg(target_arch = "x86_64")]
pub(super) use avx2::Avx2;

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64::*;

    use super::*;

    /// AVX2 kernels.
    #[derive(Debug)]
    pub(in crate::accel) struct Avx2;

    /// A ray with its constants broadcast to all lanes.
    #[derive(Clone, Copy, Debug)]
    pub(in crate::accel) struct Avx2Ray {
        o: [__m256; 3],
        inv_d: [__m256; 3],
        inv_far: [__m256; 3],
        t_min: __m256,
        near: [usize; 3],
        far: [usize; 3],
        // triangle test (4 lanes)
        k: [usize; 3],
        o_k: [__m128; 3],
        s: [__m128; 3],
        t_min4: __m128,
    }

    /// Loads 4 lanes.
    #[inline(always)]
    fn load4(v: &[f32; 4]) -> __m128 {
        // SAFETY: `v` is 4 readable f32; SSE is part of the x86-64 baseline.
        unsafe { _mm_loadu_ps(v.as_ptr()) }
    }

    #[inline(always)]
    fn store4(v: __m128) -> [f32; 4] {
        let mut out = [0.0f32; 4];
        // SAFETY: `out` is 4 writable f32; SSE is part of the x86-64 baseline.
        unsafe { _mm_storeu_ps(out.as_mut_ptr(), v) };
        out
    }

    /// Watertight test of the 4 triangles (see `triangle.rs`; same operations, same order):
    /// the valid-lane mask, distances and barycentrics (b1, b2).
    #[inline(always)]
    fn tri4_lanes(p: &Tri4, r: &Avx2Ray, t_max: f32) -> (i32, __m128, __m128, __m128) {
        let [kx, ky, kz] = r.k;
        let [sx, sy, sz] = r.s;
        // SAFETY (all intrinsics below): SSE/SSE2 are part of the x86-64 baseline.
        unsafe {
            let rel = |v: usize| {
                (
                    _mm_sub_ps(load4(&p.v[v][kx]), r.o_k[0]),
                    _mm_sub_ps(load4(&p.v[v][ky]), r.o_k[1]),
                    _mm_sub_ps(load4(&p.v[v][kz]), r.o_k[2]),
                )
            };
            let (ax, ay, az) = rel(0);
            let (bx, by, bz) = rel(1);
            let (cx, cy, cz) = rel(2);
            let (ax, ay) = (_mm_sub_ps(ax, _mm_mul_ps(sx, az)), _mm_sub_ps(ay, _mm_mul_ps(sy, az)));
            let (bx, by) = (_mm_sub_ps(bx, _mm_mul_ps(sx, bz)), _mm_sub_ps(by, _mm_mul_ps(sy, bz)));
            let (cx, cy) = (_mm_sub_ps(cx, _mm_mul_ps(sx, cz)), _mm_sub_ps(cy, _mm_mul_ps(sy, cz)));
            let mut u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
            let mut v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
            let mut w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
            let zero = _mm_setzero_ps();
            let on_edge = _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero));
            let mut edge_lanes = _mm_movemask_ps(on_edge);
            if edge_lanes != 0 {
                // rare: redo the edge functions of those lanes in f64, as the scalar test does
                let (mut uu, mut vv, mut ww) = (store4(u), store4(v), store4(w));
                let q = [ax, ay, bx, by, cx, cy].map(store4);
                while edge_lanes != 0 {
                    let l = edge_lanes.trailing_zeros() as usize;
                    edge_lanes &= edge_lanes - 1;
                    (uu[l], vv[l], ww[l]) = edge_functions_f64(q.map(|c| c[l]));
                }
                (u, v, w) = (load4(&uu), load4(&vv), load4(&ww));
            }
            let neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
            let pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
            let det = _mm_add_ps(_mm_add_ps(u, v), w);
            let (az, bz, cz) = (_mm_mul_ps(sz, az), _mm_mul_ps(sz, bz), _mm_mul_ps(sz, cz));
            let t_scaled = _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, az), _mm_mul_ps(v, bz)), _mm_mul_ps(w, cz));
            let rcp = _mm_div_ps(_mm_set1_ps(1.0), det);
            let t = _mm_mul_ps(t_scaled, rcp);
            // ordered comparisons: NaN (padding lanes, degenerate triangles) fails them
            let in_range = _mm_and_ps(_mm_cmpgt_ps(t, r.t_min4), _mm_cmplt_ps(t, _mm_set1_ps(t_max)));
            let valid = _mm_andnot_ps(_mm_and_ps(neg, pos), _mm_and_ps(_mm_cmpneq_ps(det, zero), in_range));
            (_mm_movemask_ps(valid), t, _mm_mul_ps(v, rcp), _mm_mul_ps(w, rcp))
        }
    }

    // SAFETY: every method is only called when the CPU has AVX2 (the trait's contract). They
    // are `inline(always)` without `target_feature` of their own: they are inlined into the
    // `#[target_feature(enable = "avx2")]` traversal functions (`traverse.rs`), where the
    // intrinsics inline too (a `target_feature` method would stay an out-of-line call).
    unsafe impl Kernel for Avx2 {
        type Ray = Avx2Ray;

        #[inline(always)]
        unsafe fn prepare(r: &TravRay) -> Avx2Ray {
            // SAFETY: AVX is available (the trait's contract).
            unsafe { Avx2Ray {
                o: [_mm256_set1_ps(r.o[0]), _mm256_set1_ps(r.o[1]), _mm256_set1_ps(r.o[2])],
                inv_d: [_mm256_set1_ps(r.inv_d[0]), _mm256_set1_ps(r.inv_d[1]), _mm256_set1_ps(r.inv_d[2])],
                inv_far: [_mm256_set1_ps(r.inv_far[0]), _mm256_set1_ps(r.inv_far[1]), _mm256_set1_ps(r.inv_far[2])],
                t_min: _mm256_set1_ps(r.t_min),
                near: r.near,
                far: r.far,
                k: r.wt.k,
                o_k: r.o_k.map(|x| _mm_set1_ps(x)),
                s: r.wt.s.map(|x| _mm_set1_ps(x)),
                t_min4: _mm_set1_ps(r.t_min),
            } }
        }

        #[inline(always)]
        unsafe fn node(n: &Node8, r: &Avx2Ray, t_max: f32, dist: &mut [f32; WIDTH]) -> u32 {
            // SAFETY: each plane row is 8 f32 at a 32-byte aligned offset of a 64-byte aligned
            // node, so the aligned loads are in bounds and aligned; `dist` holds 8 f32.
            unsafe {
                let b = &n.bounds;
                macro_rules! slab {
                    ($plane:expr, $a:expr, $inv:expr) => {
                        _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(b[$plane].as_ptr()), r.o[$a]), $inv)
                    };
                }
                let (nx, ny, nz) = (slab!(r.near[0], 0, r.inv_d[0]), slab!(r.near[1], 1, r.inv_d[1]), slab!(r.near[2], 2, r.inv_d[2]));
                let (fx, fy, fz) = (slab!(r.far[0], 0, r.inv_far[0]), slab!(r.far[1], 1, r.inv_far[1]), slab!(r.far[2], 2, r.inv_far[2]));
                // max/min return the second operand when one is NaN: the accumulator goes second
                let t_near = _mm256_max_ps(nx, _mm256_max_ps(ny, _mm256_max_ps(nz, r.t_min)));
                let t_far = _mm256_min_ps(fx, _mm256_min_ps(fy, _mm256_min_ps(fz, _mm256_set1_ps(t_max))));
                _mm256_storeu_ps(dist.as_mut_ptr(), t_near);
                _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(t_near, t_far)) as u32
            }
        }

        #[inline(always)]
        unsafe fn tri4(p: &Tri4, r: &Avx2Ray, t_max: f32) -> Option<LaneHit> {
            let (mut mask, t, b1, b2) = tri4_lanes(p, r, t_max);
            if mask == 0 {
                return None;
            }
            let t = store4(t);
            let mut best = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            while mask != 0 {
                let l = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if t[l] < t[best] {
                    best = l;
                }
            }
            Some((best, t[best], store4(b1)[best], store4(b2)[best]))
        }

        #[inline(always)]
        unsafe fn tri4_any(p: &Tri4, r: &Avx2Ray, t_max: f32) -> bool {
            tri4_lanes(p, r, t_max).0 != 0
        }
    }
}
