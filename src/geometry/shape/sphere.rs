//! Spheres.

use glam::{Vec2, Vec3};

use super::ShapeHit;
use crate::geometry::{Aabb, Ray};
use crate::math::{Frame, PI};

/// A sphere; its normal points outward.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius (> 0).
    pub radius: f32,
    /// The sphere's own axes (Mitsuba: the rotation in its `to_world`), in which its
    /// texture coordinates are measured; orthonormal.
    pub axes: Frame,
}

impl Sphere {
    /// A sphere with the world's axes.
    pub fn new(center: Vec3, radius: f32) -> Sphere {
        Sphere {
            center,
            radius,
            axes: Frame {
                s: Vec3::X,
                t: Vec3::Y,
                n: Vec3::Z,
            },
        }
    }

    /// Bounding box.
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: self.center - Vec3::splat(self.radius),
            max: self.center + Vec3::splat(self.radius),
        }
    }

    /// Surface area 4πr².
    pub fn area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    /// Outward unit normal at a surface point.
    #[inline]
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        ((p - self.center) / self.radius).normalize_or_zero()
    }

    /// Nearest intersection in (0, t_max). The discriminant is computed from the
    /// distance of the centre to the ray's line, which keeps precision for small spheres
    /// far away (Haines et al. 2019, "Precision Improvements for Ray/Sphere
    /// Intersection", Ray Tracing Gems ch. 7).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let a = ray.d.length_squared();
        let f = ray.o - self.center;
        let b = -f.dot(ray.d); // half of the usual b, negated
        let l = f + (b / a) * ray.d; // from the centre to the closest point of the line
        let disc = a * (self.radius * self.radius - l.length_squared());
        if disc < 0.0 {
            return None;
        }
        let c = f.length_squared() - self.radius * self.radius;
        let q = b + b.signum() * disc.sqrt();
        if q == 0.0 {
            return None;
        }
        let (t0, t1) = {
            let (x, y) = (c / q, q / a);
            if x < y { (x, y) } else { (y, x) }
        };
        let t = if t0 > 0.0 { t0 } else { t1 };
        if t <= 0.0 || t >= t_max {
            return None;
        }
        // Texture coordinates wait for the winning hit ([`Sphere::uv_at`]): the atan2 and
        // acos here cost 130 instructions per candidate, shadow rays included.
        Some(ShapeHit { t, uv: Vec2::ZERO })
    }

    /// Mitsuba's sphere uv at the point `p` on the sphere: u = φ/2π, v = θ/π, with θ and
    /// φ the spherical angles of the normal in the sphere's own axes.
    #[inline]
    pub fn uv_at(&self, p: Vec3) -> Vec2 {
        let n = self.axes.to_local(self.normal_at(p));
        let phi = n.y.atan2(n.x);
        Vec2::new(
            if phi < 0.0 { phi + 2.0 * PI } else { phi } / (2.0 * PI),
            n.z.clamp(-1.0, 1.0).acos() / PI,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_outside_and_inside() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, 5.0), 1.0);
        let h = s
            .intersect(&Ray::new(Vec3::ZERO, Vec3::Z), 100.0)
            .expect("hit");
        assert!((h.t - 4.0).abs() < 1e-5);
        let h = s
            .intersect(&Ray::new(s.center, Vec3::X), 100.0)
            .expect("inside hit");
        assert!((h.t - 1.0).abs() < 1e-5);
        assert!(s.intersect(&Ray::new(Vec3::ZERO, Vec3::X), 100.0).is_none());
        let tiny = Sphere::new(Vec3::new(1000.0, 0.0, 0.0), 1e-3);
        let h = tiny
            .intersect(&Ray::new(Vec3::ZERO, Vec3::X), 1e4)
            .expect("tiny far");
        assert!((h.t - (1000.0 - 1e-3)).abs() < 1e-3);
    }
}
