//! Top-down construction of the 8-wide BVH, straight from the SAH's decisions (`sah_build.rs`)
//! with no binary tree in between.
//!
//! A wide node starts as the two halves of its range; it keeps opening the child of largest
//! surface area that the SAH splits, until it has [`WIDTH`] children or only leaves remain (the
//! collapse of Embree's BVH8 builder, done while building). Where slots are still free, the
//! leaves of several shapes are refined: the SAH's split of such a leaf costs no node visit
//! here (all children of a wide node are tested at once) and lets the box test cull part of it
//! (`sah_build::refine`).
//!
//! Large ranges (more than [`PARALLEL_MIN`] primitives) split their halves' decisions over
//! threads, and the subtrees of their children are built as separate chunks in parallel. Each
//! chunk numbers its nodes, triangle packets and analytic primitives from 0; the layout pass
//! places the chunks depth-first in one array and offsets their codes, so the result is the
//! same for any number of threads and every node is copied once. Leaves are recorded as ranges
//! of the primitive array and turned into the packets' lane ids before the layout, so that the
//! primitive array is freed before the nodes are copied.

use rayon::prelude::*;

use super::layout::{
    leaf_code, leaf_range, with_huge_pages, Node8, PrimRef, Tri4Ids, ANALYTIC, EMPTY_CHILD, LEAF,
    WIDTH,
};
use super::sah_build::{decide, refine, BuildPrim, Decision, Extent, Split, TRI_BLOCK};
use crate::geometry::Aabb;

/// Ranges with more primitives than this are built in parallel.
const PARALLEL_MIN: usize = 4096;

/// A leaf: primitives `start .. start + count` of the (partitioned) primitive array.
#[derive(Clone, Copy, Debug)]
struct LeafRange {
    start: u32,
    count: u32,
}

impl LeafRange {
    fn range(self) -> std::ops::Range<usize> {
        self.start as usize..(self.start + self.count) as usize
    }
}

/// The built hierarchy.
#[derive(Debug, Default)]
pub(super) struct Layout {
    /// Code of the root: a node, a leaf, or [`EMPTY_CHILD`] for no primitives.
    pub root: u32,
    pub bounds: Aabb,
    pub nodes: Vec<Node8>,
    /// The lanes of the triangle packets, in packet order (a leaf of n triangles takes ⌈n/4⌉
    /// packets); the caller fills the packets' vertices from them.
    pub tri_ids: Vec<Tri4Ids>,
    /// The analytic leaves' primitives, in leaf order.
    pub others: Vec<PrimRef>,
}

/// Builds the hierarchy over `prims` (which it frees as soon as the leaves are recorded:
/// before the nodes are laid out, so that the two never take memory at once).
pub(super) fn build(mut prims: Vec<BuildPrim>) -> Layout {
    if prims.is_empty() {
        return Layout { root: EMPTY_CHILD, bounds: Aabb::EMPTY, ..Layout::default() };
    }
    let extent = Extent::of(&prims);
    let root = Cluster::new(&mut prims, 0, extent, 0);
    let mut chunk = Chunk::default();
    let code = match root.state {
        State::Inner(_) => chunk.node(root),
        State::Leaf(_) => chunk.leaf(&root),
    };
    let (nodes, packets, others) = chunk.totals();
    let mut out = Layout {
        root: EMPTY_CHILD,
        bounds: extent.bounds(),
        nodes: with_huge_pages(nodes),
        // read once per hit, not per visit: ordinary pages (huge ones cost their first touch)
        tri_ids: Vec::with_capacity(packets),
        others: Vec::with_capacity(others),
    };
    chunk.visit(&mut |c| {
        for leaf in &c.tri_leaves {
            for lanes in prims[leaf.range()].chunks(TRI_BLOCK) {
                let mut ids = Tri4Ids { shape: [u32::MAX; 4], prim: [u32::MAX; 4] };
                for (lane, p) in lanes.iter().enumerate() {
                    ids.shape[lane] = p.shape();
                    ids.prim[lane] = p.prim();
                }
                out.tri_ids.push(ids);
            }
        }
        for leaf in &c.other_leaves {
            out.others.extend(
                prims[leaf.range()].iter().map(|p| PrimRef { shape: p.shape(), prim: p.prim() }),
            );
        }
    });
    drop(prims);
    let (mut placed_packets, mut placed_others) = (0, 0);
    let root_node = chunk.place(&mut out, &mut placed_packets, &mut placed_others);
    out.root = if code & LEAF == 0 { root_node } else { code };
    debug_assert_eq!((placed_packets, placed_others), (packets, others));
    out
}

