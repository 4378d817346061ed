//! Merging rendered blocks into passes, in item order.
//!
//! Blocks arrive in whatever order the threads finish them. A pass is merged once all its
//! items are in: its blocks are added in item order into a film of its own that starts from
//! zero, and that pass film goes to the render's sums ([`RenderSums`](super::RenderSums)),
//! which fold passes in pass order. The sums (f64, and f64 addition is not associative) are
//! therefore the same bit for bit for any thread count or timing, and for any split of the
//! passes between processes; they only ever hold complete passes.
//!
//! Threads take items up to one pass ahead of the first unmerged one ([`PassGate`]): a thread
//! that finishes its last tile of a pass starts on the next pass while the others finish
//! theirs (a barrier per pass idled 4 % of the cores on a 64-spp Cornell box, 2026-12-02, 2-core
//! AMD EPYC), and blocks waiting for a slow tile of an earlier pass hold at most about two
//! passes' worth of memory. A thread that runs ahead waits on a condition variable that each
//! merged pass signals.

use std::sync::{Condvar, Mutex};
use std::time::Duration;

use crate::film::{Film, ImageBlock};

/// Collects the blocks of a render and hands on complete passes.
pub(super) struct PassMerger {
    blocks: Vec<Option<ImageBlock>>,
    /// A cleared film of the render's size and layers: each pass starts as a copy.
    template: Film,
    /// Per pass: one past its last item, and the samples per pixel once merged.
    pass_ends: Vec<(usize, u32)>,
    /// The first pass not merged yet.
    pass: usize,
    /// Items merged so far (the first unmerged item).
    merged: usize,
    /// Samples per pixel in the film.
    spp_done: u32,
}

impl PassMerger {
    pub fn new(items: usize, pass_ends: Vec<(usize, u32)>, template: &Film) -> Self {
        let mut template = template.clone();
        template.clear();
        PassMerger {
            blocks: (0..items).map(|_| None).collect(),
            template,
            pass_ends,
            pass: 0,
            merged: 0,
            spp_done: 0,
        }
    }

    /// Takes item `i`'s block and hands every pass that is now complete to `pass_done`, with
    /// the samples per pixel it ends at; returns the number of items merged so far.
    pub fn add(
        &mut self,
        i: usize,
        block: ImageBlock,
        mut pass_done: impl FnMut(u32, Film),
    ) -> usize {
        self.blocks[i] = Some(block);
        while let Some(&(end, last)) = self.pass_ends.get(self.pass) {
            if self.blocks[self.merged..end].iter().any(Option::is_none) {
                break;
            }
            let mut film = self.template.clone();
            for b in self.blocks[self.merged..end].iter_mut() {
                film.merge(&b.take().expect("checked above"));
            }
            pass_done(last, film);
            (self.merged, self.spp_done, self.pass) = (end, last, self.pass + 1);
        }
        self.merged
    }

    /// Samples per pixel in the film: those of the complete passes merged.
    #[cfg(test)]
    pub fn spp_done(&self) -> u32 {
        self.spp_done
    }
}

/// Holds threads back from taking items more than `window` ahead of the first unmerged item.
pub(super) struct PassGate {
    merged: Mutex<usize>,
    advanced: Condvar,
    window: usize,
}

/// How often a waiting thread looks at the cancel flag (a Ctrl-C does not signal the gate).
const CANCEL_POLL: Duration = Duration::from_millis(20);

impl PassGate {
    pub fn new(window: usize) -> Self {
        PassGate { merged: Mutex::new(0), advanced: Condvar::new(), window }
    }

    /// Waits until item `i` may be taken, or `cancelled` is true. The items of the first
    /// unmerged pass are never held back, so this ends while the render runs.
    pub fn wait_for(&self, i: usize, cancelled: impl Fn() -> bool) {
        let mut merged = self.merged.lock().unwrap_or_else(|e| e.into_inner());
        while i >= *merged + self.window && !cancelled() {
            merged = match self.advanced.wait_timeout(merged, CANCEL_POLL) {
                Ok((m, _)) => m,
                Err(e) => e.into_inner().0,
            };
        }
    }

