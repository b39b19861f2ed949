//! lightlab: a renderer and laboratory for Monte Carlo direct illumination and
//! importance sampling.
//!
//! | module | holds |
//! |---|---|
//! | [`settings`] | the strategy vocabulary: estimator, MIS, light sampling, light selection and sampler names, passes, and the typed settings patch every layer speaks |
//! | [`math`] | frames, RGB spectra, small numerics (vectors come from `glam`) |
//! | [`sampling`] | warps, tabulated distributions, samplers, random streams, chi-square tests |
//! | [`geometry`] | rays, boxes, shapes, meshes, hit records and the wide BVH |
//! | [`bsdf`] | the `Bsdf` trait (uniform default sampling), Lambertian, modified Phong, Mitsuba 3's conductors and plastics |
//! | [`light`] | area, polygon, point and environment lights with their per-shape strategies; light selection (uniform, power, adaptive, BVH) with its bounds and cones |
//! | [`image`] | film (Welford statistics), reconstruction filters, EXR/PNG/PFM io, error metrics |
//! | [`scene`] | the camera, scene builder, built-in scenes, Mitsuba XML loader, mesh and image files, textures, located errors |
//! | [`integrator`] | direct-lighting estimators (hemisphere, rejection, cosine, bsdf, light, mis) |
//! | [`render`] | render settings (defaults ← scene ← layers), the parallel tile loop |
//! | [`lab`] | experiments: references, equal-spp/equal-time comparisons, convergence plots, HTML reports, the lecture's figures, pass merging, benchmarks |
//! | [`cli`] | the command line, one file per subcommand |
//!
//! ## Layers
//!
//! Each module uses only the modules above it in this list; the arrows run one way:
//!
//! ```text
//! settings, math
//!   └─> sampling ─> geometry ─> bsdf, light ─> image ─> scene ─> integrator ─> render ─> lab ─> cli
//! ```
//!
//! So `light` reads no files (the scene loader does), `scene` names its requests in the
//! `settings` vocabulary (never the integrator's or the renderer's types), the strategy
//! reaches the lights through the estimator (never by copying the scene), `lab` drives
//! `render` with typed settings patches and never parses command lines, and `cli` only
//! parses arguments and calls the library.
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
