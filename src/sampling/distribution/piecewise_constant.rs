//! The lecture's "stacked rectangles": a piecewise-constant pdf on [0, 1) with n equal
//! bins, sampled by binary search in its CDF (pbrt-v4 §A.4.1, `PiecewiseConstant1D`).
//! A guide table (Chen & Asau 1974, "On generating random variates from an empirical
//! distribution", AIIE Transactions 6(2)) narrows the search to the few CDF entries in
//! u's stretch of [0, 1); the bin found is the plain search's.

use glam::Vec2;

use super::{DistributionError, check_weights};
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// A piecewise-constant density on [0, 1) with `n` equal bins whose heights are
/// proportional to the given weights. All-zero weights give the uniform density
/// (and [`PiecewiseConstant1D::integral`] returns 0 so callers can tell).
#[derive(Clone, Debug)]
pub struct PiecewiseConstant1D {
    /// Weights as given.
    weights: Vec<f32>,
    /// cdf[i] = Σ_{j<i} w_j / Σ w; cdf[0] = 0, cdf[n] = 1 exactly.
    cdf: Vec<f32>,
    /// Σ w_j / n: the integral of the unnormalised step function over [0, 1).
    integral: f32,
    /// The guide table: for k = 0..=G (G a power of two), the number of entries of
    /// cdf[1..] that are ≤ k/G. A u in [k/G, (k+1)/G) has its bin between guide[k] and
    /// guide[k + 1]; G ≥ n (up to n = 2²⁴), so that stretch holds one CDF entry on average.
    guide: Vec<u32>,
}

impl PiecewiseConstant1D {
    /// The distribution of `weights` (one per bin); an error for an empty table or a
    /// negative or non-finite weight.
    pub fn new(weights: &[f32]) -> Result<Self, DistributionError> {
        check_weights(weights)?;
        let n = weights.len();
        let total: f64 = weights.iter().map(|&w| w as f64).sum();
        // Uniform fallback for an all-zero table: every bin weighs one.
        let (weight_of, denominator): (fn(f32) -> f64, f64) = if total > 0.0 {
            (|w| w as f64, total)
        } else {
            (|_| 1.0, n as f64)
        };
        let mut cdf = Vec::with_capacity(n + 1);
        let mut running = 0.0f64;
        cdf.push(0.0);
        for (i, &w) in weights.iter().enumerate() {
            running += weight_of(w);
            cdf.push(if i + 1 == n {
                1.0
            } else {
                (running / denominator) as f32
            });
        }
        let guide = guide_table(&cdf);
        Ok(PiecewiseConstant1D {
            weights: weights.to_vec(),
            cdf,
            integral: (total / n as f64) as f32,
            guide,
        })
    }

    /// Number of bins.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Always false: a distribution has at least one bin.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// ∫₀¹ of the unnormalised step function (mean weight); 0 for an all-zero table.
    pub fn integral(&self) -> f32 {
        self.integral
    }

    /// The probability of bin `index` (0 outside the table).
    pub fn pmf(&self, index: usize) -> f32 {
        if index >= self.len() {
            0.0
        } else {
            self.cdf[index + 1] - self.cdf[index]
        }
    }

    /// Density at x ∈ [0, 1) per unit length: n·pmf(bin of x); 0 outside [0, 1).
    pub fn pdf(&self, x: f32) -> f32 {
        if !(0.0..1.0).contains(&x) {
            return 0.0;
        }
        self.pmf(self.bin_of(x)) * self.len() as f32
    }

    /// The bin containing x ∈ [0, 1).
    fn bin_of(&self, x: f32) -> usize {
        ((x * self.len() as f32) as usize).min(self.len() - 1)
    }

