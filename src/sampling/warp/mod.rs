//! Warps: pure functions from uniform numbers to a domain, each with its pdf (in the
//! measure its doc names) and an inverse where one exists. Partners are named
//! `square_to_x` / `x_pdf` / `x_to_square`; a sampler returns the pdf by calling the
//! pdf function, so each formula exists once.
//!
//! Rejection samplers take a [`Uniform`](crate::sampling::Uniform) source because they
//! consume a variable number of random numbers.

pub mod disk;
pub mod hemisphere;
pub mod phong;
pub mod sphere;

pub use disk::*;
pub use hemisphere::*;
pub use phong::*;
pub use sphere::*;
