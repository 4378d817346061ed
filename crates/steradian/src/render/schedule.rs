//! The pass schedule: which samples of which pixels each work item renders, decided from the
//! film size and the sample count alone (never from the thread count), so that images are
//! reproducible.
//!
//! Passes grow from 1 sample per pixel by doubling, up to ⌈spp / 32⌉ per pass, so that an early
//! Ctrl-C still finds a finished pass, and a render has some 32 passes or more: the units of
//! checkpoints and of distributed tasks (a pass costs one film-sized fold, 4 MB of additions
//! on a 256×256 film, against seconds of rendering). Each pass is split into
//! square tiles of [`TILE`] pixels, and each tile into sample ranges when the film has fewer
//! tiles than [`WORK_ITEMS_PER_PASS`] (a 1×1 meter film would otherwise keep one core busy).

use glam::UVec2;

/// Side of a square render tile, pixels.
pub(super) const TILE: u32 = 32;
/// Passes grow up to 1/PASS_FRACTION of the samples per pixel.
const PASS_FRACTION: u32 = 32;
/// Work items per pass to aim for when the film has few tiles.
const WORK_ITEMS_PER_PASS: u32 = 64;

/// Samples `s0..s1` of every pixel of the tile at `offset` of `size` pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct WorkItem {
    pub offset: UVec2,
    pub size: UVec2,
    pub s0: u32,
    pub s1: u32,
}

/// The work items of a render in pass order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Schedule {
    pub items: Vec<WorkItem>,
    /// For each pass: the index one past its last item, and the samples per pixel the film
    /// holds once it is merged.
    pub pass_ends: Vec<(usize, u32)>,
    /// The most items in one pass.
    pub window: usize,
}

/// Pass boundaries in samples per pixel: 0, 1, 3, 7, … up to `spp`, steps at most ⌈spp/32⌉.
pub(super) fn pass_bounds(spp: u32) -> Vec<u32> {
    let mut bounds = vec![0u32];
    let mut size = 1u32;
    while *bounds.last().expect("starts with 0") < spp {
        let next = (bounds.last().expect("starts with 0") + size).min(spp);
        bounds.push(next);
        size = (size * 2).min(spp.div_ceil(PASS_FRACTION).max(1));
    }
    bounds
}

/// The film's tiles, row by row: offset and size in pixels.
pub(super) fn tiles(width: u32, height: u32) -> Vec<(UVec2, UVec2)> {
    (0..height.div_ceil(TILE))
        .flat_map(|ty| (0..width.div_ceil(TILE)).map(move |tx| (tx, ty)))
        .map(|(tx, ty)| {
            let o = UVec2::new(tx * TILE, ty * TILE);
            (o, UVec2::new(TILE.min(width - o.x), TILE.min(height - o.y)))
        })
        .collect()
}

