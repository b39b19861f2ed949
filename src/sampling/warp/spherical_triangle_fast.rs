//! The renderer's fast path for uniform solid-angle sampling of a triangle: the map of
//! [`SphericalTriangle`](super::SphericalTriangle) (Arvo 1995) without libm trigonometry.
//! The f64 version stays the one to read, and the reference this one is tested against
//! (`--fast-paths off` renders with it).
//!
//! Arvo's map needs the solid angle Ω, the spherical angle α at vertex a, and sin and cos
//! of u₀Ω − α. The f64 version gets them from two `atan2` and two `sin_cos` per light
//! sample (with the constructor, about a fifth of a render lit by an emitting mesh); here
//! one `sin_cos`:
//! - Ω by Van Oosterom & Strackee (1983), tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)
//!   for unit a, b, c, with one f32 [`atan2`] (relative error below 10⁻⁶: the same map
//!   and density up to that factor, which `sample` and `pdf` share).
//! - α is never formed: cos α and sin α are (a×b)·(a×c) and |(a×b)×(a×c)| over their
//!   hypotenuse.
//! - sin u₀Ω and 1 − cos u₀Ω come from one f64 `sin_cos`, the latter as sin²/(1 + cos) so
//!   it keeps its relative precision for small u₀Ω (an f32 `sin_cos` moved directions by
//!   3·10⁻⁵ of the triangle's size at Ω = 10⁻³ through Arvo's cos b′, which is near 1 for
//!   small triangles); Arvo's p = cos(u₀Ω − α) − cos α and
//!   q = sin(u₀Ω − α) + sin α (a·b) are then sums of products without cancellation:
//!   p = sin α sin u₀Ω − cos α (1 − cos u₀Ω),
//!   q = cos α sin u₀Ω + sin α (1 − cos u₀Ω) − sin α (1 − a·b), with 1 − a·b = |a − b|²/2.
//!
//! The algebra that follows stays in f64, as in the f64 version.

use glam::{DVec3, Vec2, Vec3};

#[cfg(test)]
use super::spherical_triangle::SphericalTriangle;
use super::spherical_triangle::{MIN_SOLID_ANGLE, arvo_direction, inside, one_minus_dot};
use crate::math::atan::atan2;

/// A triangle seen from a shading point, ready for uniform solid-angle sampling (see the
/// module doc); the same map as [`SphericalTriangle`](super::SphericalTriangle).
#[derive(Clone, Copy, Debug)]
pub struct FastSphericalTriangle {
    /// Unit directions from the shading point to the vertices.
    a: DVec3,
    b: DVec3,
    c: DVec3,
    solid_angle: f64,
    cos_alpha: f64,
    sin_alpha: f64,
}

impl FastSphericalTriangle {
    /// The triangle (v0, v1, v2) seen from `p`, or `None` where [`SphericalTriangle::new`](super::SphericalTriangle::new)
    /// gives `None` (solid angle below [`MIN_SOLID_ANGLE`], non-finite input).
    #[inline]
    pub fn new(p: Vec3, v0: Vec3, v1: Vec3, v2: Vec3) -> Option<FastSphericalTriangle> {
        let dir = |v: Vec3| (v.as_dvec3() - p.as_dvec3()).try_normalize();
        let (a, b, c) = (dir(v0)?, dir(v1)?, dir(v2)?);
        let ab = a.cross(b);
        let ac = a.cross(c);
        let det = ab.dot(c).abs();
        let den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
        let solid_angle = 2.0 * atan2(det as f32, den as f32) as f64;
        if !(solid_angle >= MIN_SOLID_ANGLE && solid_angle.is_finite()) {
            return None;
        }
        // cos α and sin α of the angle between a×b and a×c, scaled together onto the unit
        // circle: Arvo's cos b′ cancels to 1 − O(u₀Ω·|ab|) for small triangles and needs
        // sin²α + cos²α = 1 to the last bit.
        let (x, y) = (ab.dot(ac), ab.cross(ac).length());
        let r = (x * x + y * y).sqrt();
        let (cos_alpha, sin_alpha) = (x / r, y / r);
        if !(cos_alpha.is_finite() && sin_alpha.is_finite()) {
            return None;
        }
        Some(FastSphericalTriangle {
            a,
            b,
            c,
            solid_angle,
            cos_alpha,
            sin_alpha,
        })
    }

