//! The renderer's fast path for uniform solid-angle sampling of a rectangle: the map of
//! [`SphericalRectangle`](super::SphericalRectangle) (Ureña, Fajardo & King 2013,
//! Algorithm 1) without inverse trigonometry in f64. The f64 version stays the one to
//! read, and the reference this one is tested against (`--fast-paths off` renders with
//! it).
//!
//! The paper's four angles γᵢ (four f64 `acos`, a quarter of a render's time on a scene
//! lit by one rectangle) are replaced:
//! - The solid angle is the sum of the two spherical triangles (c00, c10, c11) and
//!   (c00, c11, c01), each by Van Oosterom & Strackee (1983):
//!   tan(Ω/2) = [a b c] / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|). The triple
//!   product is |z0|·w·h exactly, so the ratio keeps its relative precision for small
//!   rectangles (where γ₀ + γ₁ + γ₂ + γ₃ − 2π cancels), and one f32 arctangent
//!   ([`crate::math::atan::atan_unit`] of the smaller of t/|d| and |d|/t, absolute error
//!   below 4·10⁻⁷ rad) per triangle is enough.
//! - k = 2π − γ₂ − γ₃ is never formed as an angle: Algorithm 1 needs only sin and cos
//!   of a_u = k + u₀S, which angle addition gives from sin k, cos k and sin u₀S,
//!   cos u₀S. cos γ and sin γ are each one product over the same two radii
//!   (cos γ = ±x·y/(r_x r_y), sin γ = |z0|·|c|/(r_x r_y), |c| the distance to the corner
//!   the two edge planes share), so sin k and cos k are sums of products.
//! - sin u₀S and 1 − cos u₀S come from one f32 `sin_cos`, the latter as sin²/(1 + cos)
//!   so it keeps its relative precision for small u₀S.
//!
//! The algebra stays in f64: near the rectangle's plane (|z0| small next to its
//! extent) x_u's denominator n² − (1 − b0²)s² cancels, and in f32 the sampled u₀ moved
//! by up to 2·10⁻³ of the square (measured while writing this; the tests, `tests.rs`,
//! bound S at 10⁻⁵ relative and the sampled u at 10⁻⁴ in the same placements).

use glam::{DVec3, Vec2, Vec3};

use super::spherical_triangle::MIN_SOLID_ANGLE;
use crate::math::atan::atan_unit;

/// A rectangle seen from a shading point, ready for uniform solid-angle sampling (see
/// the module doc); the same map as [`SphericalRectangle`](super::SphericalRectangle).
#[derive(Clone, Copy, Debug)]
pub struct FastSphericalRectangle {
    /// Unit axes: x, y along the edges, z away from the rectangle's side.
    x: DVec3,
    y: DVec3,
    z: DVec3,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    /// cos k and sin k, k = 2π − γ₂ − γ₃ (paper eq. 4).
    cos_k: f64,
    sin_k: f64,
    /// b0 = −y0/r_y0, b1 = y1/r_y1, c = 1 − b0².
    b0: f64,
    b1: f64,
    c: f64,
    solid_angle: f64,
}

/// The rectangle's frame and extent seen from a point: unit axes x, y, z (z pointing
/// away from the rectangle) and the local bounds [x0, x1] × [y0, y1] at height z0 < 0,
/// with the distances to the corners c00, c10, c11, c01.
struct Local {
    x: DVec3,
    y: DVec3,
    z: DVec3,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    lengths: [f64; 4],
}

/// What a rectangle seen from a point owes to the rectangle alone: its unit edge axes,
/// their normal and the edge lengths. [`FastSphericalRectangle::new`] computes it on every
/// call; the lanes ([`crate::light::LightLanes`]) once per light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectangleFrame {
    pub(super) x: DVec3,
    pub(super) y: DVec3,
    pub(super) z: DVec3,
    pub(super) w: f64,
    pub(super) h: f64,
}

impl RectangleFrame {
    /// `None` when the edges are not perpendicular (|cos| > 10⁻⁴, as the f64 version)
    /// or not finite.
    #[inline]
    pub fn new(ex: Vec3, ey: Vec3) -> Option<RectangleFrame> {
        let (ex, ey) = (ex.as_dvec3(), ey.as_dvec3());
        let (w, h) = (ex.length(), ey.length());
        let (x, y) = (ex / w, ey / h);
        let perpendicular = x.dot(y).abs() <= 1e-4; // false for NaN too
        perpendicular.then(|| RectangleFrame {
            x,
            y,
            z: x.cross(y),
            w,
            h,
        })
    }
}

