//! lightlab: a renderer and laboratory for Monte Carlo direct illumination and
//! importance sampling.
//!
//! | module | holds |
//! |---|---|
//! | [`math`] | frames, RGB spectra, small numerics (vectors come from `glam`) |
//! | [`sampling`] | warps, tabulated distributions, samplers, random streams, chi-square tests |
//! | [`geometry`] | rays, boxes, shapes, hit records and the BVH |
//! | [`lab`] | experiments: variance tables, warp plots |
//! | [`cli`] | one file per subcommand |
#![warn(missing_docs)]

pub mod cli;
pub mod geometry;
pub mod lab;
pub mod math;
pub mod sampling;
pub mod bsdf;
pub mod cli;
pub mod image;
pub mod integrator;
pub mod light;
pub mod render;
pub mod scene;