    /// Ω in steradians.
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// A unit direction uniform in the triangle's solid angle and its density 1/Ω (the map
    /// of [`SphericalTriangle::sample`](super::SphericalTriangle::sample)).
    #[inline]
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (a, b, c) = (self.a, self.b, self.c);
        let (cos_alpha, sin_alpha) = (self.cos_alpha, self.sin_alpha);
        let (sin_area, cos_area) = (u.x as f64 * self.solid_angle).sin_cos();
        let one_minus_cos = if cos_area > 0.0 {
            sin_area * sin_area / (1.0 + cos_area)
        } else {
            1.0 - cos_area
        };
        // s, t = sin, cos of u₀Ω − α; p = t − cos α; q = s + sin α (a·b).
        let s = sin_area * cos_alpha - cos_area * sin_alpha;
        let t = cos_area * cos_alpha + sin_area * sin_alpha;
        let p = sin_alpha * sin_area - cos_alpha * one_minus_cos;
        let q = cos_alpha * sin_area + sin_alpha * (one_minus_cos - one_minus_dot(a, b));
        let w = arvo_direction([a, b, c], sin_alpha, cos_alpha, [p, q, s, t], u.y);
        (w, (1.0 / self.solid_angle) as f32)
    }

    /// Density of [`Self::sample`]: 1/Ω per sr for directions inside the triangle, else 0.
    pub fn pdf(&self, w: Vec3) -> f32 {
        if inside(self.a, self.b, self.c, w.as_dvec3()) {
            (1.0 / self.solid_angle) as f32
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng32;

    /// Random triangles seen from random points, from 1.0·10⁻⁷ sr to 6.0 sr (0.96 of a
    /// hemisphere):
    /// the fast map lands within 2·10⁻⁵ of the triangle's angular size of the f64 map for
    /// the same (u₀, u₁) (plus the f32 rounding of both directions), and the solid angles
    /// agree to 2·10⁻⁶.
    #[test]
    fn fast_map_equals_the_f64_map() {
        let mut rng = Rng32::new(5);
        let mut r = || rng.next_f32();
        let mut checked = 0;
        for case in 0..4000 {
            let scale = [1e-3f32, 1e-2, 0.1, 1.0, 10.0][case % 5];
            let v = |r: &mut dyn FnMut() -> f32| Vec3::new(r() - 0.5, r() - 0.5, r() + 0.5);
            let c = v(&mut r);
            let (e1, e2) = (v(&mut r) - c, v(&mut r) - c);
            let (v0, v1, v2) = (c, c + e1 * scale, c + e2 * scale);
            let p = Vec3::new(r() - 0.5, r() - 0.5, -r()) * 0.5;
            let (Some(f), Some(x)) = (
                FastSphericalTriangle::new(p, v0, v1, v2),
                SphericalTriangle::new(p, v0, v1, v2),
            ) else {
                continue;
            };
            let rel = (f.solid_angle() / x.solid_angle() - 1.0).abs();
            assert!(rel < 2e-6, "Ω {} vs {}", f.solid_angle(), x.solid_angle());
            let size = x.solid_angle().sqrt();
            for _ in 0..8 {
                let u = Vec2::new(r(), r());
                let (wf, pf) = f.sample(u);
                let (wx, _) = x.sample(u);
                // Both maps round their direction to f32 (≈ 6·10⁻⁸ per component).
                let d = (wf - wx).length() / size;
                let bound = 2e-5 + 4e-7 / size;
                assert!(
                    d < bound,
                    "case {case}: Ω {} u {u}: {d} p {:?} v {:?} {:?} {:?} wf {:?} wx {:?}",
                    x.solid_angle(),
                    p.to_array(),
                    v0.to_array(),
                    v1.to_array(),
                    v2.to_array(),
                    wf.to_array(),
                    wx.to_array()
                );
                assert!((pf * f.solid_angle() - 1.0).abs() < 1e-6);
            }
            checked += 1;
        }
        assert!(checked > 3000, "{checked}");
    }
}
