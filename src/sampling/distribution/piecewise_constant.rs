//! The lecture's "stacked rectangles": a piecewise-constant pdf on [0, 1) with n equal
//! bins, sampled by binary search in its CDF (pbrt-v4 §A.4.1, `PiecewiseConstant1D`).

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
        Ok(PiecewiseConstant1D {
            weights: weights.to_vec(),
            cdf,
            integral: (total / n as f64) as f32,
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
    /// [cdf_i, cdf_{i+1}) holds `u` (binary search; zero-weight bins have empty
    /// intervals and are never chosen). Returns (index, pmf, u rescaled to [0, 1) within
    /// the chosen interval, so it can be used again).
    pub fn sample_discrete(&self, u: f32) -> (usize, f32, f32) {
        let u = u.clamp(0.0, ONE_MINUS_EPSILON);
        // partition_point: number of CDF entries ≤ u among cdf[1..]; that is the bin.
        let index = self.cdf[1..]
            .partition_point(|&c| c <= u)
            .min(self.len() - 1);
        let (lo, hi) = (self.cdf[index], self.cdf[index + 1]);
        let u_reused = if hi > lo {
            ((u - lo) / (hi - lo)).clamp(0.0, ONE_MINUS_EPSILON)
        } else {
            0.0
        };
        (index, hi - lo, u_reused)
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