/// What a range has been found to be.
#[derive(Clone, Copy, Debug)]
enum State {
    /// The SAH splits it.
    Inner(Split),
    /// A leaf.
    Leaf(Refinement),
}

/// Whether a leaf splits into free child slots (see [`sah_build::refine`](super::sah_build)).
#[derive(Clone, Copy, Debug)]
enum Refinement {
    Untried,
    Kept(Split),
    Declined,
}

/// A range of the primitive array, its extent, binary depth and state.
struct Cluster<'a> {
    prims: &'a mut [BuildPrim],
    offset: usize,
    extent: Extent,
    depth: usize,
    state: State,
}

impl<'a> Cluster<'a> {
    /// The range `prims` (starting at `offset` in the whole array), decided.
    fn new(prims: &'a mut [BuildPrim], offset: usize, extent: Extent, depth: usize) -> Self {
        let state = match decide(prims, &extent, depth) {
            Decision::Leaf => State::Leaf(Refinement::Untried),
            Decision::Inner(s) => State::Inner(s),
        };
        Cluster { prims, offset, extent, depth, state }
    }

    /// Whether the range is all triangles (leaves hold one kind).
    fn is_triangles(&self) -> bool {
        self.prims[0].is_triangle()
    }

    fn area(&self) -> f32 {
        self.extent.bounds().surface_area()
    }

    /// The two halves of an inner range, decided (in parallel for large ranges).
    fn halves(self) -> [Cluster<'a>; 2] {
        let State::Inner(s) = self.state else { unreachable!("only inner ranges are opened") };
        let parallel = self.prims.len() >= PARALLEL_MIN;
        let (l, r) = self.prims.split_at_mut(s.mid);
        let (offset, depth) = (self.offset, self.depth + 1);
        let (l, r) = if parallel {
            rayon::join(
                move || Cluster::new(l, offset, s.left, depth),
                move || Cluster::new(r, offset + s.mid, s.right, depth),
            )
        } else {
            (
                Cluster::new(l, offset, s.left, depth),
                Cluster::new(r, offset + s.mid, s.right, depth),
            )
        };
        [l, r]
    }

    /// Works out a leaf's refinement, once.
    fn try_refine(&mut self) {
        if let State::Leaf(Refinement::Untried) = self.state {
            self.state = State::Leaf(match refine(self.prims, &self.extent) {
                Some(s) => Refinement::Kept(s),
                None => Refinement::Declined,
            });
        }
    }

    /// The two halves of a leaf's kept refinement, each with its own refinement worked out.
    fn refined_halves(self) -> [Cluster<'a>; 2] {
        let State::Leaf(Refinement::Kept(s)) = self.state else {
            unreachable!("only kept refinements are opened")
        };
        let (l, r) = self.prims.split_at_mut(s.mid);
        let leaf = State::Leaf(Refinement::Untried);
        let depth = self.depth + 1;
        let mut halves = [
            Cluster { prims: l, offset: self.offset, extent: s.left, depth, state: leaf },
            Cluster { prims: r, offset: self.offset + s.mid, extent: s.right, depth, state: leaf },
        ];
        for h in &mut halves {
            h.try_refine();
        }
        halves
    }
}

/// Replaces the widest of `kids` that `openable` accepts by its two halves (the first in its
/// place, the second at the end); `false` when none is openable.
fn open_widest<'a>(
    kids: &mut Vec<Cluster<'a>>,
    openable: impl Fn(&State) -> bool,
    open: impl FnOnce(Cluster<'a>) -> [Cluster<'a>; 2],
) -> bool {
    let widest = kids
        .iter()
        .enumerate()
        .filter(|(_, k)| openable(&k.state))
        .map(|(i, k)| (i, k.area()))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let Some((i, _)) = widest else { return false };
    let [l, r] = open(kids.remove(i));
    kids.insert(i, l);
    kids.push(r);
    true
}

/// Nodes and leaves numbered from 0, and the chunks built apart for some of its child slots.
#[derive(Default)]
struct Chunk {
    nodes: Vec<Node8>,
    tri_leaves: Vec<LeafRange>,
    tri_packets: usize,
    other_leaves: Vec<LeafRange>,
    others: usize,
    links: Vec<Link>,
}

