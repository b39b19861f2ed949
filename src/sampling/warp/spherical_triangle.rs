//! Directions uniform in the solid angle a triangle subtends at a shading point (Arvo
//! 1995, "Stratified Sampling of Spherical Triangles", SIGGRAPH), with the inverse map
//! (the idea of pbrt-v4's `InvertSphericalTriangleSample`) and the solid angle by Van
//! Oosterom & Strackee (1983, "The Solid Angle of a Plane Triangle", IEEE TBME 30(2)).
//!
//! All internal arithmetic is in f64, which keeps Arvo's formulas accurate down to
//! [`MIN_SOLID_ANGLE`]; below it (or for a shading point in the triangle's plane) the
//! constructor returns `None` and the caller should sample the area instead.

use glam::{DVec3, Vec2, Vec3};

/// Smallest solid angle (sr) sampled by the spherical triangle and rectangle warps: about
/// a 3·10⁻⁴ rad wide shape, where f32 directions still resolve it to ~10⁻³ of its size.
pub const MIN_SOLID_ANGLE: f64 = 1e-7;

/// Solid angle of the spherical triangle with unit vertices a, b, c (Van Oosterom &
/// Strackee): Ω = 2·atan2(|a·(b×c)|, 1 + a·b + b·c + c·a).
pub fn spherical_triangle_solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    2.0 * a
        .dot(b.cross(c))
        .abs()
        .atan2(1.0 + a.dot(b) + b.dot(c) + c.dot(a))
}

/// The angle between two vectors, accurate near 0 and π.
pub(crate) fn angle_between(x: DVec3, y: DVec3) -> f64 {
    x.cross(y).length().atan2(x.dot(y))
}

/// A triangle seen from a shading point, ready for uniform solid-angle sampling.
#[derive(Clone, Copy, Debug)]
pub struct SphericalTriangle {
    /// Unit directions from the shading point to the vertices.
    a: DVec3,
    b: DVec3,
    c: DVec3,
    /// Ω, the solid angle.
    solid_angle: f64,
    /// α, the spherical angle at vertex a.
    alpha: f64,
}

impl SphericalTriangle {
    /// The triangle (v0, v1, v2) seen from `p` (world space), or `None` if its solid angle
    /// is below [`MIN_SOLID_ANGLE`] or any input is non-finite.
    pub fn new(p: Vec3, v0: Vec3, v1: Vec3, v2: Vec3) -> Option<SphericalTriangle> {
        let dir = |v: Vec3| (v.as_dvec3() - p.as_dvec3()).try_normalize();
        let (a, b, c) = (dir(v0)?, dir(v1)?, dir(v2)?);
        let solid_angle = spherical_triangle_solid_angle(a, b, c);
        if !(solid_angle >= MIN_SOLID_ANGLE && solid_angle.is_finite()) {
            return None;
        }
        // α: dihedral angle at a between the planes (a, b) and (a, c).
        let alpha = angle_between(a.cross(b), a.cross(c));
        Some(SphericalTriangle {
            a,
            b,
            c,
            solid_angle,
            alpha,
        })
    }

    /// Ω in steradians.
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// A unit direction uniform in the triangle's solid angle and its density 1/Ω per sr
    /// (Arvo 1995, Fig. 2): u₀ fixes the sub-triangle (a, b, c′) of area u₀Ω, u₁ places
    /// the direction on the arc from b to c′ by its cosine.
    ///
    /// ```
    /// use glam::{Vec2, Vec3};
    /// use lightlab::sampling::warp::SphericalTriangle;
    /// let t = SphericalTriangle::new(Vec3::ZERO, Vec3::new(0., 0., 1.), Vec3::new(1., 0., 1.), Vec3::new(0., 1., 1.)).unwrap();
    /// let (w, pdf) = t.sample(Vec2::new(0.3, 0.8));
    /// assert!(t.pdf(w) == pdf && (t.to_square(w) - Vec2::new(0.3, 0.8)).length() < 1e-4);
    /// ```
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (a, b, c) = (self.a, self.b, self.c);
        let (sin_alpha, cos_alpha) = self.alpha.sin_cos();
        let area = u.x as f64 * self.solid_angle;
        let (s, t) = (area - self.alpha).sin_cos();
        let p = t - cos_alpha;
        let q = s + sin_alpha * a.dot(b);
        let w = arvo_direction([a, b, c], sin_alpha, cos_alpha, [p, q, s, t], u.y);
        (w, self.pdf(w))
    }

    /// Density of [`SphericalTriangle::sample`]: 1/Ω per sr for directions inside the
    /// triangle, else 0.
    pub fn pdf(&self, w: Vec3) -> f32 {
        if inside(self.a, self.b, self.c, w.as_dvec3()) {
            (1.0 / self.solid_angle) as f32
        } else {
            0.0
        }
    }

    /// Inverse of [`SphericalTriangle::sample`]: c′ is where the great circle through b
    /// and w meets the arc a–c; u₀ = Ω(a, b, c′)/Ω and u₁ = (1 − w·b)/(1 − c′·b).
    pub fn to_square(&self, w: Vec3) -> Vec2 {
        let (a, b, c) = (self.a, self.b, self.c);
        let w = w.as_dvec3().normalize_or(b);
        let Some(mut c_prime) = b.cross(w).cross(c.cross(a)).try_normalize() else {
            return Vec2::ZERO; // w = b: every u₀ maps there.
        };
        if c_prime.dot(a + c) < 0.0 {
            c_prime = -c_prime;
        }
        let u0 = spherical_triangle_solid_angle(a, b, c_prime) / self.solid_angle;
        let u1 = one_minus_dot(w, b) / one_minus_dot(c_prime, b);
        Vec2::new(
            u0.clamp(0.0, 1.0) as f32,
            if u1.is_finite() {
                u1.clamp(0.0, 1.0) as f32
            } else {
                0.0
            },
        )
    }
}