impl Local {
    /// The rectangle seen from `p`: `None` when the point lies in the rectangle's plane
    /// or an input is not finite.
    #[inline(always)]
    fn from_frame(f: &RectangleFrame, p: Vec3, corner: Vec3) -> Option<Local> {
        let RectangleFrame { x, y, mut z, w, h } = *f;
        let d = corner.as_dvec3() - p.as_dvec3();
        let mut z0 = d.dot(z);
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let (x1, y1) = (x0 + w, y0 + h);
        if !(z0 < 0.0 && [x0, x1, y0, y1, z0].iter().all(|v| v.is_finite())) {
            return None;
        }
        let z2 = z0 * z0;
        let len = |x: f64, y: f64| (x * x + y * y + z2).sqrt();
        Some(Local {
            x,
            y,
            z,
            x0,
            x1,
            y0,
            y1,
            z0,
            lengths: [len(x0, y0), len(x1, y0), len(x1, y1), len(x0, y1)],
        })
    }

    /// The solid angle by two Van Oosterom–Strackee triangles (module doc), or `None`
    /// below [`MIN_SOLID_ANGLE`] (the f64 version's bound).
    #[inline(always)]
    fn solid_angle(&self) -> Option<f64> {
        let Local {
            x0, x1, y0, y1, z0, ..
        } = *self;
        let [l00, l10, l11, l01] = self.lengths;
        let z2 = z0 * z0;
        let dot = |xa: f64, ya: f64, xb: f64, yb: f64| xa * xb + ya * yb + z2;
        let (d00_10, d00_11, d10_11) = (
            dot(x0, y0, x1, y0),
            dot(x0, y0, x1, y1),
            dot(x1, y0, x1, y1),
        );
        let (d00_01, d11_01) = (dot(x0, y0, x0, y1), dot(x1, y1, x0, y1));
        let triple = -z0 * (x1 - x0) * (y1 - y0);
        let den_a = l00 * l10 * l11 + d00_10 * l11 + d00_11 * l10 + d10_11 * l00;
        let den_b = l00 * l11 * l01 + d00_11 * l01 + d00_01 * l11 + d11_01 * l00;
        let s = 2.0 * (half_angle(triple, den_a) + half_angle(triple, den_b));
        (s >= MIN_SOLID_ANGLE && s.is_finite()).then_some(s)
    }
}

/// atan2(t, d) for t > 0: for t/d < 0.05 (small triangles) the series
/// x − x³/3 + x⁵/5 − x⁷/7 + x⁹/9 in f64 (relative error below 10⁻¹³), else the f32
/// polynomial of the ratio of the smaller to the larger of t and |d| (one f64 division,
/// so any f64 magnitude fits; absolute error 4·10⁻⁷ rad on angles above 0.05) and the
/// octant's reflection. [`super::spherical_rectangle_lanes`] computes the same per lane.
#[inline(always)]
fn half_angle(t: f64, d: f64) -> f64 {
    if d > 20.0 * t {
        let x = t / d;
        let x2 = x * x;
        return x * (1.0 - x2 * (1.0 / 3.0 - x2 * (0.2 - x2 * (1.0 / 7.0 - x2 / 9.0))));
    }
    let ad = d.abs();
    let r = if t > ad {
        std::f64::consts::FRAC_PI_2 - atan_unit((ad / t) as f32) as f64
    } else {
        atan_unit((t / ad) as f32) as f64
    };
    if d < 0.0 { std::f64::consts::PI - r } else { r }
}

impl FastSphericalRectangle {
    /// The rectangle `corner + α·ex + β·ey` (α, β ∈ [0, 1], ex ⊥ ey) seen from `p`;
    /// `None` exactly where [`SphericalRectangle::new`](super::SphericalRectangle::new)
    /// gives `None` (up to the rounding of S at [`MIN_SOLID_ANGLE`]).
    #[inline]
    pub fn new(p: Vec3, corner: Vec3, ex: Vec3, ey: Vec3) -> Option<FastSphericalRectangle> {
        Self::from_frame(&RectangleFrame::new(ex, ey)?, p, corner)
    }