    /// Picks a bin by one uniform number: the first bin whose CDF interval
    /// [cdf_i, cdf_{i+1}) holds `u` (binary search, narrowed by the guide table;
    /// zero-weight bins have empty intervals and are never chosen). Returns (index, pmf,
    /// u rescaled to [0, 1) within the chosen interval, so it can be used again).
    #[inline]
    pub fn sample_discrete(&self, u: f32) -> (usize, f32, f32) {
        let u = u.clamp(0.0, ONE_MINUS_EPSILON);
        let index = self.guided_search(u).min(self.len() - 1);
        let (lo, hi) = (self.cdf[index], self.cdf[index + 1]);
        let u_reused = if hi > lo {
            ((u - lo) / (hi - lo)).clamp(0.0, ONE_MINUS_EPSILON)
        } else {
            0.0
        };
        (index, hi - lo, u_reused)
    }

    /// The number of entries of cdf[1..] that are ≤ `u`, by binary search over the
    /// whole CDF (the lecture's version).
    #[inline]
    fn search(&self, u: f32) -> usize {
        self.cdf[1..].partition_point(|&c| c <= u)
    }

    /// [`Self::search`] of `u` ∈ [0, 1) (or NaN), searching only between the guide
    /// table's bounds for u's stretch: k/G ≤ u < (k+1)/G holds exactly for k = ⌊u·G⌋
    /// because G is a power of two (u·G is exact), so guide[k] ≤ count ≤ guide[k + 1].
    #[inline]
    fn guided_search(&self, u: f32) -> usize {
        let g = self.guide.len() - 1;
        let k = (u * g as f32) as usize;
        if k >= g || u.is_nan() {
            return self.search(u);
        }
        let (lo, hi) = (self.guide[k] as usize, self.guide[k + 1] as usize);
        lo + self.cdf[1 + lo..1 + hi].partition_point(|&c| c <= u)
    }

    /// The lecture's two-number variant: u₀ picks the rectangle, u₁ places x uniformly
    /// inside it. Returns (x, pdf per unit length).
    pub fn sample_two(&self, u: Vec2) -> (f32, f32) {
        let (index, pmf, _) = self.sample_discrete(u.x);
        (
            point_in_bin(index, u.y, self.len()),
            pmf * self.len() as f32,
        )
    }

    /// The continuous inversion x = P⁻¹(u) of the piecewise-linear CDF. This is also
    /// the lecture's one-number variant: u picks the rectangle, and its position inside
    /// the rectangle's CDF interval places x. Returns (x, pdf per unit length).
    ///
    /// ```
    /// use lightlab::sampling::distribution::PiecewiseConstant1D;
    /// let d = PiecewiseConstant1D::new(&[1.0, 0.0, 3.0]).unwrap();
    /// let (x, pdf) = d.sample_continuous(0.5);
    /// assert!(x >= 2.0 / 3.0 && (pdf - 2.25).abs() < 1e-6);
    /// ```
    pub fn sample_continuous(&self, u: f32) -> (f32, f32) {
        let (index, pmf, u_reused) = self.sample_discrete(u);
        (
            point_in_bin(index, u_reused, self.len()),
            pmf * self.len() as f32,
        )
    }

    /// The CDF P(x), the inverse of [`PiecewiseConstant1D::sample_continuous`].
    pub fn cdf(&self, x: f32) -> f32 {
        let x = x.clamp(0.0, 1.0);
        let index = self.bin_of(x.min(ONE_MINUS_EPSILON));
        let t = x * self.len() as f32 - index as f32;
        self.cdf[index] + t * self.pmf(index)
    }
}

/// The guide table of `cdf` (see [`PiecewiseConstant1D`]'s `guide`): G + 1 counts, G
/// the power of two at or above the number of bins (at most 2²⁴, so that k/G is exact).
fn guide_table(cdf: &[f32]) -> Vec<u32> {
    let bins = cdf.len() - 1;
    let g = bins.next_power_of_two().min(1 << 24);
    let mut guide = Vec::with_capacity(g + 1);
    let mut count = 0;
    for k in 0..=g {
        let bound = k as f32 / g as f32;
        while count < bins && cdf[1 + count] <= bound {
            count += 1;
        }
        guide.push(count as u32);
    }
    guide
}

