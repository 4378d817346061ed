//! Binned SAH splitting of primitive ranges (Wald, "On fast Construction of SAH-based Bounding
//! Volume Hierarchies", 2007): the decision the builder (`wide_build.rs`) takes at every range,
//! whether it becomes a leaf or two halves, and where the halves meet.
//!
//! The SAH cost counts triangles in packets of [`TRI_BLOCK`] (a leaf of 5 triangles costs as
//! much as one of 8, they are stored 4 to a packet), as Embree does. Traversal tests a leaf's
//! packets in pairs, 8 lanes at a time (`simd.rs`), but costing leaves by pairs (blocks of 8)
//! did not change render times on the reference scenes (cornell +0.5 %, materials −3.2 %,
//! veach +0.1 %, within noise; 2026-12-02, AMD EPYC, 2 cores), so the cost stays that of
//! 4-triangle packets.
//!
//! What makes it fast on large inputs (a 20-million-triangle mesh): a primitive is 32 bytes
//! (its box, with the shape and primitive indices in the boxes' spare lanes); centroids are
//! box centres kept doubled (`lower + upper`, no multiply); the bins are SIMD boxes; the
//! partition swaps from both ends and accumulates the two halves' boxes and centroid boxes as
//! it goes, so no range is scanned again for its extent; large ranges bin in parallel.

use glam::{Vec3, Vec3A};
use rayon::prelude::*;

use crate::geometry::{is_positive, Aabb};

/// Most SAH bins per axis; a range of n primitives gets min(8 + n/8, 32). Resetting and
/// sweeping 32 bins for each of millions of small ranges was most of a large build (a
/// 20-million-triangle sphere: 7.8 s with 32 bins everywhere, 5.5 s with Embree's
/// min(4 + n/20, 32)); but with 4 bins small ranges miss the splits at multiples of 4
/// triangles that the packet-counting SAH wants, and the bunny's BVH grew 7 % (57.8 → 62.0
/// bytes per triangle; 59.4 with this rule, sphere1m 56.4 → 56.8; 2026-12-06, Intel Xeon).
const BINS: usize = 32;

/// Bins for a range of `count` primitives.
fn bin_count(count: usize) -> usize {
    (8 + count / 8).min(BINS)
}
/// Largest leaf, in primitives.
pub(super) const MAX_LEAF: usize = 8;
/// Triangles are stored 4 to a packet.
pub(super) const TRI_BLOCK: usize = 4;
/// Cost of one node visit relative to one triangle-packet test.
const TRAVERSAL_COST: f32 = 1.0;
/// Beyond this depth ranges are split at the object median: the depth stays bounded (and with
/// it the traversal stack) whatever the input.
pub(super) const SAH_MAX_DEPTH: usize = 40;
/// Ranges with more primitives than this bin in parallel.
const PARALLEL_BINNING_MIN: usize = 65536;

/// Marks an analytic primitive (not a triangle) in [`BuildPrim`]'s primitive word.
const ANALYTIC_PRIM: u32 = 1 << 31;

/// A primitive as the builder sees it: its box, and who it is (32 bytes, so that a partition
/// moves half the bytes of a box-centroid-ids layout).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub(super) struct BuildPrim {
    lower: [f32; 3],
    shape: u32,
    upper: [f32; 3],
    /// Primitive index, with [`ANALYTIC_PRIM`] set for analytic primitives.
    prim: u32,
}

const _: () = assert!(std::mem::size_of::<BuildPrim>() == 32);

impl BuildPrim {
    /// A primitive; `triangle` tells whether it is stored in a triangle packet.
    pub fn new(bounds: &Aabb, shape: u32, prim: u32, triangle: bool) -> BuildPrim {
        debug_assert!(prim & ANALYTIC_PRIM == 0);
        BuildPrim {
            lower: bounds.min.to_array(),
            shape,
            upper: bounds.max.to_array(),
            prim: prim | if triangle { 0 } else { ANALYTIC_PRIM },
        }
    }

    pub fn shape(&self) -> u32 {
        self.shape
    }

    pub fn prim(&self) -> u32 {
        self.prim & !ANALYTIC_PRIM
    }

    pub fn is_triangle(&self) -> bool {
        self.prim & ANALYTIC_PRIM == 0
    }

    /// Whether the box is non-empty and finite (degenerate data is left out of the tree).
    pub fn is_valid(&self) -> bool {
        let (l, u) = (Vec3::from(self.lower), Vec3::from(self.upper));
        l.is_finite() && u.is_finite() && l.cmple(u).all()
    }

