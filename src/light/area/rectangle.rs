//! Rectangle emitters: `area` (uniform point, lecture p = 1/A) and `solid-angle`
//! (uniform direction in the spherical rectangle, Ureña, Fajardo & King 2013), which
//! falls back to `area` where the spherical rectangle is too small to be sampled safely
//! ([`SphericalRectangle::new`] returns `None`). The fall-back depends only on the
//! shading point, so `sample` and `pdf` always agree on it.

use glam::{Vec2, Vec3};

use super::{LightPoint, LightSampling, hit_plane, uniform_area_pdf};
use crate::geometry::shape::Rectangle;
use crate::light::ShadingPoint;
use crate::sampling::warp::SphericalRectangle;

/// The spherical rectangle seen from `x`, when solid-angle sampling applies there.
#[inline]
fn spherical(r: &Rectangle, strategy: LightSampling, x: Vec3) -> Option<SphericalRectangle> {
    if strategy != LightSampling::SolidAngle {
        return None;
    }
    SphericalRectangle::new(x, r.o, r.ea, r.eb)
}

/// Draws a point of `r` with `strategy` (resolved: `area` or `solid-angle`).
#[inline]
pub(super) fn sample(
    r: &Rectangle,
    strategy: LightSampling,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    match spherical(r, strategy, at.p) {
        Some(sr) => {
            let (w, pdf) = sr.sample(u);
            let y = hit_plane(at.p, w, r.o, r.normal)?;
            Some(LightPoint {
                y,
                ny: r.normal,
                pdf,
            })
        }
        None => {
            let y = r.point(u);
            Some(LightPoint {
                y,
                ny: r.normal,
                pdf: uniform_area_pdf(at.p, y, r.normal, r.area()),
            })
        }
    }
}

/// Density per steradian at `at` of the direction towards `y` on `r`.
#[inline]
pub(super) fn pdf(
    r: &Rectangle,
    strategy: LightSampling,
    at: &ShadingPoint,
    y: Vec3,
    ny: Vec3,
) -> f32 {
    match spherical(r, strategy, at.p) {
        // y lies on the rectangle, so its direction is inside the spherical rectangle.
        Some(sr) => 1.0 / sr.solid_angle(),
        None => uniform_area_pdf(at.p, y, ny, r.area()),
    }
}
