//! Sampling: warps from the unit square, tabulated distributions and the per-sample
//! random streams (MIS weights live with the `mis` estimator), plus the chi-square machinery that checks every sampler
//! against its pdf and the registry of named warps that tests and the CLI share.
//! Knows nothing of scenes.

pub mod chi2;
pub mod distribution;
pub mod registry;
pub mod rng;
pub mod sampler;
pub mod sobol;
pub mod warp;

pub use rng::Rng32;
pub use sampler::{Sampler, SamplerKind, Uniform};
