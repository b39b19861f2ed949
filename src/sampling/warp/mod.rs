//! Warps: pure functions from uniform numbers to a domain, each with its pdf (in the
//! measure its doc names) and an inverse where one exists. Partners are named
//! `square_to_x` / `x_pdf` / `x_to_square`; a sampler returns the pdf by calling the
//! pdf function, so each formula exists once.
//!
//! Rejection samplers take a [`Uniform`](crate::sampling::Uniform) source because they
//! consume a variable number of random numbers. Shapes seen from a shading point
//! ([`SphericalTriangle`], [`SphericalRectangle`]) and polygons ([`Polygon`]) are small
//! structs built once per query, since they precompute angles or a triangulation.

pub mod bilinear;
pub mod cone;
pub mod disk;
pub mod ear_clipping;
pub mod hemisphere;
pub mod parallelogram;
pub mod phong;
pub mod polygon;
pub mod projected_polygon;
pub mod sphere;
pub mod spherical_disk;
pub mod spherical_rectangle;
pub mod spherical_rectangle_fast;
pub mod spherical_rectangle_lanes;
pub mod spherical_triangle;
pub mod spherical_triangle_fast;
pub mod triangle;
pub mod xi_squared;

pub use bilinear::*;
pub use cone::*;
pub use disk::*;
pub use hemisphere::*;
pub use parallelogram::*;
pub use phong::*;
pub use polygon::*;
pub use projected_polygon::*;
pub use sphere::*;
pub use spherical_disk::*;
pub use spherical_rectangle::*;
pub use spherical_rectangle_fast::*;
pub use spherical_rectangle_lanes::*;
pub use spherical_triangle::*;
pub use spherical_triangle_fast::*;
pub use triangle::*;
pub use xi_squared::*;