/// The end of Arvo's map, shared with the fast path: from sin α, cos α and
/// [p, q, s, t] (p = cos(u₀Ω − α) − cos α, q = sin(u₀Ω − α) + sin α (a·b), s, t = sin, cos
/// of u₀Ω − α), the point c′ on the arc a–c that closes the sub-triangle of area u₀Ω,
/// then the direction on the arc from b to c′ at u₁.
pub(super) fn arvo_direction(
    [a, b, c]: [DVec3; 3],
    sin_alpha: f64,
    cos_alpha: f64,
    [p, q, s, t]: [f64; 4],
    u1: f32,
) -> Vec3 {
    // cos of the arc from a to c′ (Arvo's eq. for q).
    let cos_b = ((q * t - p * s) * cos_alpha - q) / ((q * s + p * t) * sin_alpha);
    let cos_b = if cos_b.is_finite() {
        cos_b.clamp(-1.0, 1.0)
    } else {
        1.0
    };
    let c_prime = cos_b * a + (1.0 - cos_b * cos_b).max(0.0).sqrt() * orthogonal_part(c, a);
    // 1 − cos of the arc b–w is u₁ times that of b–c′; 1 − x·y = |x − y|²/2 for unit
    // vectors keeps it exact for small triangles.
    let one_minus_z = u1 as f64 * one_minus_dot(c_prime, b);
    let sin_theta = (one_minus_z * (2.0 - one_minus_z)).max(0.0).sqrt();
    let w = (1.0 - one_minus_z) * b + sin_theta * orthogonal_part(c_prime, b);
    w.normalize_or(b).as_vec3()
}

/// Whether the direction `w` lies in the spherical triangle with unit vertices a, b, c
/// (on the inner side of its three great circles, whatever the winding).
pub(super) fn inside(a: DVec3, b: DVec3, c: DVec3, w: DVec3) -> bool {
    let orientation = a.dot(b.cross(c)).signum();
    [a.cross(b), b.cross(c), c.cross(a)]
        .iter()
        .all(|n| orientation * n.dot(w) >= 0.0)
}

/// 1 − x·y for unit vectors, as |x − y|²/2 (no cancellation when x ≈ y).
pub(super) fn one_minus_dot(x: DVec3, y: DVec3) -> f64 {
    0.5 * (x - y).length_squared()
}

/// The unit part of x orthogonal to the unit vector n (zero if x ∥ n).
fn orthogonal_part(x: DVec3, n: DVec3) -> DVec3 {
    (x - x.dot(n) * n).normalize_or_zero()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octant_has_solid_angle_pi_over_two_and_round_trips() {
        let t = SphericalTriangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z).expect("octant");
        assert!((t.solid_angle() - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        for u in [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.5, 0.5),
            Vec2::new(0.9, 0.95),
        ] {
            let (w, pdf) = t.sample(u);
            assert!(pdf > 0.0 && w.x >= -1e-6 && w.y >= -1e-6 && w.z >= -1e-6);
            assert!((t.to_square(w) - u).length() < 1e-4, "{u} -> {w}");
        }
        for u in [
            Vec2::ZERO,
            Vec2::ONE,
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 0.0),
        ] {
            let (w, _) = t.sample(u);
            assert!(w.is_finite() && t.to_square(w).is_finite());
        }
    }

    #[test]
    fn degenerate_triangles_give_none() {
        let far = Vec3::new(0.0, 0.0, 1e5);
        assert!(
            SphericalTriangle::new(Vec3::ZERO, far, far + Vec3::X * 1e-3, far + Vec3::Y * 1e-3)
                .is_none()
        );
        assert!(SphericalTriangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X + Vec3::Y).is_none());
        assert!(SphericalTriangle::new(Vec3::X, Vec3::X, Vec3::Y, Vec3::Z).is_none());
    }
}
