//! lightlab: a renderer and laboratory for Monte Carlo direct illumination and
//! importance sampling.
//!
//! | module | holds |
//! |---|---|
//! | [`math`] | frames, RGB spectra, small numerics (vectors come from `glam`) |
//! | [`sampling`] | warps, tabulated distributions, samplers and random streams |
//! | [`geometry`] | rays, boxes, shapes, hit records and the BVH |
#![warn(missing_docs)]

pub mod geometry;
pub mod math;
pub mod sampling;
pub mod bsdf;
pub mod cli;
pub mod image;
pub mod integrator;
pub mod light;
pub mod render;
pub mod scene;
