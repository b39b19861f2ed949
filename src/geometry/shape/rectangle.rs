//! Rectangles: a corner and two perpendicular edges (the lecture's a, b − a, d − a).

use glam::{Vec2, Vec3};

use super::ShapeHit;
use crate::geometry::{Aabb, Ray};

/// A rectangle { o + α·ea + β·eb : α, β ∈ [0, 1] } with ea ⟂ eb; (α, β) are its texture
/// coordinates. Its front side is `normal`: ea × eb / |ea × eb|, or the opposite for a
/// [`Rectangle::flipped`] one.
#[derive(Clone, Copy, Debug)]
pub struct Rectangle {
    /// Corner (the lecture's a).
    pub o: Vec3,
    /// First edge (b − a).
    pub ea: Vec3,
    /// Second edge (d − a).
    pub eb: Vec3,
    /// Unit normal.
    pub normal: Vec3,
}

impl Rectangle {
    /// A rectangle from a corner and two edges; `None` when the edges are degenerate or
    /// not perpendicular (to 1e-3 relative).
    pub fn new(o: Vec3, ea: Vec3, eb: Vec3) -> Option<Rectangle> {
        let n = ea.cross(eb);
        let len = n.length();
        let perpendicular = ea.dot(eb).abs() <= 1e-3 * ea.length() * eb.length();
        (len > 0.0 && len.is_finite() && perpendicular).then(|| Rectangle {
            o,
            ea,
            eb,
            normal: n / len,
        })
    }

    /// The same rectangle with its front side reversed, keeping the edges (and so the
    /// texture coordinates) as they are.
    pub fn flipped(self) -> Rectangle {
        Rectangle {
            normal: -self.normal,
            ..self
        }
    }

    /// The four corners a, b, c, d in order.
    pub fn corners(&self) -> [Vec3; 4] {
        [
            self.o,
            self.o + self.ea,
            self.o + self.ea + self.eb,
            self.o + self.eb,
        ]
    }

    /// Bounding box.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.corners())
    }

    /// Area |ea × eb|.
    pub fn area(&self) -> f32 {
        self.ea.cross(self.eb).length()
    }

    /// The point at parameters (α, β).
    #[inline]
    pub fn point(&self, uv: Vec2) -> Vec3 {
        self.o + uv.x * self.ea + uv.y * self.eb
    }

    /// The parameters (α, β) of the point `p` of the rectangle's plane (its texture
    /// coordinates).
    #[inline]
    pub fn uv_at(&self, p: Vec3) -> Vec2 {
        let q = p - self.o;
        Vec2::new(
            q.dot(self.ea) / self.ea.length_squared(),
            q.dot(self.eb) / self.eb.length_squared(),
        )
    }

    /// Nearest intersection in (0, t_max); both sides count.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let denom = ray.d.dot(self.normal);
        if denom == 0.0 {
            return None;
        }
        let t = (self.o - ray.o).dot(self.normal) / denom;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let uv = self.uv_at(ray.at(t));
        ((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)).then_some(ShapeHit { t, uv })
    }
}
