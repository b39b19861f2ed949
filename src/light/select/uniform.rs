//! Uniform light selection: i = ⌊ξ·n⌋ (lecture, many lights, solution #1).

use super::{LightSelector, Selection};
use crate::light::ShadingPoint;
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// Every light with probability 1/n.
#[derive(Clone, Debug)]
pub struct UniformSelector {
    count: usize,
}

impl UniformSelector {
    /// A selector over `count` lights.
    pub fn new(count: usize) -> UniformSelector {
        UniformSelector { count }
    }
}

impl LightSelector for UniformSelector {
    #[inline]
    fn select(&self, _at: &ShadingPoint, u: f32) -> Option<Selection> {
        if self.count == 0 {
            return None;
        }
        let n = self.count as f32;
        let index = ((u * n) as usize).min(self.count - 1);
        let u_reused = (u * n - index as f32).clamp(0.0, ONE_MINUS_EPSILON);
        Some(Selection {
            index,
            pmf: 1.0 / n,
            u_reused,
        })
    }

    #[inline]
    fn pmf(&self, _at: &ShadingPoint, index: usize) -> f32 {
        if index < self.count {
            1.0 / self.count as f32
        } else {
            0.0
        }
    }
}
