//! The lecture's 1D observation: the smoother the integrand relative to the sampling
//! density, the lower the variance. Estimates ∫₀^{π/2} cos x dx = 1 and
//! ∫₀^{π/2} 4cos¹⁶x dx = 4·(15!!/16!!)·π/2 with uniform samples, with p = cos x (by
//! inversion, x = asin u), and with a 32-bin tabulated copy of each integrand.

use std::f64::consts::FRAC_PI_2;

use crate::sampling::Rng32;
use crate::sampling::distribution::PiecewiseConstant1D;

/// One estimate: integrand, strategy, the mean of f/p, the per-sample variance of f/p,
/// and the exact value.
#[derive(Clone, Debug)]
pub struct VarianceRow {
    /// Integrand name.
    pub integrand: &'static str,
    /// Sampling strategy name.
    pub strategy: &'static str,
    /// Monte Carlo estimate (mean of f(x)/p(x)).
    pub estimate: f64,
    /// Per-sample variance of f(x)/p(x); the estimate's variance is this over `samples`.
    pub variance: f64,
    /// The exact integral.
    pub exact: f64,
    /// Number of samples.
    pub samples: usize,
}

impl VarianceRow {
    /// Standard error of the estimate: √(variance / samples).
    pub fn standard_error(&self) -> f64 {
        (self.variance / self.samples as f64).sqrt()
    }
}

/// ∫₀^{π/2} 4cos¹⁶x dx = 4 · (15!!/16!!) · π/2 (Wallis).
pub fn exact_cos16() -> f64 {
    let ratio: f64 = (1..=8)
        .map(|k| (2 * k - 1) as f64 / (2 * k) as f64)
        .product();
    4.0 * ratio * FRAC_PI_2
}

/// An integrand: name, f, and its exact integral over [0, π/2).
type Integrand = (&'static str, fn(f64) -> f64, f64);

/// A sampler of [0, π/2): a uniform number to (x, p(x)).
type Strategy = Box<dyn Fn(f32) -> (f64, f64)>;

/// The strategies for integrand `f`: uniform, p = cos x, and a 32-bin table of f.
fn strategies(f: fn(f64) -> f64) -> Vec<(&'static str, Strategy)> {
    let bins: Vec<f32> = (0..32)
        .map(|i| f((i as f64 + 0.5) / 32.0 * FRAC_PI_2) as f32)
        .collect();
    let table = PiecewiseConstant1D::new(&bins).ok();
    vec![
        (
            "uniform",
            Box::new(|u: f32| (u as f64 * FRAC_PI_2, 1.0 / FRAC_PI_2)),
        ),
        (
            "cosine (x = asin u)",
            Box::new(|u: f32| ((u as f64).asin(), (u as f64).asin().cos())),
        ),
        (
            "tabulated (32 bins)",
            Box::new(move |u: f32| match &table {
                Some(t) => {
                    let (x, pdf) = t.sample_continuous(u);
                    (x as f64 * FRAC_PI_2, pdf as f64 / FRAC_PI_2)
                }
                None => (u as f64 * FRAC_PI_2, 1.0 / FRAC_PI_2),
            }),
        ),
    ]
}

/// The table: both integrands under every strategy, `samples` samples each, from `seed`.
pub fn variance_table(samples: usize, seed: u64) -> Vec<VarianceRow> {
    let integrands: [Integrand; 2] = [
        ("cos x", f64::cos, 1.0),
        ("4 cos^16 x", |x| 4.0 * x.cos().powi(16), exact_cos16()),
    ];
    let mut rows = Vec::new();
    for (k, (integrand, f, exact)) in integrands.into_iter().enumerate() {
        for (s, (strategy, draw)) in strategies(f).into_iter().enumerate() {
            let mut rng = Rng32::new(seed ^ ((k * 16 + s) as u64));
            // Welford's running mean and variance of f/p.
            let (mut mean, mut m2) = (0.0f64, 0.0f64);
            for i in 0..samples {
                let (x, p) = draw(rng.next_f32());
                let value = if p > 0.0 { f(x) / p } else { 0.0 };
                let delta = value - mean;
                mean += delta / (i + 1) as f64;
                m2 += delta * (value - mean);
            }
            let variance = if samples > 1 {
                m2 / (samples - 1) as f64
            } else {
                0.0
            };
            rows.push(VarianceRow {
                integrand,
                strategy,
                estimate: mean,
                variance,
                exact,
                samples,
            });
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_are_within_four_standard_errors() {
        assert!((exact_cos16() - 4.0 * 6435.0 / 32768.0 * FRAC_PI_2).abs() < 1e-12);
        for row in variance_table(100_000, 7) {
            let bound = 4.0 * row.standard_error() + 1e-9;
            assert!((row.estimate - row.exact).abs() <= bound, "{row:?}");
        }
    }
}