/// Child slot `lane` of node `node` is the root of `chunk`.
struct Link {
    node: usize,
    lane: usize,
    chunk: Chunk,
}

impl Chunk {
    /// Writes the wide node of an inner range and its subtree; returns the node's index.
    fn node(&mut self, c: Cluster) -> u32 {
        let parallel = c.prims.len() >= PARALLEL_MIN;
        let mut kids: Vec<Cluster> = Vec::with_capacity(WIDTH);
        kids.extend(c.halves());
        // inner ranges first, the largest first; then, while slots are still free, the leaves'
        // refinements
        while kids.len() < WIDTH
            && open_widest(&mut kids, |s| matches!(s, State::Inner(_)), Cluster::halves)
        {}
        if kids.len() < WIDTH {
            for k in &mut kids {
                k.try_refine();
            }
            while kids.len() < WIDTH
                && open_widest(
                    &mut kids,
                    |s| matches!(s, State::Leaf(Refinement::Kept(_))),
                    Cluster::refined_halves,
                )
            {}
        }
        let idx = self.nodes.len();
        assert!(idx < ANALYTIC as usize, "scene too large for the BVH: more than 2^30 nodes");
        self.nodes.push(Node8::EMPTY);
        let mut apart = Vec::new();
        for (lane, k) in kids.into_iter().enumerate() {
            self.nodes[idx].set_child_bounds(lane, &k.extent.bounds());
            let code = match k.state {
                State::Inner(_) if parallel => {
                    apart.push((lane, k));
                    continue;
                }
                State::Inner(_) => self.node(k),
                State::Leaf(_) => self.leaf(&k),
            };
            self.nodes[idx].child[lane] = code;
        }
        let built: Vec<(usize, Chunk)> = apart
            .into_par_iter()
            .map(|(lane, k)| {
                let mut chunk = Chunk::default();
                chunk.node(k);
                (lane, chunk)
            })
            .collect();
        self.links.extend(built.into_iter().map(|(lane, chunk)| Link { node: idx, lane, chunk }));
        idx as u32
    }

    /// Records a leaf; returns its code.
    fn leaf(&mut self, k: &Cluster) -> u32 {
        let range = LeafRange { start: k.offset as u32, count: k.prims.len() as u32 };
        if k.is_triangles() {
            let packets = k.prims.len().div_ceil(TRI_BLOCK);
            let code = leaf_code(self.tri_packets, packets, false);
            self.tri_leaves.push(range);
            self.tri_packets += packets;
            code
        } else {
            let code = leaf_code(self.others, k.prims.len(), true);
            self.other_leaves.push(range);
            self.others += k.prims.len();
            code
        }
    }

    /// Nodes, triangle packets and analytic references of this chunk and those it links.
    fn totals(&self) -> (usize, usize, usize) {
        self.links.iter().fold((self.nodes.len(), self.tri_packets, self.others), |(n, p, o), l| {
            let (ln, lp, lo) = l.chunk.totals();
            (n + ln, p + lp, o + lo)
        })
    }

    /// Calls `f` on this chunk and then, depth-first, on the chunks it links (the order of
    /// [`Chunk::place`]).
    fn visit(&self, f: &mut impl FnMut(&Chunk)) {
        f(self);
        for link in &self.links {
            link.chunk.visit(f);
        }
    }

    /// Appends this chunk and then, depth-first, the chunks it links to `out`, offsetting
    /// their codes; returns the global index of this chunk's first node.
    fn place(self, out: &mut Layout, packets: &mut usize, others: &mut usize) -> u32 {
        let node_offset = out.nodes.len();
        let (packet_offset, other_offset) = (*packets, *others);
        let relocate = |code: u32| -> u32 {
            if code == EMPTY_CHILD {
                code
            } else if code & LEAF == 0 {
                code + node_offset as u32
            } else {
                let r = leaf_range(code);
                let analytic = code & ANALYTIC != 0;
                let offset = if analytic { other_offset } else { packet_offset };
                leaf_code(r.start + offset, r.len(), analytic)
            }
        };
        out.nodes.extend(self.nodes.iter().map(|n| Node8 { child: n.child.map(relocate), ..*n }));
        *packets += self.tri_packets;
        *others += self.others;
        drop((self.nodes, self.tri_leaves, self.other_leaves));
        for link in self.links {
            let root = link.chunk.place(out, packets, others);
            out.nodes[node_offset + link.node].child[link.lane] = root;
        }
        node_offset as u32
    }
}
