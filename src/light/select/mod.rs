//! Choosing one light among many (lecture: "we can unite all light sources to a single
//! large one"): a selector draws a light with a probability and hands back the random
//! number rescaled, so the same number can be used again.

mod uniform;

pub use uniform::UniformSelector;

use super::ShadingPoint;

/// A chosen light, its probability, and `u` rescaled to [0, 1) so it can be used again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Selection {
    /// Light index.
    pub index: usize,
    /// Probability of choosing it.
    pub pmf: f32,
    /// The random number, rescaled within the chosen light's interval.
    pub u_reused: f32,
}

/// Picks lights. `select` and `pmf` must agree exactly.
pub trait LightSelector {
    /// Chooses a light for shading point `at` with uniform number `u`.
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection>;
    /// Probability that `select` chooses light `index` at `at`.
    fn pmf(&self, at: &ShadingPoint, index: usize) -> f32;
}

named_enum! {
    /// Light selection strategy, by CLI name.
    pub enum LightSelect: "light selection" {
        /// i = ⌊ξ·n⌋ (lecture solution #1).
        Uniform => "uniform",
    }
}

/// The scene's selector (closed set, one `match`).
#[derive(Clone, Debug)]
pub enum Selector {
    /// Uniform choice.
    Uniform(UniformSelector),
}

impl Selector {
    /// Builds the selector `kind` over lights with the given powers.
    pub fn new(kind: LightSelect, powers: &[f32]) -> Selector {
        match kind {
            LightSelect::Uniform => Selector::Uniform(UniformSelector::new(powers.len())),
        }
    }
}

impl LightSelector for Selector {
    #[inline]
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection> {
        match self {
            Selector::Uniform(s) => s.select(at, u),
        }
    }

    #[inline]
    fn pmf(&self, at: &ShadingPoint, index: usize) -> f32 {
        match self {
            Selector::Uniform(s) => s.pmf(at, index),
        }
    }
}
