//! Geometry: rays, boxes, shapes and their intersections, meshes, hit records, and the
//! BVH that finds the closest hit.

pub mod aabb;
pub mod bvh;
pub mod flat;
pub mod hit;
pub mod leaf_blocks;
pub mod mesh;
pub mod ray;
pub mod scene_geometry;
pub mod shape;
pub mod triangle;
pub mod triangle4;

pub use aabb::Aabb;
pub use bvh::{Bvh, TriangleSet};
pub use hit::{NO_LIGHT, SurfaceHit};
pub use mesh::Mesh;
pub use ray::{Ray, offset_origin};
pub use scene_geometry::{Along, Geometry, Primitive};
pub use shape::Shape;