    /// [`FastSphericalRectangle::new`] with the rectangle's frame precomputed (the same
    /// bits).
    #[inline]
    pub fn from_frame(
        frame: &RectangleFrame,
        p: Vec3,
        corner: Vec3,
    ) -> Option<FastSphericalRectangle> {
        let l = Local::from_frame(frame, p, corner)?;
        let solid_angle = l.solid_angle()?;
        let Local { x0, y0, y1, z0, .. } = l;
        // γ₂ (corner c01): cos = x0·y1/(r_x0 r_y1), sin = |z0|·|c01|/(r_x0 r_y1);
        // γ₃ (corner c00): cos = −x0·y0/(r_x0 r_y0), sin = |z0|·|c00|/(r_x0 r_y0).
        let z2 = z0 * z0;
        let (ry0, ry1) = ((z2 + y0 * y0).sqrt(), (z2 + y1 * y1).sqrt());
        let (c2, s2) = (x0 * y1, -z0 * l.lengths[3]);
        let (c3, s3) = (-(x0 * y0), -z0 * l.lengths[0]);
        let scale = 1.0 / ((z2 + x0 * x0) * ry0 * ry1);
        // k = 2π − (γ₂ + γ₃): cos k = cos(γ₂ + γ₃), sin k = −sin(γ₂ + γ₃).
        let cos_k = (c2 * c3 - s2 * s3) * scale;
        let sin_k = -(s2 * c3 + c2 * s3) * scale;
        (cos_k.is_finite() && sin_k.is_finite()).then_some(FastSphericalRectangle {
            x: l.x,
            y: l.y,
            z: l.z,
            x0,
            x1: l.x1,
            y0,
            y1,
            z0,
            cos_k,
            sin_k,
            b0: -y0 / ry0,
            b1: y1 / ry1,
            c: z2 / (ry0 * ry0),
            solid_angle,
        })
    }

    /// The solid angle alone, with the same `None` as [`FastSphericalRectangle::new`]
    /// (a light's pdf needs only this).
    #[inline]
    pub fn solid_angle_at(p: Vec3, corner: Vec3, ex: Vec3, ey: Vec3) -> Option<f32> {
        Local::from_frame(&RectangleFrame::new(ex, ey)?, p, corner)?
            .solid_angle()
            .map(|s| s as f32)
    }

    /// S in steradians.
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// Density of [`FastSphericalRectangle::sample`]: 1/S per sr for directions that
    /// meet the rectangle, else 0.
    pub fn pdf(&self, w: Vec3) -> f32 {
        let w = w.as_dvec3();
        let wz = w.dot(self.z);
        if wz >= 0.0 {
            return 0.0;
        }
        let t = self.z0 / wz;
        let (x, y) = (t * w.dot(self.x), t * w.dot(self.y));
        let inside = (self.x0..=self.x1).contains(&x) && (self.y0..=self.y1).contains(&y);
        if inside {
            1.0 / self.solid_angle()
        } else {
            0.0
        }
    }

    /// A direction uniform in the solid angle, the offset from the shading point to the
    /// rectangle's point along it, and the density 1/S: Algorithm 1 as
    /// [`SphericalRectangle::sample`](super::SphericalRectangle::sample) writes it, with
    /// sin a_u and cos a_u by angle addition.
    #[inline]
    pub fn sample(&self, u: Vec2) -> (Vec3, Vec3, f32) {
        let Self {
            x0, x1, y0, y1, z0, ..
        } = *self;
        let (su, cu) = ((u.x as f64 * self.solid_angle) as f32).sin_cos();
        let (su, cu) = (su as f64, cu as f64);
        // 1 − cos u₀S without cancellation for small angles.
        let one_minus_cu = if cu > 0.0 {
            su * su / (1.0 + cu)
        } else {
            1.0 - cu
        };
        let s = self.sin_k - self.sin_k * one_minus_cu + self.cos_k * su;
        let cos_au = self.cos_k - self.cos_k * one_minus_cu - self.sin_k * su;
        let n = cos_au * self.b0 - self.b1;
        let den = (n * n - self.c * s * s).max(1e-300).sqrt();
        let xu = (-z0 * s / den).copysign(-z0 * s * n).clamp(x0, x1);
        let d2 = xu * xu + z0 * z0;
        let (h0, h1) = (y0 / (d2 + y0 * y0).sqrt(), y1 / (d2 + y1 * y1).sqrt());
        let hv = h0 + u.y as f64 * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-12 {
            (hv * d2.sqrt() / (1.0 - hv2).sqrt()).clamp(y0, y1)
        } else if hv > 0.0 {
            y1
        } else {
            y0
        };
        let offset = xu * self.x + yv * self.y + z0 * self.z;
        let w = (offset / (d2 + yv * yv).sqrt()).as_vec3();
        (w, offset.as_vec3(), 1.0 / self.solid_angle())
    }
}

#[cfg(test)]
mod tests;
