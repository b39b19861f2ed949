//! Disks.

use glam::{Vec2, Vec3};

use super::ShapeHit;
use crate::geometry::{Aabb, Ray};
use crate::math::{Frame, PI};

/// A disk of radius `radius` around `center`, front side `normal`.
#[derive(Clone, Copy, Debug)]
pub struct Disk {
    /// Centre.
    pub center: Vec3,
    /// Unit normal (front side).
    pub normal: Vec3,
    /// Radius.
    pub radius: f32,
    /// Unit vectors in the disk's plane along which the texture angle φ is 0 and π/2
    /// (Mitsuba: the to_world images of local x and y).
    pub axes: [Vec3; 2],
}

impl Disk {
    /// A disk whose texture angle starts at an arbitrary tangent (for disks built in
    /// code; scene files give [`Disk::axes`]).
    pub fn new(center: Vec3, normal: Vec3, radius: f32) -> Disk {
        let f = Frame::from_normal(normal);
        Disk {
            center,
            normal,
            radius,
            axes: [f.s, f.t],
        }
    }

    /// Bounding box (tight per axis: extent r·√(1 − n_i²)).
    pub fn bounds(&self) -> Aabb {
        let e = self.radius
            * (Vec3::ONE - self.normal * self.normal)
                .max(Vec3::ZERO)
                .powf(0.5);
        Aabb {
            min: self.center - e,
            max: self.center + e,
        }
    }

    /// Area πr².
    pub fn area(&self) -> f32 {
        PI * self.radius * self.radius
    }

    /// The local frame (normal on +z).
    pub fn frame(&self) -> Frame {
        Frame::from_normal(self.normal)
    }

    /// Nearest intersection in (0, t_max); both sides count.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let denom = ray.d.dot(self.normal);
        if denom == 0.0 {
            return None;
        }
        let t = (self.center - ray.o).dot(self.normal) / denom;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let q = ray.at(t) - self.center;
        if q.length_squared() > self.radius * self.radius {
            return None;
        }
        // Texture coordinates wait for the winning hit ([`Disk::uv_at`]).
        Some(ShapeHit { t, uv: Vec2::ZERO })
    }

    /// uv = (r/R, φ/2π) at the point `p` on the disk.
    #[inline]
    pub fn uv_at(&self, p: Vec3) -> Vec2 {
        let q = p - self.center;
        let phi = q.dot(self.axes[1]).atan2(q.dot(self.axes[0]));
        let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
        Vec2::new(q.length() / self.radius, phi / (2.0 * PI))
    }
}