    /// Records that the first `merged` items are in the film and wakes waiting threads.
    pub fn advance(&self, merged: usize) {
        *self.merged.lock().unwrap_or_else(|e| e.into_inner()) = merged;
        self.advanced.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::{BoxFilter, ReconstructionFilter};
    use crate::Spectrum;
    use glam::{UVec2, Vec2};

    /// Four one-pixel blocks (items) whose values cancel: 1e30, 1, −1e30, 2. In f64 the sum
    /// depends on the order of addition ((1e30 + 1) − 1e30 = 0 but (1e30 − 1e30) + 1 = 1), so
    /// the film shows whether blocks were merged in item order.
    fn blocks(filter: &ReconstructionFilter) -> Vec<ImageBlock> {
        [1e30f32, 1.0, -1e30, 2.0]
            .iter()
            .map(|&v| {
                let mut b = ImageBlock::with_clip(UVec2::ZERO, UVec2::ONE, filter, [1, 1]);
                b.put(Vec2::splat(0.5), Spectrum::splat(v));
                b
            })
            .collect()
    }

    fn film_after(order: [usize; 4]) -> (f32, u32) {
        let filter = ReconstructionFilter::Box(BoxFilter::new());
        let mut film = Film::new(1, 1, filter).expect("valid film");
        let mut m = PassMerger::new(4, vec![(3, 1), (4, 2)], &film);
        let mut bs: Vec<Option<ImageBlock>> = blocks(&filter).into_iter().map(Some).collect();
        for i in order {
            m.add(i, bs[i].take().expect("each item once"), |_, p| {
                film.accumulate(&p).expect("same size")
            });
        }
        (film.develop().data[0], m.spp_done())
    }

    #[test]
    fn any_arrival_order_gives_the_in_order_film() {
        // passes from zero, in item order: (((1e30 + 1) − 1e30) + 2) / 4 = 0.5 (the 1 is lost
        // to rounding)
        assert_eq!(film_after([0, 1, 2, 3]), (0.5, 2));
        // merged as they arrived, these would give 0.75
        for order in [[2, 0, 1, 3], [3, 2, 1, 0], [1, 2, 3, 0]] {
            assert_eq!(film_after(order), (0.5, 2), "arrival order {order:?}");
        }
    }

    #[test]
    fn only_complete_passes_are_merged() {
        let filter = ReconstructionFilter::Box(BoxFilter::new());
        let mut f = Film::new(1, 1, filter).expect("valid film");
        let mut m = PassMerger::new(4, vec![(2, 1), (4, 2)], &f);
        let mut b: Vec<Option<ImageBlock>> = blocks(&filter).into_iter().map(Some).collect();
        let mut add = |m: &mut PassMerger, i: usize, f: &mut Film| {
            m.add(i, b[i].take().unwrap(), |_, p| f.accumulate(&p).expect("same size"))
        };
        // items 2 (second pass) and 1: the first pass is not complete, nothing is merged
        assert_eq!(add(&mut m, 2, &mut f), 0);
        assert_eq!(add(&mut m, 1, &mut f), 0);
        assert_eq!((m.spp_done(), f.develop().data[0]), (0, 0.0));
        // item 0 completes the first pass: (1e30 + 1) / 2
        assert_eq!(add(&mut m, 0, &mut f), 2);
        assert_eq!((m.spp_done(), f.develop().data[0]), (1, 5e29));
        // the second pass from zero, −1e30 + 2 = −1e30, added to the first: 0 (merged into the
        // film block by block it would be ((1e30 + 1) − 1e30 + 2) / 4 = 0.5)
        assert_eq!(add(&mut m, 3, &mut f), 4);
        assert_eq!((m.spp_done(), f.develop().data[0]), (2, 0.0));
    }

    #[test]
    fn the_gate_holds_threads_within_the_window_and_opens_on_advance() {
        use std::sync::atomic::{AtomicBool, Ordering};
        let gate = PassGate::new(2);
        gate.wait_for(1, || false); // inside the window: returns at once
        let passed = AtomicBool::new(false);
        std::thread::scope(|s| {
            s.spawn(|| {
                gate.wait_for(3, || false);
                passed.store(true, Ordering::SeqCst);
            });
            std::thread::sleep(Duration::from_millis(50));
            assert!(!passed.load(Ordering::SeqCst), "item 3 taken with 0 merged and window 2");
            gate.advance(2);
        });
        assert!(passed.load(Ordering::SeqCst));
        // a cancel releases a waiting thread
        gate.wait_for(100, || true);
    }
}
