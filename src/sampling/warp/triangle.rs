//! Uniform points on a triangle: barycentrics by rejection (α + β < 1), by folding the
//! square's upper half over the diagonal, and by the square-root map; then a point on a
//! concrete triangle with pdf 1/area.
//!
//! Barycentrics are returned as `Vec2(b1, b2)`, the weights of vertices p1 and p2; the
//! point is p0 + b1(p1 − p0) + b2(p2 − p0).

use glam::{Vec2, Vec3};

use super::parallelogram::{EDGE_SLACK, on_plane, plane_coordinates};
use crate::sampling::Uniform;

/// Uniform barycentrics by rejection: draw (α, β) in the square until α + β < 1
/// (acceptance 1/2).
pub fn triangle_rejection(src: &mut impl Uniform) -> Vec2 {
    loop {
        let b = src.next_2d();
        if b.x + b.y < 1.0 {
            return b;
        }
    }
}

/// Uniform barycentrics by folding: (α, β) ↦ (1 − α, 1 − β) when α + β > 1. The map is
/// two-to-one, so it has no inverse and breaks stratification across the diagonal.
#[inline]
pub fn square_to_triangle_fold(u: Vec2) -> Vec2 {
    if u.x + u.y > 1.0 { Vec2::ONE - u } else { u }
}

/// Uniform barycentrics by the square-root map (Turk 1990, "Generating Random Points in
/// Triangles", Graphics Gems; pbrt-v4 §6.5.1): b1 = √u₀(1 − u₁), b2 = √u₀·u₁. Density
/// 2 on the reference triangle; continuous and invertible.
#[inline]
pub fn square_to_triangle_sqrt(u: Vec2) -> Vec2 {
    let s = u.x.sqrt();
    Vec2::new(s * (1.0 - u.y), s * u.y)
}

/// Inverse of [`square_to_triangle_sqrt`]: u₀ = (b1 + b2)², u₁ = b2/(b1 + b2).
#[inline]
pub fn triangle_sqrt_to_square(b: Vec2) -> Vec2 {
    let s = b.x + b.y;
    Vec2::new(
        s * s,
        if s > 0.0 {
            (b.y / s).clamp(0.0, 1.0)
        } else {
            0.0
        },
    )
}

/// Density of the barycentric warps on the reference triangle {b1, b2 ≥ 0, b1 + b2 ≤ 1}:
/// 2 per unit (b1, b2)-area inside, else 0.
#[inline]
pub fn triangle_barycentric_pdf(b: Vec2) -> f32 {
    if b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 {
        2.0
    } else {
        0.0
    }
}

/// The area of triangle (p0, p1, p2).
#[inline]
pub fn triangle_area(p0: Vec3, p1: Vec3, p2: Vec3) -> f32 {
    0.5 * (p1 - p0).cross(p2 - p0).length()
}

/// The point of triangle (p0, p1, p2) with barycentrics `b` (from any warp above) and
/// its density 1/area per unit area; `None` for a triangle of zero area.
///
/// ```
/// use glam::{Vec2, Vec3};
/// use lightlab::sampling::warp::{sample_triangle, square_to_triangle_sqrt};
/// let b = square_to_triangle_sqrt(Vec2::new(0.4, 0.2));
/// let (p, pdf) = sample_triangle(Vec3::ZERO, Vec3::X, Vec3::Y, b).unwrap();
/// assert!(p.x + p.y <= 1.0 && (pdf - 2.0).abs() < 1e-6);
/// ```
#[inline]
pub fn sample_triangle(p0: Vec3, p1: Vec3, p2: Vec3, b: Vec2) -> Option<(Vec3, f32)> {
    let area = triangle_area(p0, p1, p2);
    if !(area > 0.0 && area.is_finite()) {
        return None;
    }
    Some((p0 + b.x * (p1 - p0) + b.y * (p2 - p0), 1.0 / area))
}

/// Density of [`sample_triangle`] at `x`: 1/area per unit area if `x` lies on the
/// triangle (within 10⁻⁴ of its plane, relative to its size), else 0.
pub fn triangle_pdf(p0: Vec3, p1: Vec3, p2: Vec3, x: Vec3) -> f32 {
    let (e1, e2) = (p1 - p0, p2 - p0);
    match plane_coordinates(p0, e1, e2, x) {
        Some(b) if on_triangle(b) && on_plane(p0, e1, e2, b, x) => 1.0 / triangle_area(p0, p1, p2),
        _ => 0.0,
    }
}

/// Whether barycentrics lie on the closed reference triangle, with rounding slack.
fn on_triangle(b: Vec2) -> bool {
    b.x >= -EDGE_SLACK && b.y >= -EDGE_SLACK && b.x + b.y <= 1.0 + EDGE_SLACK
}

/// The barycentrics (b1, b2) of `x` projected onto the triangle's plane (the inverse of
/// [`sample_triangle`]); compose with [`triangle_sqrt_to_square`] to recover u.
#[inline]
pub fn triangle_to_barycentrics(p0: Vec3, p1: Vec3, p2: Vec3, x: Vec3) -> Vec2 {
    plane_coordinates(p0, p1 - p0, p2 - p0, x).unwrap_or(Vec2::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng32;

    #[test]
    fn barycentrics_stay_inside_and_sqrt_round_trips() {
        let mut rng = Rng32::new(5);
        for u in [
            Vec2::ZERO,
            Vec2::ONE,
            Vec2::new(0.2, 0.9),
            Vec2::new(0.7, 0.4),
        ] {
            for b in [
                square_to_triangle_fold(u),
                square_to_triangle_sqrt(u),
                triangle_rejection(&mut rng),
            ] {
                assert!(triangle_barycentric_pdf(b) > 0.0, "{u} -> {b}");
            }
            if u.x > 0.0 && u.x < 1.0 {
                assert!((triangle_sqrt_to_square(square_to_triangle_sqrt(u)) - u).length() < 1e-5);
            }
        }
    }

    #[test]
    fn triangle_pdf_is_inverse_area_on_the_triangle_only() {
        let (p0, p1, p2) = (
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 3.0),
        );
        let (x, pdf) = sample_triangle(p0, p1, p2, Vec2::new(0.25, 0.5)).expect("area > 0");
        assert!((pdf * triangle_area(p0, p1, p2) - 1.0).abs() < 1e-6);
        assert_eq!(triangle_pdf(p0, p1, p2, x), pdf);
        assert!((triangle_to_barycentrics(p0, p1, p2, x) - Vec2::new(0.25, 0.5)).length() < 1e-5);
        assert_eq!(triangle_pdf(p0, p1, p2, p1 + (p1 - p0)), 0.0);
        assert!(sample_triangle(p0, p1, p0, Vec2::ONE).is_none());
    }
}
