//! Geometry: rays, boxes, shapes and their intersections, and the BVH that finds them.

pub mod aabb;
pub mod bvh;
pub mod ray;
pub mod triangle;

pub use aabb::Aabb;
pub use bvh::{Bvh, TriangleSet};
pub use ray::{Ray, offset_origin};
