//! Stack-based BVH traversal: closest hit and any hit.

use glam::Vec3;

use super::bvh::{Accel, Node, PrimRef, NOT_A_TRIANGLE};
use super::triangle::intersect_triangle;
use crate::geometry::{Aabb, PreliminaryHit, Ray};
use crate::shape::Shape;

const STACK_SIZE: usize = 64;

/// Slab test of a node against the ray restricted to `(0, t_max)`: the entry distance.
#[inline(always)]
fn hit_node(n: &Node, o: Vec3, inv_d: Vec3, t_max: f32) -> Option<f32> {
    let mut t0 = 0.0f32;
    let mut t1 = t_max;
    for a in 0..3 {
        let ta = (n.min[a] - o[a]) * inv_d[a];
        let tb = (n.max[a] - o[a]) * inv_d[a];
        // f32::min/max ignore NaN (0·∞ when the origin lies on a slab of a parallel ray)
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    (t0 <= t1).then_some(t0)
}

impl Accel {
    /// Bounds of everything in the hierarchy (empty for an empty scene).
    pub fn bounds(&self) -> Aabb {
        match self.nodes.first() {
            Some(n) => Aabb::new(Vec3::from(n.min), Vec3::from(n.max)),
            None => Aabb::EMPTY,
        }
    }

    #[inline(always)]
    fn intersect_ref(&self, shapes: &[Shape], r: &PrimRef, ray: &Ray) -> Option<(f32, glam::Vec2)> {
        if r.tri != NOT_A_TRIANGLE {
            let [a, b, c] = self.tris[r.tri as usize];
            intersect_triangle(a, b, c, ray)
        } else {
            shapes[r.shape as usize].intersect_prim(r.prim, ray)
        }
    }

    /// The closest hit with `t < ray.t_max`.
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray) -> Option<PreliminaryHit> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv_d = ray.d.recip();
        let mut ray = *ray;
        let mut best: Option<PreliminaryHit> = None;
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0usize;
        hit_node(&self.nodes[0], ray.o, inv_d, ray.t_max)?;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.count > 0 {
                let first = n.offset as usize;
                for r in &self.prims[first..first + n.count as usize] {
                    if let Some((t, uv)) = self.intersect_ref(shapes, r, &ray) {
                        ray.t_max = t;
                        best = Some(PreliminaryHit { t, uv, shape: r.shape, prim: r.prim });
                    }
                }
            } else {
                let l = n.offset as usize;
                let hl = hit_node(&self.nodes[l], ray.o, inv_d, ray.t_max);
                let hr = hit_node(&self.nodes[l + 1], ray.o, inv_d, ray.t_max);
                match (hl, hr) {
                    (Some(tl), Some(tr)) => {
                        let (near, far) = if tl <= tr { (l, l + 1) } else { (l + 1, l) };
                        if sp < STACK_SIZE {
                            stack[sp] = far as u32;
                            sp += 1;
                            node = near;
                            continue;
                        }
                        // A stack overflow cannot happen for trees of sane depth; fall back
                        // to a recursive query of the far subtree to stay correct.
                        if let Some(h) = self.intersect_subtree(shapes, &ray, inv_d, far) {
                            ray.t_max = h.t;
                            best = Some(h);
                        }
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = l;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = l + 1;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // pop, skipping nodes that the shortened ray no longer reaches
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                let cand = stack[sp] as usize;
                if hit_node(&self.nodes[cand], ray.o, inv_d, ray.t_max).is_some() {
                    node = cand;
                    break;
                }
            }
        }
    }

    /// Closest hit inside the subtree rooted at `root` (recursive; only used on stack overflow).
    fn intersect_subtree(&self, shapes: &[Shape], ray: &Ray, inv_d: Vec3, root: usize) -> Option<PreliminaryHit> {
        let n = &self.nodes[root];
        hit_node(n, ray.o, inv_d, ray.t_max)?;
        if n.count > 0 {
            let mut ray = *ray;
            let mut best = None;
            let first = n.offset as usize;
            for r in &self.prims[first..first + n.count as usize] {
                if let Some((t, uv)) = self.intersect_ref(shapes, r, &ray) {
                    ray.t_max = t;
                    best = Some(PreliminaryHit { t, uv, shape: r.shape, prim: r.prim });
                }
            }
            return best;
        }
        let l = n.offset as usize;
        let mut ray = *ray;
        let a = self.intersect_subtree(shapes, &ray, inv_d, l);
        if let Some(h) = a {
            ray.t_max = h.t;
        }
        self.intersect_subtree(shapes, &ray, inv_d, l + 1).or(a)
    }

    /// Whether anything is hit with `t < ray.t_max` (stops at the first hit found).
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv_d = ray.d.recip();
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0usize;
        let mut node = 0usize;
        if hit_node(&self.nodes[0], ray.o, inv_d, ray.t_max).is_none() {
            return false;
        }
        loop {
            let n = &self.nodes[node];
            if n.count > 0 {
                let first = n.offset as usize;
                if self.prims[first..first + n.count as usize].iter().any(|r| self.intersect_ref(shapes, r, ray).is_some()) {
                    return true;
                }
            } else {
                let l = n.offset as usize;
                let hl = hit_node(&self.nodes[l], ray.o, inv_d, ray.t_max).is_some();
                let hr = hit_node(&self.nodes[l + 1], ray.o, inv_d, ray.t_max).is_some();
                match (hl, hr) {
                    (true, true) => {
                        if sp < STACK_SIZE {
                            stack[sp] = (l + 1) as u32;
                            sp += 1;
                        } else if self.intersect_subtree(shapes, ray, inv_d, l + 1).is_some() {
                            return true;
                        }
                        node = l;
                        continue;
                    }
                    (true, false) => {
                        node = l;
                        continue;
                    }
                    (false, true) => {
                        node = l + 1;
                        continue;
                    }
                    (false, false) => {}
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            node = stack[sp] as usize;
        }
    }
}
