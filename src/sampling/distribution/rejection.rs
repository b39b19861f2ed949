//! Rejection sampling of a 1D density under a constant bound (the lecture's "box around
//! the graph of p": draw points in the box, keep those under the curve).

use crate::sampling::Uniform;

/// Samples a normalised density p on [min, max) given a bound M ≥ sup p. Each try costs
/// two uniform numbers and succeeds with probability 1/(M·(max − min)).
#[derive(Clone, Copy, Debug)]
pub struct RejectionSampler {
    /// Lower end of the support.
    pub min: f32,
    /// Upper end of the support.
    pub max: f32,
    /// M: an upper bound of p on [min, max).
    pub bound: f32,
    /// Tries before giving up (the expected count is M·(max − min)).
    pub max_tries: u32,
}

impl RejectionSampler {
    /// Draws x ∝ p by rejection. Returns (x, p(x) per unit length), or `None` when
    /// `max_tries` points all fell above the curve. A point where p exceeds the bound
    /// (the bound was wrong, so the result would be biased) also gives `None` in
    /// release builds and panics in debug builds.
    ///
    /// ```
    /// use lightlab::sampling::{Rng32, distribution::RejectionSampler};
    /// let s = RejectionSampler { min: 0.0, max: 1.0, bound: 2.0, max_tries: 100 };
    /// let (x, pdf) = s.sample(|x| 2.0 * x, &mut Rng32::new(1)).unwrap();
    /// assert!((pdf - 2.0 * x).abs() < 1e-6);
    /// ```
    pub fn sample(&self, p: impl Fn(f32) -> f32, src: &mut impl Uniform) -> Option<(f32, f32)> {
        for _ in 0..self.max_tries {
            let u = src.next_2d();
            let x = self.min + u.x * (self.max - self.min);
            let px = p(x);
            debug_assert!(
                px <= self.bound,
                "p({x}) = {px} exceeds the bound {}",
                self.bound
            );
            if px.is_nan() || px > self.bound {
                return None;
            }
            if u.y * self.bound < px {
                return Some((x, px));
            }
        }
        None
    }
}
