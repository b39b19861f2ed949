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
/// the seed alone, so where seeds repeat from sample to sample (a pixel's first
/// dimensions) they are hashed once: [`crate::sampling::sampler::PixelStreams`] holds
/// them for the chunks of points it draws.
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

/// Samples per call of [`sobol_2d_chunk`]: a chunk of a pixel's consecutive samples
/// (the camera packets' `CHUNK`).
pub const CHUNK_LANES: usize = 8;

/// [`sobol_2d_seeded`] of samples `first`, `first` + 1, … (the [`CHUNK_LANES`]
/// consecutive sample indices of one pixel) under each of `seeds` (one per dimension):
/// `points[lane][dimension]`, bit for bit the point-by-point values. Each step runs over
/// the lanes at once, the integer hashes and bit reversals as vector instructions where
/// the processor has AVX2 (detected at run time), else for the target's baseline. One
/// 2D point by itself is a chain of about 70 dependent integer steps (the 64-bit
/// reversal alone is a dozen on x86-64, which has no instruction for it); eight side by
/// side share those steps. Indices at or past 2¹⁶ give values no sampler uses.
#[inline]
pub fn sobol_2d_chunk<const D: usize>(
    first: u32,
    seeds: &[SobolSeed; D],
) -> [[Vec2; D]; CHUNK_LANES] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2, checked just above.
        return unsafe { chunk_avx2(first, seeds) };
    }
    chunk_lanes(first, seeds)
}

/// Whether [`sobol_2d_chunk`] runs in AVX2 lanes on this processor (where it does not,
/// its lanes cost what as many single points cost).
#[inline]
pub fn chunk_is_wide() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// [`chunk_lanes`] in AVX2 registers of eight u32 lanes: the hashes as vector
/// multiplies, the table reads as gathers, each 32-bit reversal as two nibble-table
/// shuffles and a byte swap.
///
/// # Safety
///
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn chunk_avx2<const D: usize>(
    first: u32,
    seeds: &[SobolSeed; D],
) -> [[Vec2; D]; CHUNK_LANES] {
    use std::arch::x86_64::*;
    let t = tables();
    let splat = |v: u32| _mm256_set1_epi32(v as i32);
    // sobol_burley's owen_scramble_rev, lane by lane.
    let owen = |n: __m256i, scramble: u32| {
        let n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, splat(0x3d20_adea)));
        let n = _mm256_add_epi32(n, splat(scramble));
        let n = _mm256_mullo_epi32(n, splat((scramble >> 16) | 1));
        let n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, splat(0x0552_6c56)));
        _mm256_xor_si256(n, _mm256_mullo_epi32(n, splat(0x53a2_2864)))
    };
    // The four bits of a nibble reversed, placed low (`low`) or high (`high`).
    let low = _mm256_setr_epi8(
        0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15, //
        0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15,
    );
    let high = _mm256_slli_epi16::<4>(low);
    let swap = _mm256_setr_epi8(
        3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, //
        3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12,
    );
    let reverse = |n: __m256i| {
        let nib = splat(0x0f0f_0f0f);
        let lo = _mm256_and_si256(n, nib);
        let hi = _mm256_and_si256(_mm256_srli_epi32::<4>(n), nib);
        let bytes = _mm256_or_si256(_mm256_shuffle_epi8(high, lo), _mm256_shuffle_epi8(low, hi));
        _mm256_shuffle_epi8(bytes, swap)
    };
    // u32_to_f32_norm: the top 23 bits as the mantissa of a number in [1, 2), minus 1.
    let unit = |n: __m256i| {
        let bits = _mm256_or_si256(_mm256_srli_epi32::<9>(n), splat(0x3f80_0000));
        _mm256_sub_ps(_mm256_castsi256_ps(bits), _mm256_set1_ps(1.0))
    };
    let index = _mm256_add_epi32(splat(first), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    let rev = reverse(index);
    let mut points = [[Vec2::ZERO; D]; CHUNK_LANES];
    for (d, seed) in seeds.iter().enumerate() {
        let shuffled = owen(rev, seed.shuffle);
        let hi = _mm256_srli_epi32::<24>(shuffled);
        let lo = _mm256_and_si256(_mm256_srli_epi32::<16>(shuffled), splat(0xff));
        let axis = |k: usize| {
            // SAFETY: every index is a byte (0..256), within the 256-entry tables.
            let (h, l) = unsafe {
                (
                    _mm256_i32gather_epi32::<4>(t.high[k].as_ptr().cast(), hi),
                    _mm256_i32gather_epi32::<4>(t.low[k].as_ptr().cast(), lo),
                )
            };
            unit(reverse(owen(_mm256_xor_si256(h, l), seed.scramble[k])))
        };
        let (mut x, mut y) = ([0.0f32; CHUNK_LANES], [0.0f32; CHUNK_LANES]);
        // SAFETY: both arrays hold eight f32, an unaligned store's width.
        unsafe {
            _mm256_storeu_ps(x.as_mut_ptr(), axis(0));
            _mm256_storeu_ps(y.as_mut_ptr(), axis(1));
        }
        for (l, point) in points.iter_mut().enumerate() {
            point[d] = Vec2::new(x[l], y[l]);
        }
    }
    points
}

