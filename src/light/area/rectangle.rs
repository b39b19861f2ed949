//! Rectangle emitters: `area` (uniform point, lecture p = 1/A), `solid-angle` (uniform
//! direction in the spherical rectangle, Ureña, Fajardo & King 2013) and
//! `solid-angle-cos` (the same after a bilinear cosine warp, Hart et al. 2020), which
//! falls back to `area` where the spherical rectangle is too small to be sampled safely
//! ([`SphericalRectangle::new`] returns `None`). The fall-back depends only on the
//! shading point, so `sample` and `pdf` always agree on it. `projected-solid-angle`
//! draws ∝ cos θ over the part above the horizon (see the `projected` module).
//!
//! With the render's fast paths on (the default), `solid-angle` uses
//! [`FastSphericalRectangle`]: the same map without inverse trigonometry in f64, on the
//! same shading points (its `None` falls back to `area` as the f64 version's does).

use glam::{Vec2, Vec3};

use super::{LightPoint, LightSampling, cosine_warp, hit_plane, projected, uniform_area_pdf};
use crate::geometry::shape::Rectangle;
use crate::light::ShadingPoint;
use crate::sampling::warp::{FastSphericalRectangle, SphericalRectangle};

/// The spherical rectangle seen from `at` when solid-angle sampling applies there, and
/// the cosine weights of its corners under `solid-angle-cos`.
#[inline]
fn spherical(
    r: &Rectangle,
    strategy: LightSampling,
    at: &ShadingPoint,
) -> Option<(SphericalRectangle, Option<[f32; 4]>)> {
    if !matches!(
        strategy,
        LightSampling::SolidAngle | LightSampling::SolidAngleCos
    ) {
        return None;
    }
    let sr = SphericalRectangle::new(at.p, r.o, r.ea, r.eb)?;
    let corners = [r.o, r.o + r.ea, r.o + r.eb, r.o + r.ea + r.eb];
    let weights = (strategy == LightSampling::SolidAngleCos)
        .then(|| cosine_warp::corner_cosines(at.p, at.n, corners));
    Some((sr, weights))
}

/// Draws a point of `r` with `strategy` (resolved: `area`, `solid-angle` or
/// `solid-angle-cos`), `solid-angle` on the fast path when `fast`.
#[inline]
pub(super) fn sample(
    r: &Rectangle,
    strategy: LightSampling,
    fast: bool,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    if strategy == LightSampling::ProjectedSolidAngle {
        return projected::sample(r.corners(), r.normal, at, u);
    }
    if fast && strategy == LightSampling::SolidAngle {
        if let Some(sr) = FastSphericalRectangle::new(at.p, r.o, r.ea, r.eb) {
            let (_, offset, pdf) = sr.sample(u);
            return Some(LightPoint {
                y: at.p + offset,
                ny: r.normal,
                pdf,
            });
        }
        return area_point(r, at, u);
    }
    match spherical(r, strategy, at) {
        Some((sr, weights)) => {
            let (w, pdf) = cosine_warp::sample(&sr, weights, u);
            let y = hit_plane(at.p, w, r.o, r.normal)?;
            Some(LightPoint {
                y,
                ny: r.normal,
                pdf,
            })
        }
        None => area_point(r, at, u),
    }
}

/// A point uniform by area (`area`, and the fall-back of the solid-angle strategies).
#[inline]
fn area_point(r: &Rectangle, at: &ShadingPoint, u: Vec2) -> Option<LightPoint> {
    let y = r.point(u);
    Some(LightPoint {
        y,
        ny: r.normal,
        pdf: uniform_area_pdf(at.p, y, r.normal, r.area()),
    })
}

/// Density per steradian at `at` of the direction towards `y` on `r`, for `sample`
/// with the same `strategy` and `fast`.
#[inline]
pub(super) fn pdf(
    r: &Rectangle,
    strategy: LightSampling,
    fast: bool,
    at: &ShadingPoint,
    y: Vec3,
    ny: Vec3,
) -> f32 {
    if strategy == LightSampling::ProjectedSolidAngle {
        return projected::pdf(r.corners(), at, y);
    }
    if fast && strategy == LightSampling::SolidAngle {
        return match FastSphericalRectangle::solid_angle_at(at.p, r.o, r.ea, r.eb) {
            Some(s) => 1.0 / s,
            None => uniform_area_pdf(at.p, y, ny, r.area()),
        };
    }
    match spherical(r, strategy, at) {
        // y lies on the rectangle, so its direction is inside the spherical rectangle.
        Some((sr, None)) => 1.0 / sr.solid_angle(),
        Some((sr, weights)) => cosine_warp::pdf(&sr, weights, (y - at.p).normalize()),
        None => uniform_area_pdf(at.p, y, ny, r.area()),
    }
}
