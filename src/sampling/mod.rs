//! Sampling: warps from the unit square, tabulated distributions, MIS weights and the
//! per-sample random streams. Knows nothing of scenes.

pub mod rng;
pub mod sampler;
pub mod warp;

pub use rng::Rng32;
pub use sampler::{Sampler, SamplerKind, Uniform};