/// [`sobol_2d_chunk`]'s body: [`sobol_2d_seeded`]'s steps, each over every lane. The
/// two dimensions are reversed by two 32-bit reversals (the single-point version's
/// 64-bit reversal swaps and reverses them: the same bits).
#[inline(always)]
fn chunk_lanes<const D: usize>(first: u32, seeds: &[SobolSeed; D]) -> [[Vec2; D]; CHUNK_LANES] {
    type Lanes = [u32; CHUNK_LANES];
    let t = tables();
    let rev: Lanes = std::array::from_fn(|l| first.wrapping_add(l as u32).reverse_bits());
    let mut points = [[Vec2::ZERO; D]; CHUNK_LANES];
    for (d, seed) in seeds.iter().enumerate() {
        let shuffled: Lanes = std::array::from_fn(|l| owen_scramble_rev(rev[l], seed.shuffle));
        let axis = |k: usize| -> Lanes {
            let sobol: Lanes = std::array::from_fn(|l| {
                let (high, low) = (shuffled[l] >> 24, (shuffled[l] >> 16) & 0xff);
                t.high[k][high as usize] ^ t.low[k][low as usize]
            });
            std::array::from_fn(|l| owen_scramble_rev(sobol[l], seed.scramble[k]).reverse_bits())
        };
        let (x, y) = (axis(0), axis(1));
        for (l, point) in points.iter_mut().enumerate() {
            point[d] = Vec2::new(u32_to_f32_norm(x[l]), u32_to_f32_norm(y[l]));
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chunk_is_its_points_one_by_one() {
        let seeds: [SobolSeed; 5] =
            std::array::from_fn(|d| SobolSeed::new(0x9e37_79b9u32.wrapping_mul(d as u32 + 3)));
        for first in (0..1u32 << 16).step_by(8).chain([3, 13, 65_529]) {
            let check = |chunk: [[Vec2; 5]; CHUNK_LANES]| {
                for (l, points) in chunk.iter().enumerate() {
                    let index_rev = (first + l as u32).reverse_bits();
                    if first + l as u32 >= 1 << 16 {
                        continue;
                    }
                    for (d, p) in points.iter().enumerate() {
                        let q = sobol_2d_seeded(index_rev, &seeds[d]);
                        let bits = |v: Vec2| (v.x.to_bits(), v.y.to_bits());
                        assert_eq!(bits(*p), bits(q), "first {first} lane {l} dimension {d}");
                    }
                }
            };
            check(sobol_2d_chunk(first, &seeds));
            check(chunk_lanes(first, &seeds));
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the processor has AVX2, checked just above.
                check(unsafe { chunk_avx2(first, &seeds) });
            }
        }
    }

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
