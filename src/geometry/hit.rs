//! Surface hits: everything shading needs at the point a ray found.

use glam::{Vec2, Vec3};

use crate::math::Frame;

/// Marker for "no light" in [`SurfaceHit::light`] and in primitives.
pub const NO_LIGHT: u32 = u32::MAX;

/// A ray's closest surface hit.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// Hit point.
    pub p: Vec3,
    /// Ray parameter.
    pub t: f32,
    /// Geometric normal (unit, the shape's front side).
    pub ng: Vec3,
    /// Shading frame; `frame.n` is the shading normal, on the same side as `ng`.
    pub frame: Frame,
    /// The shape's hit parameters ([`ShapeHit::uv`](crate::geometry::shape::ShapeHit::uv): a
    /// triangle's barycentrics b1, b2, a rectangle's (u, v), zero on spheres and disks).
    /// Texture coordinates cost an `atan2` or two on curved shapes, so only a textured
    /// material asks for them ([`Geometry::texture_uv`](crate::geometry::Geometry::texture_uv)).
    pub shape_uv: Vec2,
    /// Index of the primitive in the scene geometry.
    pub prim: u32,
    /// Material index.
    pub material: u32,
    /// Index of the light this surface emits as, or [`NO_LIGHT`].
    pub light: u32,
}
