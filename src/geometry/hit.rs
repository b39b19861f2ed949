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
    /// Texture coordinates.
    pub uv: Vec2,
    /// Index of the primitive in the scene geometry.
    pub prim: u32,
    /// Material index.
    pub material: u32,
    /// Index of the light this surface emits as, or [`NO_LIGHT`].
    pub light: u32,
}