    #[inline(always)]
    fn lower(&self) -> Vec3A {
        Vec3A::from_array(self.lower)
    }

    #[inline(always)]
    fn upper(&self) -> Vec3A {
        Vec3A::from_array(self.upper)
    }

    /// Twice the box centre.
    #[inline(always)]
    fn centroid2(&self) -> Vec3A {
        self.lower() + self.upper()
    }
}

/// What the builder knows of a range without looking at it again: the union of its boxes, the
/// box of its (doubled) centroids, and how many of its primitives are analytic.
#[derive(Clone, Copy, Debug)]
pub(super) struct Extent {
    lower: Vec3A,
    upper: Vec3A,
    clower: Vec3A,
    cupper: Vec3A,
    other: usize,
}

impl Extent {
    const EMPTY: Extent = Extent {
        lower: Vec3A::INFINITY,
        upper: Vec3A::NEG_INFINITY,
        clower: Vec3A::INFINITY,
        cupper: Vec3A::NEG_INFINITY,
        other: 0,
    };

    #[inline(always)]
    fn grow(&mut self, p: &BuildPrim) {
        let (l, u) = (p.lower(), p.upper());
        let c = l + u;
        self.lower = self.lower.min(l);
        self.upper = self.upper.max(u);
        self.clower = self.clower.min(c);
        self.cupper = self.cupper.max(c);
        self.other += !p.is_triangle() as usize;
    }

    fn union(&self, o: &Extent) -> Extent {
        Extent {
            lower: self.lower.min(o.lower),
            upper: self.upper.max(o.upper),
            clower: self.clower.min(o.clower),
            cupper: self.cupper.max(o.cupper),
            other: self.other + o.other,
        }
    }

    /// The extent of `prims` (in parallel for large ranges).
    pub fn of(prims: &[BuildPrim]) -> Extent {
        let scan = |chunk: &[BuildPrim]| {
            let mut e = Extent::EMPTY;
            for p in chunk {
                e.grow(p);
            }
            e
        };
        if prims.len() >= PARALLEL_BINNING_MIN {
            prims
                .par_chunks(PARALLEL_BINNING_MIN / 4)
                .map(scan)
                .reduce(|| Extent::EMPTY, |a, b| a.union(&b))
        } else {
            scan(prims)
        }
    }

    /// The union of the range's boxes.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(Vec3::from(self.lower), Vec3::from(self.upper))
    }

    /// Whether a range of `count` primitives with this extent is all triangles or all
    /// analytic primitives.
    fn is_pure(&self, count: usize) -> bool {
        self.other == 0 || self.other == count
    }
}

/// SAH cost of a leaf of `n` primitives, all triangles or all analytic.
pub(super) fn leaf_cost(n: usize, triangles: bool) -> f32 {
    if triangles {
        n.div_ceil(TRI_BLOCK) as f32
    } else {
        n as f32
    }
}

/// Cost of `n` primitives of which `other` are not triangles.
fn block_cost(n: usize, other: usize) -> f32 {
    (n - other).div_ceil(TRI_BLOCK) as f32 + other as f32
}

/// The bins of one range: per axis, the box and the counts of the primitives whose centroid
/// falls in each bin.
#[derive(Clone, Copy)]
struct Bins {
    lower: [[Vec3A; BINS]; 3],
    upper: [[Vec3A; BINS]; 3],
    count: [[u32; BINS]; 3],
    other: [[u32; BINS]; 3],
}

impl Bins {
    fn empty() -> Bins {
        Bins {
            lower: [[Vec3A::INFINITY; BINS]; 3],
            upper: [[Vec3A::NEG_INFINITY; BINS]; 3],
            count: [[0; BINS]; 3],
            other: [[0; BINS]; 3],
        }
    }

    /// Empties the first `n` bins of each axis (the only ones a [`Binner`] of `n` bins uses).
    fn reset(&mut self, n: usize) {
        for axis in 0..3 {
            self.lower[axis][..n].fill(Vec3A::INFINITY);
            self.upper[axis][..n].fill(Vec3A::NEG_INFINITY);
            self.count[axis][..n].fill(0);
            self.other[axis][..n].fill(0);
        }
    }

