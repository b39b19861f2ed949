//! Uniform points on a parallelogram (a rectangle in particular): p = a + α(b − a) + β(d − a).
//! Also holds the affine plane coordinates that the triangle and polygon warps share.

use glam::{Vec2, Vec3};

/// Coordinates (s, t) of the point of the plane {o + s·e1 + t·e2} nearest to `x`
/// (least squares through the 2×2 Gram matrix), or `None` when e1 and e2 are parallel.
#[inline]
pub fn plane_coordinates(origin: Vec3, e1: Vec3, e2: Vec3, x: Vec3) -> Option<Vec2> {
    let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let det = g11 * g22 - g12 * g12;
    if det <= 1e-12 * g11 * g22 || !det.is_finite() {
        return None;
    }
    let d = x - origin;
    let (r1, r2) = (d.dot(e1), d.dot(e2));
    Some(Vec2::new(g22 * r1 - g12 * r2, g11 * r2 - g12 * r1) / det)
}

/// Uniform point on the parallelogram with corner `a` and neighbours `b` and `d`:
/// a + u₀(b − a) + u₁(d − a). pdf = 1/|(b − a) × (d − a)| per unit area; `None` if the
/// parallelogram has zero area.
///
/// ```
/// use glam::{Vec2, Vec3};
/// use lightlab::sampling::warp::square_to_parallelogram;
/// let (p, pdf) = square_to_parallelogram(Vec3::ZERO, Vec3::X * 2.0, Vec3::Y, Vec2::splat(0.5)).unwrap();
/// assert!((p - Vec3::new(1.0, 0.5, 0.0)).length() < 1e-6 && (pdf - 0.5).abs() < 1e-6);
/// ```
#[inline]
pub fn square_to_parallelogram(a: Vec3, b: Vec3, d: Vec3, u: Vec2) -> Option<(Vec3, f32)> {
    let area = (b - a).cross(d - a).length();
    if !(area > 0.0 && area.is_finite()) {
        return None;
    }
    Some((a + u.x * (b - a) + u.y * (d - a), 1.0 / area))
}

/// Density of [`square_to_parallelogram`] at `x`: 1/area per unit area if `x` lies in the
/// parallelogram (within 10⁻⁴ of its plane, relative to its size), else 0.
pub fn parallelogram_pdf(a: Vec3, b: Vec3, d: Vec3, x: Vec3) -> f32 {
    let area = (b - a).cross(d - a).length();
    match plane_coordinates(a, b - a, d - a, x) {
        Some(st) if in_unit_square(st) && on_plane(a, b - a, d - a, st, x) => 1.0 / area,
        _ => 0.0,
    }
}

/// Inverse of [`square_to_parallelogram`]: the (α, β) of `x` (projected onto the plane).
#[inline]
pub fn parallelogram_to_square(a: Vec3, b: Vec3, d: Vec3, x: Vec3) -> Vec2 {
    plane_coordinates(a, b - a, d - a, x).unwrap_or(Vec2::ZERO)
}

/// Rounding slack on the support's edges, in plane coordinates: samples on an edge
/// (α or β exactly 0 or 1) must not get a zero pdf after a round trip through 3D.
pub(crate) const EDGE_SLACK: f32 = 1e-5;

#[inline]
fn in_unit_square(st: Vec2) -> bool {
    st.cmpge(Vec2::splat(-EDGE_SLACK)).all() && st.cmple(Vec2::splat(1.0 + EDGE_SLACK)).all()
}

/// Whether `x` is within 10⁻⁴·(edge length) of the plane point with coordinates `st`.
#[inline]
pub(crate) fn on_plane(origin: Vec3, e1: Vec3, e2: Vec3, st: Vec2, x: Vec3) -> bool {
    let scale = e1.length().max(e2.length());
    (origin + st.x * e1 + st.y * e2 - x).length() <= 1e-4 * scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallelogram_round_trips_and_rejects_degenerate() {
        let (a, b, d) = (
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(1.0, 0.5, 2.0),
        );
        for u in [Vec2::ZERO, Vec2::new(0.3, 0.8), Vec2::ONE] {
            let (p, pdf) = square_to_parallelogram(a, b, d, u).expect("non-degenerate");
            assert!((parallelogram_to_square(a, b, d, p) - u).length() < 1e-5);
            assert_eq!(parallelogram_pdf(a, b, d, p), pdf);
        }
        assert_eq!(
            parallelogram_pdf(a, b, d, a + Vec3::Z * 0.1 + (b - a) * 0.5),
            0.0
        );
        assert!(square_to_parallelogram(a, b, a + 2.0 * (b - a), Vec2::ONE).is_none());
    }
}
