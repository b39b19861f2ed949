//! Rays and the offset that keeps secondary rays off the surface they leave.

use glam::Vec3;

/// A ray o + t·d for t in (0, t_max). `d` need not be unit length.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Origin.
    pub o: Vec3,
    /// Direction.
    pub d: Vec3,
}

impl Ray {
    /// A ray from `o` along `d`.
    #[inline]
    pub fn new(o: Vec3, d: Vec3) -> Ray {
        Ray { o, d }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

/// Moves a surface point off its surface along the geometric normal `ng`, on the side
/// of `w` (the direction the new ray leaves in), by an amount that grows with the
/// magnitude of the point's coordinates: float error in a computed hit point is relative
/// to its coordinates (after Wächter & Binder 2019, "A Fast and Robust Method for
/// Avoiding Self-Intersection", Ray Tracing Gems ch. 6, which scales the offset the
/// same way).
#[inline]
pub fn offset_origin(p: Vec3, ng: Vec3, w: Vec3) -> Vec3 {
    let scale = 1e-4 * (1.0 + p.abs().max_element());
    let offset = ng * scale;
    if w.dot(ng) >= 0.0 {
        p + offset
    } else {
        p - offset
    }
}
