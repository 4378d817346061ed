//! Node and triangle-packet kernels: a portable scalar set and an x86-64 AVX2 set.
//!
//! Both compute the same thing with the same floating-point operations in the same order (no
//! FMA), so they return bit-identical distances and barycentrics; `tests.rs` checks both against
//! brute force. The AVX2 node test handles the 8 boxes of a [`Node8`] in one 256-bit register
//! per plane; the triangle test handles two [`Tri4`] packets (8 triangles) in 256-bit
//! registers, so that a leaf of two packets, the common case in small scenes, is one test.

use super::kernel::{Kernel, LaneHit, TravRay};
use super::layout::{Node8, Tri4, WIDTH};
use crate::geometry::triangle::{edge_functions_f64, watertight_core};

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

    #[inline(always)]
    unsafe fn tri8(p: &Tri4, q: &Tri4, r: &TravRay, mut t_max: f32) -> Option<LaneHit> {
        let mut best = None;
        for lane in 0..8 {
            if let Some((t, b1, b2)) = scalar_lane(if lane < 4 { p } else { q }, r, lane % 4, t_max)
            {
                t_max = t;
                best = Some((lane, t, b1, b2));
            }
        }
        best
    }

    #[inline(always)]
    unsafe fn tri8_any(p: &Tri4, q: &Tri4, r: &TravRay, t_max: f32) -> bool {
        (0..8).any(|lane| scalar_lane(if lane < 4 { p } else { q }, r, lane % 4, t_max).is_some())
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
        // triangle test
        k: [usize; 3],
        o_k: [__m256; 3],
        s: [__m256; 3],
    }

    /// The vector operations of the triangle test, for 4 lanes (SSE) and 8 lanes (AVX), so that
    /// one body ([`tri_lanes`]) serves both widths. Every method needs AVX (VEX encoding),
    /// which the kernel's contract provides.
    trait Lanes: Copy {
        type Array: Copy + Default + AsRef<[f32]> + AsMut<[f32]>;
        fn splat(x: f32) -> Self;
        /// The lower lanes of a broadcast 8-lane register.
        fn from_broadcast(x: __m256) -> Self;
        fn load(a: &Self::Array) -> Self;
        fn store(self) -> Self::Array;
        fn add(self, o: Self) -> Self;
        fn sub(self, o: Self) -> Self;
        fn mul(self, o: Self) -> Self;
        fn div(self, o: Self) -> Self;
        fn or(self, o: Self) -> Self;
        fn and(self, o: Self) -> Self;
        /// `!self & o`.
        fn andnot(self, o: Self) -> Self;
        /// Ordered comparisons (false with NaN) ...
        fn eq(self, o: Self) -> Self;
        fn lt(self, o: Self) -> Self;
        fn gt(self, o: Self) -> Self;
        /// ... and the unordered `!=` (true with NaN).
        fn neq(self, o: Self) -> Self;
        fn movemask(self) -> i32;
    }

    macro_rules! lanes {
        ($t:ty, $n:expr, $set1:ident, $from:expr, $loadu:ident, $storeu:ident, $add:ident, $sub:ident, $mul:ident, $div:ident, $or:ident, $and:ident, $andnot:ident, $cmp:ident, $movemask:ident) => {
            // SAFETY (every method): AVX is available (the kernel's contract); loads and stores
            // touch exactly the array given.
            impl Lanes for $t {
                type Array = [f32; $n];
                #[inline(always)]
                fn splat(x: f32) -> Self {
                    unsafe { $set1(x) }
                }
                #[inline(always)]
                fn from_broadcast(x: __m256) -> Self {
                    unsafe { $from(x) }
                }
                #[inline(always)]
                fn load(a: &[f32; $n]) -> Self {
                    unsafe { $loadu(a.as_ptr()) }
                }
                #[inline(always)]
                fn store(self) -> [f32; $n] {
                    let mut out = [0.0f32; $n];
                    unsafe { $storeu(out.as_mut_ptr(), self) };
                    out
                }
                #[inline(always)]
                fn add(self, o: Self) -> Self {
                    unsafe { $add(self, o) }
                }
                #[inline(always)]
                fn sub(self, o: Self) -> Self {
                    unsafe { $sub(self, o) }
                }
                #[inline(always)]
                fn mul(self, o: Self) -> Self {
                    unsafe { $mul(self, o) }
                }
                #[inline(always)]
                fn div(self, o: Self) -> Self {
                    unsafe { $div(self, o) }
                }
                #[inline(always)]
                fn or(self, o: Self) -> Self {
                    unsafe { $or(self, o) }
                }
                #[inline(always)]
                fn and(self, o: Self) -> Self {
                    unsafe { $and(self, o) }
                }
                #[inline(always)]
                fn andnot(self, o: Self) -> Self {
                    unsafe { $andnot(self, o) }
                }
                #[inline(always)]
                fn eq(self, o: Self) -> Self {
                    unsafe { $cmp::<_CMP_EQ_OQ>(self, o) }
                }
                #[inline(always)]
                fn lt(self, o: Self) -> Self {
                    unsafe { $cmp::<_CMP_LT_OQ>(self, o) }
                }
                #[inline(always)]
                fn gt(self, o: Self) -> Self {
                    unsafe { $cmp::<_CMP_GT_OQ>(self, o) }
                }
                #[inline(always)]
                fn neq(self, o: Self) -> Self {
                    unsafe { $cmp::<_CMP_NEQ_UQ>(self, o) }
                }
                #[inline(always)]
                fn movemask(self) -> i32 {
                    unsafe { $movemask(self) }
                }
            }
        };
    }

    /// The identity, in the shape of `_mm256_castps256_ps128`.
    #[inline(always)]
    unsafe fn unchanged(x: __m256) -> __m256 {
        x
    }

    lanes!(
        __m128,
        4,
        _mm_set1_ps,
        _mm256_castps256_ps128,
        _mm_loadu_ps,
        _mm_storeu_ps,
        _mm_add_ps,
        _mm_sub_ps,
        _mm_mul_ps,
        _mm_div_ps,
        _mm_or_ps,
        _mm_and_ps,
        _mm_andnot_ps,
        _mm_cmp_ps,
        _mm_movemask_ps
    );
    lanes!(
        __m256,
        8,
        _mm256_set1_ps,
        unchanged,
        _mm256_loadu_ps,
        _mm256_storeu_ps,
        _mm256_add_ps,
        _mm256_sub_ps,
        _mm256_mul_ps,
        _mm256_div_ps,
        _mm256_or_ps,
        _mm256_and_ps,
        _mm256_andnot_ps,
        _mm256_cmp_ps,
        _mm256_movemask_ps
    );

    /// Watertight test of 4 or 8 triangles (see `triangle.rs`; same operations, same order):
    /// the valid-lane mask, distances and barycentrics (b1, b2). `vertex(v, axis)` loads
    /// coordinate `axis` of vertex `v` of every lane.
    #[inline(always)]
    fn tri_lanes<V: Lanes>(
        vertex: impl Fn(usize, usize) -> V,
        r: &Avx2Ray,
        t_max: f32,
    ) -> (i32, V, V, V) {
        let [kx, ky, kz] = r.k;
        let [o_x, o_y, o_z] = r.o_k.map(V::from_broadcast);
        let [sx, sy, sz] = r.s.map(V::from_broadcast);
        let rel =
            |v: usize| (vertex(v, kx).sub(o_x), vertex(v, ky).sub(o_y), vertex(v, kz).sub(o_z));
        let (ax, ay, az) = rel(0);
        let (bx, by, bz) = rel(1);
        let (cx, cy, cz) = rel(2);
        let (ax, ay) = (ax.sub(sx.mul(az)), ay.sub(sy.mul(az)));
        let (bx, by) = (bx.sub(sx.mul(bz)), by.sub(sy.mul(bz)));
        let (cx, cy) = (cx.sub(sx.mul(cz)), cy.sub(sy.mul(cz)));
        let mut u = cx.mul(by).sub(cy.mul(bx));
        let mut v = ax.mul(cy).sub(ay.mul(cx));
        let mut w = bx.mul(ay).sub(by.mul(ax));
        let zero = V::splat(0.0);
        let mut edge_lanes = u.eq(zero).or(v.eq(zero)).or(w.eq(zero)).movemask();
        if edge_lanes != 0 {
            // rare: redo the edge functions of those lanes in f64, as the scalar test does
            let (mut uu, mut vv, mut ww) = (u.store(), v.store(), w.store());
            let e = [ax, ay, bx, by, cx, cy].map(V::store);
            while edge_lanes != 0 {
                let l = edge_lanes.trailing_zeros() as usize;
                edge_lanes &= edge_lanes - 1;
                (uu.as_mut()[l], vv.as_mut()[l], ww.as_mut()[l]) =
                    edge_functions_f64(e.map(|c| c.as_ref()[l]));
            }
            (u, v, w) = (V::load(&uu), V::load(&vv), V::load(&ww));
        }
        let neg = u.lt(zero).or(v.lt(zero)).or(w.lt(zero));
        let pos = u.gt(zero).or(v.gt(zero)).or(w.gt(zero));
        let det = u.add(v).add(w);
        let (az, bz, cz) = (sz.mul(az), sz.mul(bz), sz.mul(cz));
        let t_scaled = u.mul(az).add(v.mul(bz)).add(w.mul(cz));
        let rcp = V::splat(1.0).div(det);
        let t = t_scaled.mul(rcp);
        // ordered comparisons: NaN (padding lanes, degenerate triangles) fails them
        let in_range = t.gt(V::from_broadcast(r.t_min)).and(t.lt(V::splat(t_max)));
        let valid = neg.and(pos).andnot(det.neq(zero).and(in_range));
        (valid.movemask(), t, v.mul(rcp), w.mul(rcp))
    }

    /// The closest valid lane of a [`tri_lanes`] result; ties go to the lowest lane.
    #[inline(always)]
    fn closest_lane<V: Lanes>((mut mask, t, b1, b2): (i32, V, V, V)) -> Option<LaneHit> {
        if mask == 0 {
            return None;
        }
        let t = t.store();
        let t = t.as_ref();
        let mut best = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        while mask != 0 {
            let l = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            if t[l] < t[best] {
                best = l;
            }
        }
        Some((best, t[best], b1.store().as_ref()[best], b2.store().as_ref()[best]))
    }

    /// Lanes 0–3 from `lo`, 4–7 from `hi`.
    #[inline(always)]
    fn load4x2(lo: &[f32; 4], hi: &[f32; 4]) -> __m256 {
        // SAFETY: both are 4 readable f32; AVX is available (the kernel's contract).
        unsafe {
            _mm256_insertf128_ps::<1>(
                _mm256_castps128_ps256(_mm_loadu_ps(lo.as_ptr())),
                _mm_loadu_ps(hi.as_ptr()),
            )
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
            unsafe {
                Avx2Ray {
                    o: [_mm256_set1_ps(r.o[0]), _mm256_set1_ps(r.o[1]), _mm256_set1_ps(r.o[2])],
                    inv_d: [
                        _mm256_set1_ps(r.inv_d[0]),
                        _mm256_set1_ps(r.inv_d[1]),
                        _mm256_set1_ps(r.inv_d[2]),
                    ],
                    inv_far: [
                        _mm256_set1_ps(r.inv_far[0]),
                        _mm256_set1_ps(r.inv_far[1]),
                        _mm256_set1_ps(r.inv_far[2]),
                    ],
                    t_min: _mm256_set1_ps(r.t_min),
                    near: r.near,
                    far: r.far,
                    k: r.wt.k,
                    o_k: r.o_k.map(|x| _mm256_set1_ps(x)),
                    s: r.wt.s.map(|x| _mm256_set1_ps(x)),
                }
            }
        }

        #[inline(always)]
        unsafe fn node(n: &Node8, r: &Avx2Ray, t_max: f32, dist: &mut [f32; WIDTH]) -> u32 {
            // SAFETY: each plane row is 8 f32 at a 32-byte aligned offset of a 64-byte aligned
            // node, so the aligned loads are in bounds and aligned; `dist` holds 8 f32.
            unsafe {
                let b = &n.bounds;
                macro_rules! slab {
                    ($plane:expr, $a:expr, $inv:expr) => {
                        _mm256_mul_ps(
                            _mm256_sub_ps(_mm256_load_ps(b[$plane].as_ptr()), r.o[$a]),
                            $inv,
                        )
                    };
                }
                let (nx, ny, nz) = (
                    slab!(r.near[0], 0, r.inv_d[0]),
                    slab!(r.near[1], 1, r.inv_d[1]),
                    slab!(r.near[2], 2, r.inv_d[2]),
                );
                let (fx, fy, fz) = (
                    slab!(r.far[0], 0, r.inv_far[0]),
                    slab!(r.far[1], 1, r.inv_far[1]),
                    slab!(r.far[2], 2, r.inv_far[2]),
                );
                // max/min return the second operand when one is NaN: the accumulator goes second
                let t_near = _mm256_max_ps(nx, _mm256_max_ps(ny, _mm256_max_ps(nz, r.t_min)));
                let t_far =
                    _mm256_min_ps(fx, _mm256_min_ps(fy, _mm256_min_ps(fz, _mm256_set1_ps(t_max))));
                _mm256_storeu_ps(dist.as_mut_ptr(), t_near);
                _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(t_near, t_far)) as u32
            }
        }

        #[inline(always)]
        unsafe fn tri4(p: &Tri4, r: &Avx2Ray, t_max: f32) -> Option<LaneHit> {
            closest_lane(tri_lanes(|v, a| __m128::load(&p.v[v][a]), r, t_max))
        }

        #[inline(always)]
        unsafe fn tri4_any(p: &Tri4, r: &Avx2Ray, t_max: f32) -> bool {
            tri_lanes(|v, a| __m128::load(&p.v[v][a]), r, t_max).0 != 0
        }

        #[inline(always)]
        unsafe fn tri8(p: &Tri4, q: &Tri4, r: &Avx2Ray, t_max: f32) -> Option<LaneHit> {
            closest_lane(tri_lanes(|v, a| load4x2(&p.v[v][a], &q.v[v][a]), r, t_max))
        }

        #[inline(always)]
        unsafe fn tri8_any(p: &Tri4, q: &Tri4, r: &Avx2Ray, t_max: f32) -> bool {
            tri_lanes(|v, a| load4x2(&p.v[v][a], &q.v[v][a]), r, t_max).0 != 0
        }
    }
}