    fn merge(mut self, b: &Bins) -> Bins {
        for axis in 0..3 {
            for i in 0..BINS {
                self.lower[axis][i] = self.lower[axis][i].min(b.lower[axis][i]);
                self.upper[axis][i] = self.upper[axis][i].max(b.upper[axis][i]);
                self.count[axis][i] += b.count[axis][i];
                self.other[axis][i] += b.other[axis][i];
            }
        }
        self
    }
}

/// Maps doubled centroids to bins.
#[derive(Clone, Copy)]
struct Binner {
    /// Bins per axis.
    n: usize,
    origin: Vec3A,
    /// Bins per unit of doubled centroid, 0 on axes where the centroids do not spread.
    scale: Vec3A,
    /// The last bin's index, n − 1.
    last: f32,
    /// Whether the range holds analytic primitives to count (its extent knows).
    analytic: bool,
}

impl Binner {
    fn new(e: &Extent, count: usize) -> Binner {
        let n = bin_count(count);
        let size = e.cupper - e.clower;
        let scale = Vec3A::from_array(std::array::from_fn(|a| {
            let s = n as f32 / size[a];
            if is_positive(size[a]) && s.is_finite() {
                s
            } else {
                0.0
            }
        }));
        Binner { n, origin: e.clower, scale, last: (n - 1) as f32, analytic: e.other > 0 }
    }

    /// The bin of `p` on each axis.
    #[inline(always)]
    fn bins(&self, p: &BuildPrim) -> [usize; 3] {
        let f = ((p.centroid2() - self.origin) * self.scale)
            .clamp(Vec3A::ZERO, Vec3A::splat(self.last));
        // SAFETY: `f` is finite and in [0, n − 1] (centroids and scales are finite, the clamp
        // bounds it), where truncation to an integer is defined; Rust's saturating `as` costs
        // two compares per axis here, the binning's hottest loop.
        f.to_array().map(|x| unsafe { x.to_int_unchecked::<u32>() } as usize)
    }

    /// The bin of `p` on `axis` (the same arithmetic as [`Binner::bins`]).
    #[inline(always)]
    fn bin_on(&self, axis: usize, p: &BuildPrim) -> usize {
        let c = p.lower[axis] + p.upper[axis];
        let f = ((c - self.origin[axis]) * self.scale[axis]).clamp(0.0, self.last);
        // SAFETY: as in `bins`
        unsafe { f.to_int_unchecked::<u32>() as usize }
    }

    /// The bins of `prims` in fresh bins.
    fn bin(&self, prims: &[BuildPrim]) -> Bins {
        let mut bins = [Bins::empty(), Bins::empty()];
        self.bin_into(prims, &mut bins);
        bins[0]
    }

    /// Adds `prims` to `bins[0]`, using `bins[1]` (also reset) as scratch: even and odd
    /// primitives go to separate bins, merged at the end. Neighbouring primitives of a mesh
    /// usually fall in the same bins, and one set of bins makes each update wait for the
    /// previous one's store (the binning took 28 % of a large build so).
    fn bin_into(&self, prims: &[BuildPrim], bins: &mut [Bins; 2]) {
        if self.analytic {
            self.bin_pairs::<true>(prims, bins);
        } else {
            self.bin_pairs::<false>(prims, bins);
        }
        let [a, b] = bins;
        for axis in 0..3 {
            for i in 0..self.n {
                a.lower[axis][i] = a.lower[axis][i].min(b.lower[axis][i]);
                a.upper[axis][i] = a.upper[axis][i].max(b.upper[axis][i]);
                a.count[axis][i] += b.count[axis][i];
                a.other[axis][i] += b.other[axis][i];
            }
        }
    }

    /// [`Binner::bin_into`] before the merge; `ANALYTIC`: whether to count analytic
    /// primitives (a range of triangles has none to count).
    #[inline(always)]
    fn bin_pairs<const ANALYTIC: bool>(&self, prims: &[BuildPrim], bins: &mut [Bins; 2]) {
        let add = |bins: &mut Bins, p: &BuildPrim| {
            let b = self.bins(p);
            let (l, u) = (p.lower(), p.upper());
            for (axis, &i) in b.iter().enumerate() {
                bins.lower[axis][i] = bins.lower[axis][i].min(l);
                bins.upper[axis][i] = bins.upper[axis][i].max(u);
                bins.count[axis][i] += 1;
                if ANALYTIC {
                    bins.other[axis][i] += !p.is_triangle() as u32;
                }
            }
        };
        let [even, odd] = bins;
        let mut pairs = prims.chunks_exact(2);
        for pair in &mut pairs {
            add(even, &pair[0]);
            add(odd, &pair[1]);
        }
        for p in pairs.remainder() {
            add(even, p);
        }
    }
}

