//! Experiments from the lecture: variance tables, warp plots, throughput benchmarks.

pub mod bench;
pub mod variance_1d;
pub mod warp_plot;
