//! Division of 32-bit integers by a divisor fixed in advance, by one multiplication
//! instead of a `div` instruction (Lemire, Kaser & Kurz 2019, "Faster remainder by
//! direct computation", Theorem 1 with N = 32, F = 64): with c = ⌈2⁶⁴ / d⌉, the
//! quotient ⌊a / d⌋ is the high 64 bits of c·a for every 32-bit a. The stratified
//! sampler divides by the same few numbers (its sample count, its row widths) in every
//! dimension of every sample.

/// A divisor d ≥ 1 with its multiplier; the quotients and remainders are exactly
/// those of `/` and `%`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Divisor {
    d: u32,
    /// ⌈2⁶⁴ / d⌉ (mod 2⁶⁴: 0 for d = 1, whose quotient is taken apart).
    c: u64,
}

impl Divisor {
    /// One.
    pub const ONE: Divisor = Divisor { d: 1, c: 0 };

    /// The divisor `d`; `d` must not be zero.
    pub fn new(d: u32) -> Divisor {
        assert!(d > 0, "division by zero");
        Divisor {
            d,
            c: (u64::MAX / d as u64).wrapping_add(1),
        }
    }

    /// The divisor.
    #[inline(always)]
    pub fn get(&self) -> u32 {
        self.d
    }

    /// ⌊a / d⌋.
    #[inline(always)]
    pub fn quotient(&self, a: u32) -> u32 {
        if self.d == 1 {
            a
        } else {
            ((self.c as u128 * a as u128) >> 64) as u32
        }
    }

    /// (⌊a / d⌋, a mod d).
    #[inline(always)]
    pub fn div_rem(&self, a: u32) -> (u32, u32) {
        let q = self.quotient(a);
        (q, a - q * self.d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng32;

    fn check(a: u32, d: u32) {
        assert_eq!(Divisor::new(d).div_rem(a), (a / d, a % d), "{a} / {d}");
    }

    #[test]
    fn quotients_and_remainders_are_exact() {
        let edges = [
            0u32,
            1,
            2,
            3,
            5,
            7,
            63,
            64,
            65,
            1000,
            1 << 16,
            (1 << 31) - 1,
        ];
        let edges = edges
            .iter()
            .flat_map(|&e| [e, e.wrapping_neg(), u32::MAX - e]);
        let edges: Vec<u32> = edges.collect();
        for &d in edges.iter().filter(|&&d| d > 0) {
            for &a in &edges {
                check(a, d);
            }
            // Around multiples of d, where a wrong quotient shows first.
            for k in [1u32, 2, 3, u32::MAX / d] {
                let m = k.wrapping_mul(d);
                for a in [m.wrapping_sub(1), m, m.wrapping_add(1)] {
                    check(a, d);
                }
            }
        }
        let mut rng = Rng32::new(7);
        for _ in 0..200_000 {
            let d = rng.next_u32() >> (rng.next_u32() % 32);
            check(rng.next_u32(), d.max(1));
        }
        for d in 1..=4096 {
            for a in 0..2 * d + 3 {
                check(a, d);
            }
        }
    }

    #[test]
    #[should_panic(expected = "division by zero")]
    fn zero_is_refused() {
        Divisor::new(0);
    }
}
