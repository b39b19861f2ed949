//! Random streams: a PCG32 generator and the hashes that derive one stream per
//! (seed, pixel, sample index), so renders repeat exactly for any thread count.

use rand_core::Rng;
use rand_pcg::Pcg32;

/// 64-bit finaliser of MurmurHash3 (Appleby): a bijective avalanche mix.
#[inline]
pub fn mix64(mut x: u64) -> u64 {
    x ^= x >> 33;
    x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
    x ^= x >> 33;
    x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    x ^ (x >> 33)
}

/// 2⁶⁴ / φ, odd: the constant [`hash_words`] starts from and adds to every word.
const GOLDEN_GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// The state [`hash_words`] starts from.
pub const HASH_START: u64 = GOLDEN_GAMMA;

/// Hashes a list of integers into one 64-bit key (order matters).
#[inline]
pub fn hash_words(words: &[u64]) -> u64 {
    words.iter().fold(HASH_START, |h, &w| hash_more(h, w))
}

/// One step of [`hash_words`]: the state `h` after one more word `w`, so that a key
/// shared by many hashes (a pixel's, before its sample indices) is folded in once:
/// `hash_words(&[a, b]) == hash_more(hash_more(HASH_START, a), b)`.
#[inline(always)]
pub fn hash_more(h: u64, w: u64) -> u64 {
    mix64(h ^ w.wrapping_add(GOLDEN_GAMMA).wrapping_add(h << 6))
}

/// Hashes `bytes` into a 64-bit key, continuing from `h`: 8-byte little-endian words
/// folded by [`mix64`], then the length (so trailing zero bytes change the key). For
/// telling contents apart, not against an adversary.
pub fn hash_bytes(mut h: u64, bytes: &[u8]) -> u64 {
    let mut chunks = bytes.chunks_exact(8);
    let fold =
        |h: u64, w: [u8; 8]| mix64(h ^ u64::from_le_bytes(w)).wrapping_add(0x9e37_79b9_7f4a_7c15);
    for c in &mut chunks {
        let mut w = [0u8; 8];
        w.copy_from_slice(c);
        h = fold(h, w);
    }
    let mut tail = [0u8; 8];
    tail[..chunks.remainder().len()].copy_from_slice(chunks.remainder());
    h = fold(h, tail);
    mix64(h ^ bytes.len() as u64)
}

/// A PCG32 stream (O'Neill 2014) producing uniform numbers in [0, 1).
#[derive(Clone, Debug)]
pub struct Rng32 {
    pcg: Pcg32,
}

impl Rng32 {
    /// A stream selected by `key`: state and stream increment both derive from it.
    pub fn new(key: u64) -> Rng32 {
        Rng32 {
            pcg: Pcg32::new(mix64(key), mix64(key ^ 0xda3e_39cb_94b9_5bdb)),
        }
    }

    /// A fixed stream, for samplers that never draw from it (no hashing).
    #[inline]
    pub fn unused() -> Rng32 {
        Rng32 {
            pcg: Pcg32::new(0, 0),
        }
    }

    /// A uniform 32-bit integer.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        self.pcg.next_u32()
    }

    /// A uniform float in [0, 1): the top 24 bits scaled by 2⁻²⁴, so 1.0 never occurs.
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_are_in_unit_interval_and_streams_differ() {
        let mut a = Rng32::new(1);
        let mut b = Rng32::new(2);
        let mut same = 0;
        for _ in 0..10_000 {
            let (x, y) = (a.next_f32(), b.next_f32());
            assert!((0.0..1.0).contains(&x));
            same += (x == y) as u32;
        }
        assert!(same < 5);
    }

    #[test]
    fn byte_hashes_tell_contents_lengths_and_seeds_apart() {
        let keys = [
            hash_bytes(0, b""),
            hash_bytes(0, b"\0"),
            hash_bytes(0, b"\0\0\0\0\0\0\0\0"),
            hash_bytes(0, b"scene"),
            hash_bytes(0, b"scenf"),
            hash_bytes(1, b"scene"),
        ];
        for (i, a) in keys.iter().enumerate() {
            for b in &keys[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert_eq!(hash_bytes(3, b"same"), hash_bytes(3, b"same"));
    }
}
