//! One level of the light tree's descent (Conty Estevez & Kulla 2018, §4.1): at a 4-wide
//! node, choose the child whose interval of the importance CDF holds the walk's random
//! number, rescale the number into that interval, and multiply the choice's probability
//! into the walk's.
//!
//! The choice is the lecture's tabulated PDF with one random number reused ("CDF +
//! search"), over four entries: of the children with probability `p_l = I_l / ΣI` that
//! is positive, in lane order, the first whose running sum exceeds `u`, else the last
//! positive one (where rounding leaves `u` past every interval). Two ways to find it,
//! with the same result bit for bit (the table test below and the tests of `bvh::lanes`
//! compare them):
//! [`Search::Linear`], the lecture's loop, for one walk at a time, where the branch
//! predictor runs ahead into the next level; and [`Search::Masked`], one SIMD division
//! and two comparisons turned into bit masks, for walks interleaved with each other
//! (`bvh::lanes`), where a mispredicted branch on `u` would throw away the other walks'
//! work begun after it. On `mesh_ply_serialized` the loop made the interleaved walks'
//! render 10 % slower than the masks, and the masks the single walk's 5 % slower than
//! the loop (BENCHMARKS.md, session 38).

use glam::Vec4;

use super::wide::{LANES, WideNode};
use crate::light::select::Selection;
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// Where a selection stands in the tree: the node it is at, its random number, and the
/// probability of the choices that led there.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Walk {
    pub node: u32,
    pub u: f32,
    pub pmf: f32,
}

impl Walk {
    /// A walk from the root with random number `u`.
    #[inline(always)]
    pub fn from_root(u: f32) -> Walk {
        Walk {
            node: 0,
            u: u.clamp(0.0, ONE_MINUS_EPSILON),
            pmf: 1.0,
        }
    }
}

/// How [`descend`] finds the chosen child (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Search {
    /// A loop over the lanes that stops at the first interval holding `u`.
    Linear,
    /// Bit masks of the positive lanes and of the running sums above `u`.
    Masked,
}

/// What one level of the descent leads to.
pub(super) enum Step {
    /// An inner node, one level down.
    Inner(Walk),
    /// A light: the selection.
    Light(Selection),
    /// No child can contribute: no light.
    Dead,
}

/// The sum of a node's importances when some child can contribute (a usable number).
#[inline(always)]
pub(super) fn usable_total(importance: &[f32; LANES]) -> Option<f32> {
    let total = (importance[0] + importance[1]) + (importance[2] + importance[3]);
    // Two comparisons rather than `is_finite`, which LLVM merged with the first into a
    // test on the bits: 1.6 M fewer instructions in 210 M on `mesh_ply_serialized` at
    // 16 spp (callgrind; BENCHMARKS.md, session 38).
    (total > 0.0 && total < f32::INFINITY).then_some(total)
}

/// One level of the descent of `walk` at `node`, whose children have importances
/// `importance` at the shading point, choosing the child with `search` (see the module
/// doc).
#[inline(always)]
pub(super) fn descend(
    node: &WideNode,
    importance: &[f32; LANES],
    walk: Walk,
    search: Search,
) -> Step {
    let Some(total) = usable_total(importance) else {
        return Step::Dead;
    };
    let (lane, below, p) = match search {
        Search::Linear => linear(importance, total, walk.u),
        Search::Masked => masked(importance, total, walk.u),
    };
    let u = ((walk.u - below) / p).clamp(0.0, ONE_MINUS_EPSILON);
    let pmf = walk.pmf * p;
    let child = node.child[lane];
    if node.leaf[lane] {
        Step::Light(Selection {
            index: child as usize,
            pmf,
            u_reused: u,
        })
    } else {
        Step::Inner(Walk {
            node: child,
            u,
            pmf,
        })
    }
}

/// The chosen lane, the probabilities below it and its own, by the lecture's loop.
#[inline(always)]
fn linear(importance: &[f32; LANES], total: f32, u: f32) -> (usize, f32, f32) {
    let mut chosen = (0, 0.0f32, 0.0f32);
    let mut below = 0.0f32;
    for (lane, &imp) in importance.iter().enumerate() {
        let p = imp / total;
        if p > 0.0 {
            chosen = (lane, below, p);
            if u < below + p {
                break;
            }
            below += p;
        }
    }
    chosen
}

/// [`linear`]'s result by bit masks, with no branch on `u`.
#[inline(always)]
fn masked(importance: &[f32; LANES], total: f32, u: f32) -> (usize, f32, f32) {
    let p = Vec4::from_array(*importance) / Vec4::splat(total);
    let [p0, p1, p2, p3] = p.to_array();
    // The running sums, added in lane order as a sequential search adds them (adding a
    // lane's zero leaves a sum as it is).
    let upto0 = 0.0 + p0;
    let upto1 = upto0 + p1;
    let upto2 = upto1 + p2;
    let upto3 = upto2 + p3;
    let positive = p.cmpgt(Vec4::ZERO).bitmask();
    let within = Vec4::new(upto0, upto1, upto2, upto3)
        .cmpgt(Vec4::splat(u))
        .bitmask();
    let holding = positive & within;
    let lane = if holding != 0 {
        holding.trailing_zeros()
    } else {
        // No interval holds u: the last positive lane (lane 0 if none is, which a
        // usable total rules out: its largest share is at least a quarter; `linear`
        // would then give lane 0 with p = 0 as well).
        31 - (positive | 1).leading_zeros()
    } as usize
        & (LANES - 1);
    let below = [0.0, upto0, upto1, upto2][lane];
    (lane, below, p.to_array()[lane])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two searches give the same lane, probability below it and its own, bit for
    /// bit, at every boundary: importances of zero, the least subnormal, ordinary and
    /// huge sizes in every pattern of four lanes (shares that underflow to zero, zeros
    /// between positive lanes), with u at 0, 0.5, the largest number below 1, NaN, and
    /// at each running sum and one float either side of it; the fallback past every
    /// interval is reached, by rounding and by NaN.
    #[test]
    fn both_searches_choose_alike_at_every_boundary() {
        let sizes = [0.0, 1e-45, 1.0, 3.0, 1e30];
        let (mut cases, mut past) = (0, 0);
        for code in 0..sizes.len().pow(LANES as u32) {
            let importance: [f32; LANES] =
                std::array::from_fn(|l| sizes[code / sizes.len().pow(l as u32) % sizes.len()]);
            let Some(total) = usable_total(&importance) else {
                continue;
            };
            let mut us = vec![0.0, 0.5, ONE_MINUS_EPSILON, f32::NAN];
            let mut sum = 0.0f32;
            for i in importance {
                sum += i / total;
                us.extend([sum.next_down(), sum, sum.next_up()]);
            }
            for u in us {
                // A walk's number is clamped to [0, 1) (NaN stays NaN).
                let u = u.clamp(0.0, ONE_MINUS_EPSILON);
                let bits =
                    |(lane, below, p): (usize, f32, f32)| (lane, below.to_bits(), p.to_bits());
                assert_eq!(
                    bits(linear(&importance, total, u)),
                    bits(masked(&importance, total, u)),
                    "importances {importance:?}, u {u:e}"
                );
                cases += 1;
                // Past every interval: u at or above the last sum, or NaN.
                past += (u >= sum || u.is_nan()) as u32;
            }
        }
        assert!(cases > 5_000, "{cases} cases");
        assert!(past > 500, "{past} numbers past every interval");
    }
}
