//! Owen-scrambled Sobol points, four dimensions at a time, as the sampler draws them.
//!
//! [`sample_4d`] returns exactly what `sobol_burley::sample_4d(index, 0, seed)` returns
//! (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020: a shuffled index, the
//! first four Sobol dimensions, then a hash-based Owen scramble per dimension), computed
//! faster for the one dimension set the sampler uses:
//!
//! - the Sobol matrix–vector product over the 16 index bits is two lookups in byte tables
//!   (2 × 256 entries of four dimensions, 8 KiB, built once from the crate's own product),
//!   instead of a loop over the set bits;
//! - the hashes run on scalar 32-bit integers, which x86-64's baseline multiplies natively
//!   (the crate's 4-wide integers emulate 32-bit multiplies with SSE2 shuffles); only the
//!   final bit reversal and conversion use the crate's 4-wide integers.
//!
//! The crate stays the source of truth: a test compares both on many indices and seeds.

use std::sync::OnceLock;

use sobol_burley::parts::{hash, owen_scramble_rev, sobol_int4_rev, Int4};

/// `TABLES[0][b]`: the bit-reversed Sobol product for index bits whose reversed top byte is
/// `b`; `TABLES[1][b]`: the same for the second byte.
type Tables = [[[u32; 4]; 256]; 2];

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Box<Tables>> = OnceLock::new();
    TABLES.get_or_init(|| {
        let mut t = Box::new([[[0u32; 4]; 256]; 2]);
        for (k, table) in t.iter_mut().enumerate() {
            let shift = 24 - 8 * k as u32;
            for (b, entry) in table.iter_mut().enumerate() {
                *entry = sobol_int4_rev((b as u32) << shift, 0).into();
            }
        }
        t
    })
}

/// Per-dimension constants of the crate's scramble seeds.
const DIM_SALT: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];

/// One 4-D point of the sequence before its dimensions are scrambled: the shuffled index's
/// Sobol product per dimension (bit-reversed) and the seed the dimensions' scrambles derive
/// from. Each pair of dimensions is finished on demand ([`SobolPoint::dims`]): a 2-D draw
/// that starts a block needs only dimensions 0 and 1, and half the scrambling work.
#[derive(Clone, Copy, Debug)]
pub struct SobolPoint {
    sobol_rev: [u32; 4],
    seed: u32,
}

impl SobolPoint {
    /// A placeholder before the first block.
    pub const EMPTY: SobolPoint = SobolPoint { sobol_rev: [0; 4], seed: 0 };

    /// Sample `index` (< 2¹⁶) of the Owen-scrambled Sobol sequence `seed`.
    #[inline]
    pub fn new(index: u32, seed: u32) -> SobolPoint {
        debug_assert!(index < 1 << 16);
        let t = tables();
        let rev = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c6_8e4a));
        let hi = &t[0][(rev >> 24) as usize];
        let lo = &t[1][((rev >> 16) & 0xff) as usize];
        SobolPoint {
            sobol_rev: std::array::from_fn(|d| hi[d] ^ lo[d]),
            seed: seed.wrapping_mul(0x9c8f_2d3b),
        }
    }

    /// Dimensions `2·pair` and `2·pair + 1` (`pair` is 0 or 1), in [0, 1).
    #[inline]
    pub fn dims(&self, pair: usize) -> [f32; 2] {
        let (a, b) = (2 * pair, 2 * pair + 1);
        let scramble =
            |d: usize| owen_scramble_rev(self.sobol_rev[d], hash(self.seed ^ DIM_SALT[d]));
        // un-reversing lanes is cheap in SSE2 (no multiplies); two lanes are left idle
        let v = Int4::from([scramble(a), scramble(b), 0, 0]).reverse_bits().to_f32_norm();
        [v[0], v[1]]
    }
}

/// Dimensions 0–3 of sample `index` (< 2¹⁶) of the Owen-scrambled Sobol sequence `seed`
/// (what the tests compare with the crate).
#[cfg(test)]
fn sample_4d(index: u32, seed: u32) -> [f32; 4] {
    let p = SobolPoint::new(index, seed);
    let ([a, b], [c, d]) = (p.dims(0), p.dims(1));
    [a, b, c, d]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bit-identical to the crate for all 2¹⁶ indices of a few seeds, and for many seeds.
    #[test]
    fn matches_sobol_burley() {
        for seed in [0u32, 1, 0xdead_beef, u32::MAX] {
            for index in 0..1u32 << 16 {
                assert_eq!(
                    sample_4d(index, seed),
                    sobol_burley::sample_4d(index, 0, seed),
                    "index {index} seed {seed}"
                );
            }
        }
        let mut s = 0x1234_5678u32;
        for i in 0..100_000u32 {
            s = hash(s ^ i);
            let index = s & 0xffff;
            assert_eq!(
                sample_4d(index, s),
                sobol_burley::sample_4d(index, 0, s),
                "index {index} seed {s}"
            );
        }
    }
}
