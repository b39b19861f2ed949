//! Ray–triangle intersection.

use glam::Vec3;

use super::Ray;

/// A hit on a triangle: ray parameter and barycentrics (b1, b2) of vertices 1 and 2.
#[derive(Clone, Copy, Debug)]
pub struct TriangleHit {
    /// Ray parameter.
    pub t: f32,
    /// Barycentric weight of vertex 1.
    pub b1: f32,
    /// Barycentric weight of vertex 2.
    pub b2: f32,
}

/// Intersects `ray` with the triangle (p0, p0 + e1, p0 + e2) for t in (t_min, t_max)
/// (Möller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection").
/// Both sides count.
#[inline(always)]
pub fn intersect_triangle(
    ray: &Ray,
    p0: Vec3,
    e1: Vec3,
    e2: Vec3,
    t_max: f32,
) -> Option<TriangleHit> {
    let p = ray.d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = ray.o - p0;
    let b1 = s.dot(p) * inv_det;
    if !(0.0..=1.0).contains(&b1) {
        return None;
    }
    let q = s.cross(e1);
    let b2 = ray.d.dot(q) * inv_det;
    if b2 < 0.0 || b1 + b2 > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv_det;
    if t > 0.0 && t < t_max {
        Some(TriangleHit { t, b1, b2 })
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_and_misses_outside() {
        let (p0, e1, e2) = (Vec3::ZERO, Vec3::X, Vec3::Y);
        let down = Vec3::new(0.0, 0.0, -1.0);
        let hit = intersect_triangle(&Ray::new(Vec3::new(0.2, 0.3, 1.0), down), p0, e1, e2, 10.0);
        let hit = hit.expect("hit");
        assert!(
            (hit.t - 1.0).abs() < 1e-6
                && (hit.b1 - 0.2).abs() < 1e-6
                && (hit.b2 - 0.3).abs() < 1e-6
        );
        assert!(
            intersect_triangle(&Ray::new(Vec3::new(0.8, 0.8, 1.0), down), p0, e1, e2, 10.0)
                .is_none()
        );
        assert!(
            intersect_triangle(&Ray::new(Vec3::new(0.2, 0.3, 1.0), down), p0, e1, e2, 0.5)
                .is_none()
        );
    }
}
