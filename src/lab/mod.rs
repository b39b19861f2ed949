//! Experiments: the lecture's 1D variance demo and warp plots; throughput benchmarks;
//! references, equal-spp and equal-time comparisons, convergence plots, the HTML report,
//! the lecture's figures, and the merge of render passes. The lab drives `render`, never
//! the reverse.

pub mod bench;
pub mod budget;
pub mod compare;
pub mod converge;
mod error;
pub mod experiment;
pub mod figure;
pub mod insets;
pub mod merge;
pub mod plot;
pub mod probe;
pub mod reference;
pub mod report;
pub mod strategy;
pub mod variance_1d;
pub mod warp_plot;

pub use error::LabError;
