//! Experiments from the lecture: variance tables and warp plots.

pub mod variance_1d;
pub mod warp_plot;