/// Every work item of a `width` × `height` film at `spp` samples per pixel.
pub(super) fn schedule(width: u32, height: u32, spp: u32) -> Schedule {
    let tiles = tiles(width, height);
    let mut items = Vec::new();
    let mut pass_ends = Vec::new();
    let mut window = 1;
    for pass in pass_bounds(spp).windows(2) {
        // samples [first, last) of every pixel
        let (first, last) = (pass[0], pass[1]);
        let pass_start = items.len();
        let per_pass = last - first;
        let chunks = (WORK_ITEMS_PER_PASS.div_ceil(tiles.len() as u32)).clamp(1, per_pass);
        for &(offset, size) in &tiles {
            for c in 0..chunks {
                let s0 = first + (per_pass as u64 * c as u64 / chunks as u64) as u32;
                let s1 = first + (per_pass as u64 * (c as u64 + 1) / chunks as u64) as u32;
                if s1 > s0 {
                    items.push(WorkItem { offset, size, s0, s1 });
                }
            }
        }
        pass_ends.push((items.len(), last));
        window = window.max(items.len() - pass_start);
    }
    Schedule { items, pass_ends, window }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_double_up_to_a_32nd_and_end_at_spp() {
        assert_eq!(pass_bounds(1), [0, 1]);
        assert_eq!(pass_bounds(4), [0, 1, 2, 3, 4]);
        let odd: Vec<u32> = [0].into_iter().chain((0..32).map(|k| 2 * k + 1)).chain([64]).collect();
        assert_eq!(pass_bounds(64), odd);
        assert_eq!(pass_bounds(256)[..6], [0, 1, 3, 7, 15, 23]);
        for spp in 1..300 {
            let b = pass_bounds(spp);
            assert_eq!((b[0], *b.last().unwrap()), (0, spp));
            let cap = spp.div_ceil(PASS_FRACTION).max(1);
            for (k, w) in b.windows(2).enumerate() {
                let step = w[1] - w[0];
                assert!(step >= 1 && step <= cap, "spp {spp}: step {step} > {cap}");
                assert!(k >= 31 || step <= 1 << k, "spp {spp}: pass {k} takes {step} samples");
            }
        }
    }

    #[test]
    fn tiles_cover_the_film_once() {
        for (w, h) in [(1, 1), (31, 33), (64, 64), (100, 7), (256, 256)] {
            let mut hits = vec![0u8; (w * h) as usize];
            for (o, s) in tiles(w, h) {
                assert!(s.x >= 1 && s.y >= 1 && s.x <= TILE && s.y <= TILE);
                for y in o.y..o.y + s.y {
                    for x in o.x..o.x + s.x {
                        hits[(y * w + x) as usize] += 1;
                    }
                }
            }
            assert!(hits.iter().all(|&n| n == 1), "{w}x{h}");
        }
    }

    /// Every (pixel, sample) is rendered exactly once, by an item of the pass that holds the
    /// sample, and each pass ends at its bound.
    #[test]
    fn items_cover_every_pixel_sample_once_in_pass_order() {
        for (w, h, spp) in [(1, 1, 1), (1, 1, 100), (3, 2, 17), (40, 70, 9), (256, 256, 64)] {
            let sched = schedule(w, h, spp);
            let bounds = pass_bounds(spp);
            assert_eq!(sched.pass_ends.len(), bounds.len() - 1);
            let mut count = vec![0u16; (w * h * spp) as usize];
            let mut start = 0;
            for (pass, &(end, last)) in sched.pass_ends.iter().enumerate() {
                assert_eq!(last, bounds[pass + 1]);
                assert!(end - start <= sched.window);
                for it in &sched.items[start..end] {
                    assert!(bounds[pass] <= it.s0 && it.s0 < it.s1 && it.s1 <= last);
                    for y in it.offset.y..it.offset.y + it.size.y {
                        for x in it.offset.x..it.offset.x + it.size.x {
                            for s in it.s0..it.s1 {
                                count[((y * w + x) * spp + s) as usize] += 1;
                            }
                        }
                    }
                }
                start = end;
            }
            assert_eq!(start, sched.items.len());
            assert!(count.iter().all(|&n| n == 1), "{w}x{h} at {spp} spp");
        }
    }

    #[test]
    fn small_films_split_passes_into_sample_ranges() {
        // a meter's 1x1 film: a 4-sample pass becomes 4 items, so every core gets work
        let sched = schedule(1, 1, 100);
        let (end, last) = sched.pass_ends[sched.pass_ends.len() - 2];
        let prev = sched.pass_ends[sched.pass_ends.len() - 3];
        assert_eq!(last - prev.1, 4);
        assert_eq!(end - prev.0, 4);
        // a film of 64 tiles or more: one item per tile and pass
        let sched = schedule(256, 256, 64);
        assert_eq!(sched.window, 64);
        assert_eq!(sched.items.len(), 64 * (pass_bounds(64).len() - 1));
    }
}
