//! Triangle emitters (and so each triangle of an emitting mesh): `area` (uniform point by
//! folding, as on the lecture's slide), `solid-angle` (uniform direction in the
//! spherical triangle, Arvo 1995) and `solid-angle-cos` (the same after a bilinear cosine
//! warp, Hart et al. 2020). Solid-angle sampling falls back to `area` where the
//! spherical triangle is numerically unsafe: smaller than
//! [`MIN_SOLID_ANGLE`](crate::sampling::warp::MIN_SOLID_ANGLE) (far or edge-on: the
//! constructor returns `None`) or within [`MAX_SOLID_ANGLE_FRACTION`] of a hemisphere (the
//! shading point almost on the triangle, where its vertices are nearly coplanar with it).
//! The choice depends only on the shading point, so `sample` and `pdf` agree on it. With
//! the render's fast paths on (the default), `solid-angle` uses the same map without libm
//! trigonometry ([`FastSphericalTriangle`]), under the same fall-backs.
//! `projected-solid-angle` draws ∝ cos θ over the part above the horizon (the
//! `projected` module).

use glam::{Vec2, Vec3};

use super::{LightPoint, LightSampling, cosine_warp, hit_plane, projected, uniform_area_pdf};
use crate::geometry::shape::Triangle;
use crate::light::ShadingPoint;
use crate::math::PI;
use crate::sampling::warp::{FastSphericalTriangle, SphericalTriangle, square_to_triangle_fold};

/// Spherical triangles above this fraction of 2π are sampled by area instead.
pub const MAX_SOLID_ANGLE_FRACTION: f32 = 0.999;

/// The spherical triangle (p0, p1, p2) seen from `x`, when solid-angle sampling is safe.
#[inline]
pub(crate) fn safe_spherical_triangle(
    x: Vec3,
    p0: Vec3,
    p1: Vec3,
    p2: Vec3,
) -> Option<SphericalTriangle> {
    SphericalTriangle::new(x, p0, p1, p2)
        .filter(|st| st.solid_angle() <= MAX_SOLID_ANGLE_FRACTION * 2.0 * PI)
}

/// The spherical triangle of `t` seen from `at` when solid-angle sampling applies there,
/// and the cosine weights of its corners under `solid-angle-cos`.
#[inline]
fn spherical(
    t: &Triangle,
    strategy: LightSampling,
    at: &ShadingPoint,
) -> Option<(SphericalTriangle, Option<[f32; 4]>)> {
    if !matches!(
        strategy,
        LightSampling::SolidAngle | LightSampling::SolidAngleCos
    ) {
        return None;
    }
    let [p0, p1, p2] = t.vertices();
    let st = safe_spherical_triangle(at.p, p0, p1, p2)?;
    Some((st, cosine_weights(strategy, at, [p0, p1, p2])))
}

/// The cosine weights of a spherical triangle's square corners under `solid-angle-cos`
/// (Arvo's map sends (0, 0) and (1, 0) to p1, (0, 1) to p0 and (1, 1) to p2).
#[inline]
pub(crate) fn cosine_weights(
    strategy: LightSampling,
    at: &ShadingPoint,
    [p0, p1, p2]: [Vec3; 3],
) -> Option<[f32; 4]> {
    (strategy == LightSampling::SolidAngleCos)
        .then(|| cosine_warp::corner_cosines(at.p, at.n, [p1, p1, p0, p2]))
}

/// A uniform point of `t` by folding the unit square onto the triangle, and its normal.
#[inline]
pub(super) fn sample_area(t: &Triangle, u: Vec2) -> (Vec3, Vec3) {
    let b = square_to_triangle_fold(u);
    (t.p0 + b.x * t.e1 + b.y * t.e2, t.normal())
}

/// The fast path's spherical triangle of `t` seen from `at`, under the same conditions as
/// [`safe_spherical_triangle`].
#[inline]
fn fast_spherical(t: &Triangle, at: &ShadingPoint) -> Option<FastSphericalTriangle> {
    let [p0, p1, p2] = t.vertices();
    FastSphericalTriangle::new(at.p, p0, p1, p2)
        .filter(|st| st.solid_angle() <= MAX_SOLID_ANGLE_FRACTION * 2.0 * PI)
}

/// Draws a point of `t` with `strategy` (resolved: `area`, `solid-angle` or
/// `solid-angle-cos`), `solid-angle` on the fast path when `fast`.
#[inline]
pub(super) fn sample(
    t: &Triangle,
    strategy: LightSampling,
    fast: bool,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    if strategy == LightSampling::ProjectedSolidAngle {
        return projected::sample(t.vertices(), t.normal(), at, u);
    }
    let ny = t.normal();
    if fast && strategy == LightSampling::SolidAngle {
        if let Some(st) = fast_spherical(t, at) {
            let (w, pdf) = st.sample(u);
            let y = hit_plane(at.p, w, t.p0, ny)?;
            return Some(LightPoint { y, ny, pdf });
        }
        let (y, ny) = sample_area(t, u);
        return Some(LightPoint {
            y,
            ny,
            pdf: uniform_area_pdf(at.p, y, ny, t.area()),
        });
    }
    match spherical(t, strategy, at) {
        Some((st, weights)) => {
            let (w, pdf) = cosine_warp::sample(&st, weights, u);
            let y = hit_plane(at.p, w, t.p0, ny)?;
            Some(LightPoint { y, ny, pdf })
        }
        None => {
            let (y, ny) = sample_area(t, u);
            Some(LightPoint {
                y,
                ny,
                pdf: uniform_area_pdf(at.p, y, ny, t.area()),
            })
        }
    }
}

/// Density per steradian at `at` of the direction towards `y` on `t`, for `sample` with
/// the same `strategy` and `fast`.
#[inline]
pub(super) fn pdf(
    t: &Triangle,
    strategy: LightSampling,
    fast: bool,
    at: &ShadingPoint,
    y: Vec3,
    ny: Vec3,
) -> f32 {
    if strategy == LightSampling::ProjectedSolidAngle {
        return projected::pdf(t.vertices(), at, y);
    }
    if fast && strategy == LightSampling::SolidAngle {
        return match fast_spherical(t, at) {
            Some(st) => 1.0 / st.solid_angle(),
            None => uniform_area_pdf(at.p, y, ny, t.area()),
        };
    }
    match spherical(t, strategy, at) {
        Some((st, None)) => 1.0 / st.solid_angle(),
        Some((st, weights)) => cosine_warp::pdf(&st, weights, (y - at.p).normalize()),
        None => uniform_area_pdf(at.p, y, ny, t.area()),
    }
}
