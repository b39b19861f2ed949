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
//! trigonometry ([`FastSphericalTriangle`]), under the same fall-backs. Under `best`
//! (`small_by_area`), a triangle small for its distance ([`SMALL_RATIO`]) is sampled by
//! area, which leaves about the same error there for less work; an explicit
//! `solid-angle` keeps solid angle.
//! `projected-solid-angle` draws ∝ cos θ over the part above the horizon (the
//! `projected` module).

use glam::{Vec2, Vec3};

use super::{LightPoint, LightSampling, cosine_warp, hit_plane, projected, uniform_area_pdf};
use crate::geometry::shape::Triangle;
use crate::light::ShadingPoint;
use crate::math::PI;
use crate::sampling::warp::{FastSphericalTriangle, SphericalTriangle, square_to_triangle_fold};

/// Under `best` a triangle is sampled by area where it is small for its distance: the
/// ball of radius r = max(|e₁|, |e₂|) about its vertex p₀ holds it, and r² ≤ `SMALL_RATIO`·d²
/// (d = |x − p₀|, so r/d ≤ 0.1: within a cone of half-angle 5.7°, Ω ≤ 0.032 sr). There the
/// area estimate's factor cos θ_y·A/d² varies over the triangle by O(r/d) (relatively more
/// at grazing angles, where little light comes from), as much as the receiver's cos θ_x,
/// which solid-angle sampling leaves too: the two strategies leave about the same error,
/// and area costs less (pbrt-v4 takes area below Ω = 3·10⁻⁴ sr; this bound is ten times
/// wider in angle). On `mesh_ply_serialized` (a ball of 256 emitting triangles): 1.21× the
/// speed, relMSE within 0.4 % at 64 spp (BENCHMARKS.md, session 21).
pub const SMALL_RATIO: f32 = 1e-2;

/// Whether `t` is small for its distance from `at` ([`SMALL_RATIO`]).
#[inline]
fn small_for_its_distance(t: &Triangle, at: &ShadingPoint) -> bool {
    let r2 = t.e1.length_squared().max(t.e2.length_squared());
    r2 <= SMALL_RATIO * (at.p - t.p0).length_squared()
}

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

/// What [`sample`] and [`pdf`] run, given the resolved strategy and whether it came
/// from `best` (`small_by_area`): `area` in place of `solid-angle` where `best` asked for
/// it and `t` is small for its distance from `at`.
#[inline]
fn running(
    t: &Triangle,
    strategy: LightSampling,
    small_by_area: bool,
    at: &ShadingPoint,
) -> LightSampling {
    if small_by_area && strategy == LightSampling::SolidAngle && small_for_its_distance(t, at) {
        LightSampling::Area
    } else {
        strategy
    }
}

/// Draws a point of `t` with `strategy` (resolved: `area`, `solid-angle` or
/// `solid-angle-cos`; `area` where `small_by_area` and `t` is small for its distance),
/// `solid-angle` on the fast path when `fast`.
#[inline]
pub(super) fn sample(
    t: &Triangle,
    (strategy, small_by_area): (LightSampling, bool),
    fast: bool,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    if strategy == LightSampling::ProjectedSolidAngle {
        return projected::sample(t.vertices(), t.normal(), at, u);
    }
    let strategy = running(t, strategy, small_by_area, at);
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
/// the same `strategy`, `small_by_area` and `fast`.
#[inline]
pub(super) fn pdf(
    t: &Triangle,
    (strategy, small_by_area): (LightSampling, bool),
    fast: bool,
    at: &ShadingPoint,
    y: Vec3,
    ny: Vec3,
) -> f32 {
    if strategy == LightSampling::ProjectedSolidAngle {
        return projected::pdf(t.vertices(), at, y);
    }
    let strategy = running(t, strategy, small_by_area, at);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `best` samples a triangle by solid angle while r² > [`SMALL_RATIO`]·d² and by area
    /// beyond, on the fast path and the plain one; `sample` and `pdf` agree on either
    /// side, and an explicit `solid-angle` keeps solid angle. Solid angle's density is
    /// the same at every point of the triangle, area's (d²/(A cos θ_y)) is not, which
    /// tells the two apart.
    #[test]
    fn small_far_triangles_are_sampled_by_area_under_best() {
        let t = Triangle {
            p0: Vec3::new(-0.5, -0.4, 1.0),
            e1: Vec3::new(0.2, 1.0, 0.0),
            e2: Vec3::new(1.0, 0.1, 0.0),
            mesh: 0,
            index: 0,
        };
        let r2 = t.e1.length_squared().max(t.e2.length_squared());
        // Points below the triangle (its normal is −z), offset a little from p₀.
        let below = |ratio: f32| {
            let d = (r2 / ratio).sqrt();
            let p = t.p0 - Vec3::new(0.0, 0.0, d) + Vec3::new(0.3, 0.2, 0.0);
            ShadingPoint {
                p,
                ng: Vec3::Z,
                n: Vec3::Z,
            }
        };
        assert!(t.normal().z < 0.0, "the triangle faces the points below it");
        let us = [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.8, 0.7),
            Vec2::new(0.45, 0.95),
        ];
        let pdfs = |at: &ShadingPoint, best: bool, fast: bool| -> Vec<f32> {
            let strategy = (LightSampling::SolidAngle, best);
            us.iter()
                .map(|&u| {
                    let s = sample(&t, strategy, fast, at, u).expect("sample");
                    let p = pdf(&t, strategy, fast, at, s.y, s.ny);
                    assert!((p - s.pdf).abs() <= 1e-5 * p, "sample {} vs pdf {p}", s.pdf);
                    p
                })
                .collect()
        };
        let constant = |v: &[f32]| v.iter().all(|p| (p - v[0]).abs() <= 1e-5 * v[0]);
        let near = below(1.2 * SMALL_RATIO);
        let far = below(0.8 * SMALL_RATIO);
        for fast in [true, false] {
            assert!(
                constant(&pdfs(&near, true, fast)),
                "best: solid angle above the ratio"
            );
            assert!(!constant(&pdfs(&far, true, fast)), "best: area below it");
            assert!(
                constant(&pdfs(&far, false, fast)),
                "solid-angle asked for: kept"
            );
        }
    }
}