/// The point at fraction `t` ∈ [0, 1) of bin `index` of `n` equal bins of [0, 1):
/// (index + t)/n, stepped down if rounding carried it into the next bin, so that
/// ⌊x·n⌋ = index always holds in f32.
pub fn point_in_bin(index: usize, t: f32, n: usize) -> f32 {
    let mut x = ((index as f32 + t) / n as f32).min(ONE_MINUS_EPSILON);
    while x > 0.0 && (x * n as f32) as usize > index {
        x = f32::from_bits(x.to_bits() - 1);
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The guided search finds the plain search's bin for every u that matters: each
    /// CDF entry and its neighbouring floats, the stretch bounds k/G and theirs, and a
    /// sweep, on tables with zero bins, ties and uneven weights.
    #[test]
    fn guide_finds_the_searched_bin() {
        let mut rng = crate::sampling::Rng32::new(5);
        let tables: Vec<Vec<f32>> = vec![
            vec![1.0],
            vec![0.0, 0.0, 1.0],
            vec![0.0, 2.0, 0.0, 0.0, 1.0, 0.0],
            vec![1e-30, 1.0, 1e-30, 1e-30, 3.0],
            (0..1000).map(|i| ((i * 7919) % 13) as f32).collect(),
            (0..33).map(|_| rng.next_f32().powi(8)).collect(),
            vec![0.0; 17],
        ];
        let near = |x: f32| {
            let b = x.to_bits();
            [
                f32::from_bits(b.saturating_sub(1)),
                x,
                f32::from_bits(b + 1),
            ]
        };
        for weights in &tables {
            let d = PiecewiseConstant1D::new(weights).expect("valid");
            let g = d.guide.len() - 1;
            assert!(g >= d.len() && g.is_power_of_two());
            let mut us: Vec<f32> = d.cdf.iter().flat_map(|&c| near(c)).collect();
            us.extend((0..=g).flat_map(|k| near(k as f32 / g as f32)));
            us.extend((0..10_000).map(|i| i as f32 / 10_000.0));
            us.extend((0..10_000).map(|_| rng.next_f32()));
            for u in us {
                let u = u.clamp(0.0, ONE_MINUS_EPSILON);
                assert_eq!(d.guided_search(u), d.search(u), "u = {u} of {weights:?}");
            }
            assert_eq!(d.guided_search(f32::NAN), d.search(f32::NAN));
        }
    }

    #[test]
    fn zero_bins_are_never_chosen() {
        let d = PiecewiseConstant1D::new(&[0.0, 2.0, 0.0, 0.0, 1.0, 0.0]).expect("valid");
        for i in 0..=1000 {
            let u = i as f32 / 1000.0;
            let (index, pmf, u_reused) = d.sample_discrete(u);
            assert!(
                pmf > 0.0 && (0.0..1.0).contains(&u_reused),
                "u = {u}: bin {index}"
            );
            let (x, pdf) = d.sample_continuous(u);
            assert!(pdf > 0.0 && (d.cdf(x) - u.min(ONE_MINUS_EPSILON)).abs() < 1e-5);
        }
    }

    #[test]
    fn points_never_round_into_the_next_bin() {
        for n in [3usize, 7, 10, 1000] {
            for index in 0..n {
                let x = point_in_bin(index, ONE_MINUS_EPSILON, n);
                assert_eq!((x * n as f32) as usize, index, "n = {n}");
            }
        }
    }

    #[test]
    fn all_zero_is_uniform_and_bad_weights_are_errors() {
        let d = PiecewiseConstant1D::new(&[0.0; 4]).expect("uniform fallback");
        assert_eq!(d.integral(), 0.0);
        assert_eq!(d.sample_continuous(0.3), (0.3, 1.0));
        assert!(PiecewiseConstant1D::new(&[]).is_err());
        assert!(PiecewiseConstant1D::new(&[1.0, -1.0]).is_err());
        assert!(PiecewiseConstant1D::new(&[1.0, f32::NAN]).is_err());
    }
}
