//! lightlab: a renderer and laboratory for Monte Carlo direct illumination and
//! importance sampling.
//!
//! | module | holds |
//! |---|---|
//! | [`math`] | frames, RGB spectra, small numerics (vectors come from `glam`) |
//! | [`sampling`] | warps, tabulated distributions, samplers, random streams, chi-square tests |
//! | [`geometry`] | rays, boxes, shapes, meshes, hit records and the wide BVH |
//! | [`bsdf`] | the `Bsdf` trait (uniform default sampling), Lambertian, modified Phong |
//! | [`light`] | area and point lights, area/solid-angle conversion, light bounds, light selection (uniform, power, adaptive, BVH) |
//! | [`integrator`] | direct-lighting estimators (hemisphere, rejection, cosine, bsdf, light) |
//! | [`render`] | camera, render settings, parallel tile loop |
//! | [`image`] | film (Welford statistics), EXR/PNG/PFM io, error metrics |
//! | [`scene`] | scene builder, built-in scenes, Mitsuba XML loader, mesh files, textures, located errors |
//! | [`lab`] | experiments: references, equal-spp/equal-time comparisons, convergence plots, HTML reports, the lecture's figures, pass merging |
//! | [`cli`] | the command line, one file per subcommand |
#![warn(missing_docs)]

#[macro_use]
mod names;

pub mod bsdf;
pub mod cli;
pub mod geometry;
pub mod image;
pub mod integrator;
pub mod lab;
pub mod light;
pub mod math;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod settings;
