//! Render passes: the share of a render's samples one process computes (`--pass I/N`).

use std::fmt;
use std::str::FromStr;

/// The share of the samples a render computes: pass `index` of `count` (1-based in the
/// CLI as `I/N`, stored 0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pass {
    /// 0-based pass index.
    pub index: u32,
    /// Number of passes.
    pub count: u32,
}

impl Pass {
    /// The whole render.
    pub const WHOLE: Pass = Pass { index: 0, count: 1 };

    /// Sample indices [first, last) of this pass out of `spp`: the same indices (and so
    /// the same random streams) a single render would use for them.
    pub fn sample_range(&self, spp: u32) -> (u32, u32) {
        let split = |i: u32| ((spp as u64 * i as u64) / self.count as u64) as u32;
        (split(self.index), split(self.index + 1))
    }
}

impl fmt::Display for Pass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index + 1, self.count)
    }
}

impl FromStr for Pass {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let err = || format!("bad pass \"{s}\": expected I/N with 1 ≤ I ≤ N, e.g. 2/8");
        let (i, n) = s.split_once('/').ok_or_else(err)?;
        let (i, n): (u32, u32) = (
            i.trim().parse().map_err(|_| err())?,
            n.trim().parse().map_err(|_| err())?,
        );
        if i == 0 || n == 0 || i > n {
            return Err(err());
        }
        Ok(Pass {
            index: i - 1,
            count: n,
        })
    }
}

/// A block of samples a render computed: sample indices `first..last` of every pixel
/// under seed `seed`. Two blocks hold the same random numbers exactly when their seeds
/// are equal and their ranges overlap, so a merge may combine blocks that are disjoint
/// under every seed. Written `seed:first..last`, e.g. `0:16..32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleBlock {
    /// The render's seed.
    pub seed: u64,
    /// First sample index.
    pub first: u32,
    /// One past the last sample index.
    pub last: u32,
}

impl SampleBlock {
    /// True when both blocks hold some of the same samples.
    pub fn overlaps(&self, o: &SampleBlock) -> bool {
        self.seed == o.seed && self.first < o.last && o.first < self.last
    }
}

impl fmt::Display for SampleBlock {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}..{}", self.seed, self.first, self.last)
    }
}

impl FromStr for SampleBlock {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let err = || format!("bad sample block \"{s}\": expected SEED:FIRST..LAST, e.g. 0:16..32");
        let (seed, range) = s.split_once(':').ok_or_else(err)?;
        let (first, last) = range.split_once("..").ok_or_else(err)?;
        let block = SampleBlock {
            seed: seed.parse().map_err(|_| err())?,
            first: first.parse().map_err(|_| err())?,
            last: last.parse().map_err(|_| err())?,
        };
        if block.first > block.last {
            return Err(err());
        }
        Ok(block)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_partition_the_samples() {
        let spp = 37;
        let mut next = 0;
        for i in 0..5 {
            let (a, b) = Pass { index: i, count: 5 }.sample_range(spp);
            assert_eq!(a, next);
            next = b;
        }
        assert_eq!(next, spp);
        assert_eq!("2/8".parse::<Pass>().unwrap(), Pass { index: 1, count: 8 });
        for bad in ["0/3", "4/3", "x", "1/0"] {
            assert!(bad.parse::<Pass>().is_err());
        }
    }

    #[test]
    fn sample_blocks_round_trip_and_overlap_only_under_one_seed() {
        let a: SampleBlock = "7:0..16".parse().unwrap();
        assert_eq!(a.to_string(), "7:0..16");
        let b: SampleBlock = "7:16..32".parse().unwrap();
        let c: SampleBlock = "7:8..9".parse().unwrap();
        let d: SampleBlock = "8:0..16".parse().unwrap();
        assert!(!a.overlaps(&b) && a.overlaps(&c) && c.overlaps(&a) && !a.overlaps(&d));
        for bad in ["7", "7:3", "x:0..1", "1:5..2", "1:0..-1"] {
            assert!(bad.parse::<SampleBlock>().is_err(), "{bad}");
        }
    }
}
