//! Per-point adaptive selection (lecture, many lights, solution #3): at every shading
//! point, estimate each light's unoccluded contribution and choose lights in proportion,
//! mixed with a floor so that a light that can contribute is never given probability
//! zero ("be careful not to underestimate the contribution as zero"). O(n) per
//! selection and per `pmf`: the reference strategy, not a fast one.

use super::{LightSelector, Selection};
use crate::light::{Light, LightBounds, ShadingPoint};
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// Share of the probability spread by the conservative bound (the floor).
pub const ADAPTIVE_FLOOR: f64 = 0.1;

/// p_i = (1 − α)·e_i/Σe + α·m_i/Σm, with e_i = [`Light::contribution_estimate`] and
/// m_i = [`LightBounds::importance`] (zero only for a light that cannot reach the
/// point), α = [`ADAPTIVE_FLOOR`]. When every estimate is zero, p_i = m_i/Σm.
#[derive(Clone, Debug)]
pub struct AdaptiveSelector {
    lights: Vec<(Light, LightBounds)>,
    /// Lights left out (probability zero), by index; empty when none is.
    excluded: Vec<bool>,
}

/// Σe and Σm at a shading point.
#[derive(Clone, Copy, Debug)]
struct Sums {
    estimate: f64,
    bound: f64,
}

impl Sums {
    /// The normalisation of [`Sums::weight`]: Σ_i weight_i up to rounding.
    fn total(&self) -> f64 {
        if self.estimate > 0.0 {
            self.estimate * self.bound
        } else {
            self.bound
        }
    }

    /// The unnormalised mixture weight (1 − α)·e·Σm + α·m·Σe (or m when Σe = 0).
    fn weight(&self, e: f64, m: f64) -> f64 {
        if self.estimate > 0.0 {
            (1.0 - ADAPTIVE_FLOOR) * e * self.bound + ADAPTIVE_FLOOR * m * self.estimate
        } else {
            m
        }
    }
}

impl AdaptiveSelector {
    /// A selector over `lights` (cloned: it evaluates them per point).
    pub fn new(lights: &[Light]) -> AdaptiveSelector {
        AdaptiveSelector {
            lights: lights.iter().map(|l| (l.clone(), l.bounds())).collect(),
            excluded: Vec::new(),
        }
    }

    /// The same selector giving the lights marked in `excluded` probability zero.
    pub fn excluding(mut self, excluded: &[bool]) -> AdaptiveSelector {
        self.excluded = excluded.to_vec();
        self
    }

    /// (e_i, m_i) of light `i` at `at`.
    #[inline]
    fn terms(&self, i: usize, at: &ShadingPoint) -> (f64, f64) {
        if self.excluded.get(i) == Some(&true) {
            return (0.0, 0.0);
        }
        let (light, bounds) = &self.lights[i];
        let estimate = light.contribution_estimate(at) as f64;
        // A light at infinity has no spatial bound: its estimate is its own floor.
        let bound = if light.is_infinite() {
            estimate
        } else {
            bounds.importance(at) as f64
        };
        (estimate, bound)
    }

    /// Σe and Σm at `at`.
    fn sums(&self, at: &ShadingPoint) -> Sums {
        let mut s = Sums {
            estimate: 0.0,
            bound: 0.0,
        };
        for i in 0..self.lights.len() {
            let (e, m) = self.terms(i, at);
            s.estimate += e;
            s.bound += m;
        }
        s
    }
}

impl LightSelector for AdaptiveSelector {
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection> {
        let sums = self.sums(at);
        let total = sums.total();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        // Walk the implicit CDF: the first light whose interval [c, c + w) holds u·total.
        let target = u.clamp(0.0, ONE_MINUS_EPSILON) as f64 * total;
        let mut c = 0.0;
        let mut last = None;
        for i in 0..self.lights.len() {
            let (e, m) = self.terms(i, at);
            let w = sums.weight(e, m);
            if w <= 0.0 {
                continue;
            }
            last = Some((i, w, c));
            if target < c + w {
                break;
            }
            c += w;
        }
        // Rounding can leave u·total just past the last interval: take the last light.
        let (index, w, c) = last?;
        Some(Selection {
            index,
            pmf: (w / total) as f32,
            u_reused: (((target - c) / w) as f32).clamp(0.0, ONE_MINUS_EPSILON),
        })
    }

    fn pmf(&self, at: &ShadingPoint, index: usize) -> f32 {
        if index >= self.lights.len() {
            return 0.0;
        }
        let sums = self.sums(at);
        let total = sums.total();
        if !(total > 0.0 && total.is_finite()) {
            return 0.0;
        }
        let (e, m) = self.terms(index, at);
        let w = sums.weight(e, m);
        if w <= 0.0 { 0.0 } else { (w / total) as f32 }
    }
}