thread_local! {
    /// Each thread's bins for the ranges it bins alone (reset, not re-made, for each range).
    static SCRATCH_BINS: std::cell::RefCell<Box<[Bins; 2]>> =
        std::cell::RefCell::new(Box::new([Bins::empty(), Bins::empty()]));
}

fn surface_area(lower: Vec3A, upper: Vec3A) -> f32 {
    let d = (upper - lower).max(Vec3A::ZERO);
    2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
}

/// When [`sah_split`] may answer that a leaf is cheaper.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum SplitPolicy {
    /// The SAH's choice: `None` where a leaf costs less than the best split.
    LeafIfCheaper,
    /// The best split whatever it costs (`None` only where no bin boundary separates the
    /// centroids): the refinement of a leaf.
    Always,
}

/// Two halves of a range: `prims[..mid]` and `prims[mid..]`, with their extents.
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    pub mid: usize,
    pub left: Extent,
    pub right: Extent,
}

/// The cheapest split of the binned primitives: (cost, axis, last bin on the left).
fn best_split(bins: &Bins, binner: &Binner, count: usize) -> Option<(f32, usize, usize)> {
    let n_bins = binner.n;
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        if binner.scale[axis] == 0.0 {
            continue;
        }
        // sweep from the right for suffix areas and costs
        let mut right_cost = [0.0f32; BINS];
        let (mut lo, mut hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        let (mut n, mut o) = (0usize, 0usize);
        for i in (1..n_bins).rev() {
            lo = lo.min(bins.lower[axis][i]);
            hi = hi.max(bins.upper[axis][i]);
            n += bins.count[axis][i] as usize;
            o += bins.other[axis][i] as usize;
            right_cost[i] = if n > 0 { surface_area(lo, hi) * block_cost(n, o) } else { f32::NAN };
        }
        let (mut lo, mut hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        let (mut n, mut o) = (0usize, 0usize);
        for i in 0..n_bins - 1 {
            lo = lo.min(bins.lower[axis][i]);
            hi = hi.max(bins.upper[axis][i]);
            n += bins.count[axis][i] as usize;
            o += bins.other[axis][i] as usize;
            if n == 0 || n == count {
                continue;
            }
            let cost = surface_area(lo, hi) * block_cost(n, o) + right_cost[i + 1];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, i));
            }
        }
    }
    best
}

/// Binned SAH: partitions `prims` (whose extent is `e`) and returns the halves, or `None`
/// when a leaf is cheaper under `policy` (or no bin boundary separates the centroids).
pub(super) fn sah_split(prims: &mut [BuildPrim], e: &Extent, policy: SplitPolicy) -> Option<Split> {
    let count = prims.len();
    let binner = Binner::new(e, count);
    let best = if count >= PARALLEL_BINNING_MIN {
        let bins = prims
            .par_chunks(PARALLEL_BINNING_MIN / 4)
            .map(|c| binner.bin(c))
            .reduce_with(|a, b| a.merge(&b))
            .expect("a non-empty range has a chunk");
        best_split(&bins, &binner, count)
    } else {
        SCRATCH_BINS.with(|bins| {
            let mut bins = bins.borrow_mut();
            bins[0].reset(binner.n);
            bins[1].reset(binner.n);
            binner.bin_into(prims, &mut bins);
            best_split(&bins[0], &binner, count)
        })
    };
    let (cost, axis, split) = best?;
    let area = surface_area(e.lower, e.upper);
    let split_cost = if area > 0.0 { TRAVERSAL_COST + cost / area } else { TRAVERSAL_COST };
    if policy == SplitPolicy::LeafIfCheaper
        && count <= MAX_LEAF
        && e.is_pure(count)
        && split_cost >= leaf_cost(count, e.other == 0)
    {
        return None;
    }
    let s = partition(prims, |p| binner.bin_on(axis, p) <= split);
    (s.mid > 0 && s.mid < count).then_some(s)
}

