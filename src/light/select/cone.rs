//! Cones of directions: the normal cones of light bounds and the cone of directions a
//! box subtends from a point (Conty Estevez & Kulla 2018, "Importance Sampling of Many
//! Lights with Adaptive Tree Splitting"; the same construction as pbrt-v4's
//! `DirectionCone`, §3.8.4 and §12.6.3).

use glam::Vec3;

use crate::geometry::Aabb;
use crate::math::safe_sqrt;

/// Merged cones are widened by this angle (radians) so that rounding in the union never
/// makes a cone miss a direction one of its parts holds (a light that can contribute
/// must never get importance 0).
const UNION_PADDING: f32 = 1e-3;

/// The directions within angle θ of the unit axis `w`, stored as cos θ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionCone {
    /// Unit axis.
    pub w: Vec3,
    /// cos θ of the half-angle θ (−1: the whole sphere).
    pub cos_theta: f32,
}

impl DirectionCone {
    /// Every direction.
    pub const ENTIRE_SPHERE: DirectionCone = DirectionCone {
        w: Vec3::Z,
        cos_theta: -1.0,
    };

    /// The single direction `w` (normalised).
    pub fn direction(w: Vec3) -> DirectionCone {
        DirectionCone {
            w: w.normalize_or(Vec3::Z),
            cos_theta: 1.0,
        }
    }

    /// The smallest cone (axis in the plane of both axes) holding both cones:
    /// θ_o = (θ_a + θ_d + θ_b)/2, axis rotated from a's by θ_o − θ_a towards b's.
    pub fn union(self, b: DirectionCone) -> DirectionCone {
        let a = self;
        // A cone of every direction holds the other: what the tests below conclude for
        // it, without their three `acos` (most unions of a large light BVH's build, where
        // clusters soon face every way).
        if a.cos_theta <= -1.0 {
            return a;
        }
        if b.cos_theta <= -1.0 {
            return b;
        }
        let theta_a = a.cos_theta.clamp(-1.0, 1.0).acos();
        let theta_b = b.cos_theta.clamp(-1.0, 1.0).acos();
        let theta_d = a.w.dot(b.w).clamp(-1.0, 1.0).acos();
        let pi = std::f32::consts::PI;
        if (theta_d + theta_b).min(pi) <= theta_a {
            return a;
        }
        if (theta_d + theta_a).min(pi) <= theta_b {
            return b;
        }
        let theta_o = 0.5 * (theta_a + theta_d + theta_b) + UNION_PADDING;
        if theta_o >= pi {
            return DirectionCone::ENTIRE_SPHERE;
        }
        let k = a.w.cross(b.w);
        let len = k.length();
        if len == 0.0 || !len.is_finite() {
            return DirectionCone::ENTIRE_SPHERE;
        }
        // Rodrigues' rotation of a.w about k/|k| (a.w ⟂ k) by θ_r = θ_o − θ_a.
        let theta_r = theta_o - theta_a;
        let w = a.w * theta_r.cos() + (k / len).cross(a.w) * theta_r.sin();
        DirectionCone {
            w: w.normalize_or(a.w),
            cos_theta: theta_o.cos(),
        }
    }
}

/// The cone of directions from `p` towards the bounding sphere of `b`: axis towards its
/// centre, sin²θ = r²/d²; the whole sphere when `p` is inside it.
pub fn bound_subtended_directions(b: &Aabb, p: Vec3) -> DirectionCone {
    let center = b.centroid();
    let radius2 = (0.5 * b.extent()).length_squared();
    let d = center - p;
    let dist2 = d.length_squared();
    if dist2 <= radius2 || dist2 == 0.0 {
        return DirectionCone::ENTIRE_SPHERE;
    }
    let sin2 = radius2 / dist2;
    DirectionCone {
        w: d / dist2.sqrt(),
        cos_theta: safe_sqrt(1.0 - sin2),
    }
}

/// cos(θ_a − θ_b) clamped to 1 when θ_a ≤ θ_b (the angle cannot go below zero), from
/// the sines and cosines of both angles.
#[inline]
pub fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// sin(θ_a − θ_b) clamped to 0 when θ_a ≤ θ_b.
#[inline]
pub fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contains(c: &DirectionCone, w: Vec3) -> bool {
        c.w.dot(w.normalize()) >= c.cos_theta - 1e-5
    }

    #[test]
    fn union_holds_both_cones() {
        let cases = [
            (Vec3::Z, 1.0, Vec3::X, 1.0),
            (Vec3::Z, 0.9, Vec3::new(0.3, 0.2, 0.9), 0.99),
            (Vec3::Z, 0.0, -Vec3::Z, 0.5),
            (Vec3::Y, 1.0, Vec3::Y, 1.0),
            (
                Vec3::new(1.0, 1.0, 0.0),
                0.7,
                Vec3::new(-1.0, 0.2, 0.1),
                0.95,
            ),
            (Vec3::Z, -1.0, Vec3::X, 0.5),
            (Vec3::X, 0.3, Vec3::Y, -1.0),
        ];
        for (wa, ca, wb, cb) in cases {
            let a = DirectionCone {
                w: wa.normalize(),
                cos_theta: ca,
            };
            let b = DirectionCone {
                w: wb.normalize(),
                cos_theta: cb,
            };
            let u = a.union(b);
            assert!(u.cos_theta.is_finite() && u.w.is_finite());
            assert!(ca > -1.0 && cb > -1.0 || u.cos_theta == -1.0, "{u:?}");
            // Both axes and the rims of both cones towards each other lie inside.
            for c in [a, b] {
                assert!(contains(&u, c.w), "{u:?} misses axis of {c:?}");
                let perp = c.w.any_orthonormal_vector();
                for k in 0..16 {
                    let phi = k as f32 * std::f32::consts::TAU / 16.0;
                    let t = perp * phi.cos() + c.w.cross(perp) * phi.sin();
                    let s = safe_sqrt(1.0 - c.cos_theta * c.cos_theta);
                    let rim = c.w * c.cos_theta + t * s;
                    assert!(contains(&u, rim), "{u:?} misses rim {rim} of {c:?}");
                }
            }
        }
    }

    #[test]
    fn subtended_cone_holds_the_box() {
        let b = Aabb {
            min: Vec3::new(1.0, 2.0, 3.0),
            max: Vec3::new(2.0, 2.5, 3.1),
        };
        let p = Vec3::new(-1.0, 0.0, 0.5);
        let c = bound_subtended_directions(&b, p);
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            assert!(contains(&c, corner - p));
        }
        let inside = bound_subtended_directions(&b, b.centroid());
        assert_eq!(inside.cos_theta, -1.0);
    }
}
