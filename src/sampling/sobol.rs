//! Dimensions 0 and 1 of the Owen-scrambled, shuffled Sobol sequence of the `sobol_burley`
//! crate (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)), bit for bit,
//! at a lower cost: the index shuffle is shared by the two dimensions, and the Sobol
//! points come from byte tables instead of a loop over the index bits.
//!
//! A Sobol point is linear over GF(2) in the bits of its index (Joe & Kuo 2008): the
//! point of an index is the XOR of the direction numbers of its set bits. So the point of
//! a 16-bit index is `HIGH[index's high byte] ^ LOW[index's low byte]`, two loads. The
//! tables are built once from the crate's own `sobol_rev`, and the tests compare every
//! index against `sobol_burley::sample`.

use std::sync::OnceLock;

use glam::Vec2;
use sobol_burley::parts::{hash, owen_scramble_rev, sobol_rev, u32_to_f32_norm};

/// For dimensions 0 and 1: the (bit-reversed) Sobol points of indices whose reversed
/// value has only bits 24..32 set (`high`) or only bits 16..24 (`low`).
struct Tables {
    high: [[u32; 256]; 2],
    low: [[u32; 256]; 2],
}

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let mut t = Tables {
            high: [[0; 256]; 2],
            low: [[0; 256]; 2],
        };
        for dimension in 0..2 {
            for byte in 0..256u32 {
                t.high[dimension][byte as usize] = sobol_rev(byte << 24, dimension as u32);
                t.low[dimension][byte as usize] = sobol_rev(byte << 16, dimension as u32);
            }
        }
        t
    })
}

/// The per-dimension scramble constants and seed multiplier of `sobol_burley::sample`
/// (dimensions 0 and 1 of its first set of four); the tests pin them to the crate.
const SCRAMBLE: [u32; 2] = [0x912f_69ba, 0x174f_18ab];
const SEED_MULTIPLIER: u32 = 0x9c8f_2d3b;
const SHUFFLE_SALT: u32 = 0x79c6_8e4a;

/// The hashes of one seed that a Sobol point needs before it looks at the index: the
/// index shuffle's scramble (Burley 2020 §3) and each dimension's (§2). They depend on
/// the seed alone, so a sampler whose seeds repeat from sample to sample (a pixel's
/// dimensions, see [`crate::sampling::sampler::PixelStreams`]) hashes them once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SobolSeed {
    shuffle: u32,
    scramble: [u32; 2],
}

impl SobolSeed {
    /// The hashes of `seed`.
    #[inline(always)]
    pub fn new(seed: u32) -> SobolSeed {
        let scramble = |d: usize| hash(seed.wrapping_mul(SEED_MULTIPLIER) ^ SCRAMBLE[d]);
        SobolSeed {
            shuffle: hash(seed ^ SHUFFLE_SALT),
            scramble: [scramble(0), scramble(1)],
        }
    }
}

/// The Owen-scrambled shuffle of the sample index (Burley 2020 §3), given bit-reversed
/// (`index.reverse_bits()`), split into the byte-table indices of its top 16 bits.
#[inline(always)]
fn shuffled_bytes(index_rev: u32, seed: &SobolSeed) -> (usize, usize) {
    let shuffled = owen_scramble_rev(index_rev, seed.shuffle);
    (
        (shuffled >> 24) as usize,
        ((shuffled >> 16) & 0xff) as usize,
    )
}

/// Dimension `d` (0 or 1) of the shuffled index, Owen-scrambled (Burley 2020 §2), still
/// bit-reversed.
#[inline(always)]
fn dimension_rev(t: &Tables, d: usize, (high, low): (usize, usize), seed: &SobolSeed) -> u32 {
    let sobol = t.high[d][high] ^ t.low[d][low];
    owen_scramble_rev(sobol, seed.scramble[d])
}

/// `sobol_burley::sample(index, 0, seed)`. `index` must be below 2¹⁶.
#[inline]
pub fn sobol_1d(index: u32, seed: u32) -> f32 {
    sobol_1d_rev(index.reverse_bits(), seed)
}

/// `[sobol_burley::sample(index, 0, seed), sobol_burley::sample(index, 1, seed)]`,
/// computed together. `index` must be below 2¹⁶.
#[inline]
pub fn sobol_2d(index: u32, seed: u32) -> Vec2 {
    sobol_2d_rev(index.reverse_bits(), seed)
}

/// [`sobol_1d`] of the index whose bit reversal is `index_rev`: a sampler reverses its
/// sample index once for all its dimensions (x86-64 has no bit-reversal instruction).
#[inline]
pub fn sobol_1d_rev(index_rev: u32, seed: u32) -> f32 {
    sobol_1d_seeded(index_rev, &SobolSeed::new(seed))
}

/// [`sobol_2d`] of the index whose bit reversal is `index_rev`.
#[inline]
pub fn sobol_2d_rev(index_rev: u32, seed: u32) -> Vec2 {
    sobol_2d_seeded(index_rev, &SobolSeed::new(seed))
}

/// [`sobol_1d_rev`] under a seed already hashed ([`SobolSeed::new`]).
#[inline]
pub fn sobol_1d_seeded(index_rev: u32, seed: &SobolSeed) -> f32 {
    u32_to_f32_norm(
        dimension_rev(tables(), 0, shuffled_bytes(index_rev, seed), seed).reverse_bits(),
    )
}

/// [`sobol_2d_rev`] under a seed already hashed ([`SobolSeed::new`]).
#[inline]
pub fn sobol_2d_seeded(index_rev: u32, seed: &SobolSeed) -> Vec2 {
    let (t, bytes) = (tables(), shuffled_bytes(index_rev, seed));
    // Both dimensions reversed by one 64-bit reversal (x86-64 has no instruction for
    // it, so it costs a dozen), which also swaps them.
    let x = dimension_rev(t, 0, bytes, seed) as u64;
    let y = dimension_rev(t, 1, bytes, seed) as u64;
    let both = (x | y << 32).reverse_bits();
    Vec2::new(
        u32_to_f32_norm((both >> 32) as u32),
        u32_to_f32_norm(both as u32),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equals_the_crate_for_every_index() {
        for seed in [0u32, 1, 0x1234_5678, 0x9e37_79b9, u32::MAX] {
            for index in 0..1u32 << 16 {
                let p = sobol_2d(index, seed);
                assert_eq!(
                    p.x.to_bits(),
                    sobol_burley::sample(index, 0, seed).to_bits()
                );
                assert_eq!(
                    p.y.to_bits(),
                    sobol_burley::sample(index, 1, seed).to_bits()
                );
                assert_eq!(sobol_1d(index, seed).to_bits(), p.x.to_bits());
            }
        }
    }
}