/// Moves the primitives for which `in_left` holds to the front (swapping from both ends) and
/// returns the two parts.
fn partition(prims: &mut [BuildPrim], in_left: impl Fn(&BuildPrim) -> bool) -> Split {
    let (mut left, mut right) = (Extent::EMPTY, Extent::EMPTY);
    let (mut i, mut j) = (0usize, prims.len());
    loop {
        while i < j && in_left(&prims[i]) {
            left.grow(&prims[i]);
            i += 1;
        }
        while i < j && !in_left(&prims[j - 1]) {
            right.grow(&prims[j - 1]);
            j -= 1;
        }
        if i >= j {
            break;
        }
        // the extents grow from the copies in registers: reading back the slots just written
        // stalls on store forwarding (a third of the partition's time)
        let (a, b) = (prims[i], prims[j - 1]);
        prims[i] = b;
        prims[j - 1] = a;
        left.grow(&b);
        right.grow(&a);
        i += 1;
        j -= 1;
    }
    Split { mid: i, left, right }
}

/// What a range becomes.
#[derive(Clone, Copy, Debug)]
pub(super) enum Decision {
    /// A leaf: at most [`MAX_LEAF`] primitives, all of one kind.
    Leaf,
    /// Two halves.
    Inner(Split),
}

/// The builder's decision for `prims` (extent `e`, at binary depth `depth`), partitioning
/// them where they split: the SAH's split; below [`SAH_MAX_DEPTH`], or where the SAH prefers
/// a leaf that would be too large or mixed, the object median or triangles-first.
pub(super) fn decide(prims: &mut [BuildPrim], e: &Extent, depth: usize) -> Decision {
    let count = prims.len();
    if count == 1 {
        return Decision::Leaf;
    }
    if depth < SAH_MAX_DEPTH {
        if let Some(s) = sah_split(prims, e, SplitPolicy::LeafIfCheaper) {
            return Decision::Inner(s);
        }
    }
    let pure = e.is_pure(count);
    if count <= MAX_LEAF && pure {
        return Decision::Leaf;
    }
    if count <= MAX_LEAF {
        // the SAH wants a leaf, but leaves hold one kind: triangles first, then the rest
        return Decision::Inner(partition(prims, BuildPrim::is_triangle));
    }
    // the SAH prefers a leaf (or all centroids coincide) but it would be too big, or the tree
    // is too deep: split at the median along the widest centroid axis
    let axis = Aabb::new(Vec3::from(e.clower), Vec3::from(e.cupper)).max_axis();
    let mid = count / 2;
    prims.select_nth_unstable_by(mid, |a, b| a.centroid2()[axis].total_cmp(&b.centroid2()[axis]));
    let (l, r) = prims.split_at(mid);
    let (left, right) = if count >= PARALLEL_BINNING_MIN {
        rayon::join(|| Extent::of(l), || Extent::of(r))
    } else {
        (Extent::of(l), Extent::of(r))
    };
    Decision::Inner(Split { mid, left, right })
}

/// A refinement of a leaf of several shapes (see `wide_build.rs`): the SAH's best split of it,
/// kept where it lowers the expected number of tests (surface area × packets or analytic
/// primitives; the node visit is free where a wide node has a slot to spare). A refinement
/// that needs more triangle packets than the leaf also costs memory, so it must cut the tests
/// to [`REFINE_GROWTH_GAIN`] of the leaf's: a wall and a light pass; overlapping halves do
/// not.
///
/// Only leaves that hold several shapes are refined: those are separate objects the SAH put
/// together (cornell's walls, materials' spheres). The triangles of one mesh in a leaf are a
/// compact patch; refining those too made sphere1m's BVH build 1.3–1.5× longer and its shadow
/// rays 0.67–0.72 of Embree's speed instead of 0.99 (benches/embree, 2 threads; 2026-12-02,
/// AMD EPYC, 2 cores).
pub(super) fn refine(prims: &mut [BuildPrim], e: &Extent) -> Option<Split> {
    let count = prims.len();
    if count < 2 || prims.iter().all(|p| p.shape == prims[0].shape) {
        return None;
    }
    let triangles = e.other == 0;
    let cost = |x: &Extent, n: usize| surface_area(x.lower, x.upper) * leaf_cost(n, triangles);
    let s = sah_split(prims, e, SplitPolicy::Always)?;
    let grows = leaf_cost(s.mid, triangles) + leaf_cost(count - s.mid, triangles)
        > leaf_cost(count, triangles);
    let gain = if grows && triangles { REFINE_GROWTH_GAIN } else { 1.0 };
    (cost(&s.left, s.mid) + cost(&s.right, count - s.mid) < gain * cost(e, count)).then_some(s)
}

/// See [`refine`].
const REFINE_GROWTH_GAIN: f32 = 0.75;
