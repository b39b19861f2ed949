//! `projected-solid-angle`: directions ∝ cos θ over a convex planar emitter above the
//! shading point's horizon ([`ProjectedPolygon`], after Peters 2021), so that for a
//! Lambertian receiver under a constant emitter the unoccluded estimate does not vary.
//! Everything below the horizon is clipped away before sampling: the strategy never
//! draws a sample there, and its density there is zero. Where Ω⊥ is below
//! [`MIN_PROJECTED_SOLID_ANGLE`] the light is treated as invisible from the point (it
//! could add at most L·10⁻¹² of irradiance).

use glam::{DVec3, Vec2, Vec3};

use super::LightPoint;
use crate::light::ShadingPoint;
use crate::sampling::warp::{MIN_PROJECTED_SOLID_ANGLE, ProjectedPolygon, projected_solid_angle};

/// The outline in f64.
#[inline]
fn outline64<const N: usize>(outline: [Vec3; N]) -> [DVec3; N] {
    outline.map(|v| v.as_dvec3())
}

/// A point of the convex outline (plane normal `ny`) drawn ∝ cos θ from `at`.
#[inline]
pub(super) fn sample<const N: usize>(
    outline: [Vec3; N],
    ny: Vec3,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    let vertices = outline64(outline);
    let (x, n) = (at.p.as_dvec3(), at.n.as_dvec3());
    let polygon = ProjectedPolygon::new(x, n, &vertices)?;
    let (w, pdf) = polygon.sample(u.as_dvec2());
    let y = hit_plane64(x, w, vertices[0], ny.as_dvec3())?;
    Some(LightPoint {
        y: y.as_vec3(),
        ny,
        pdf: pdf as f32,
    })
}

/// Where the ray x + t·w (t > 0) meets the plane through `o` with normal `n`, in f64.
#[inline]
pub(crate) fn hit_plane64(x: DVec3, w: DVec3, o: DVec3, n: DVec3) -> Option<DVec3> {
    let t = (o - x).dot(n) / w.dot(n);
    (t > 0.0 && t.is_finite()).then(|| x + t * w)
}

/// Ω⊥ of the convex outline above the horizon of `at`, or `None` below
/// [`MIN_PROJECTED_SOLID_ANGLE`].
#[inline]
pub(crate) fn visible_projected_solid_angle(vertices: &[DVec3], at: &ShadingPoint) -> Option<f64> {
    let omega = projected_solid_angle(at.p.as_dvec3(), at.n.as_dvec3(), vertices);
    (omega >= MIN_PROJECTED_SOLID_ANGLE && omega.is_finite()).then_some(omega)
}

/// cos θ / Ω⊥ at `at` for the direction towards `y`, given Ω⊥ (zero below the horizon).
#[inline]
pub(crate) fn density(at: &ShadingPoint, y: Vec3, omega: f64) -> f32 {
    let w = (y.as_dvec3() - at.p.as_dvec3()).normalize_or_zero();
    (w.dot(at.n.as_dvec3()).max(0.0) / omega) as f32
}

/// Density per steradian at `at` of the direction towards `y` on the convex outline.
#[inline]
pub(super) fn pdf<const N: usize>(outline: [Vec3; N], at: &ShadingPoint, y: Vec3) -> f32 {
    match visible_projected_solid_angle(&outline64(outline), at) {
        Some(omega) => density(at, y, omega),
        None => 0.0,
    }
}
