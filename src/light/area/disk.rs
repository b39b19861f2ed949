//! Disk emitters: `area` (uniform point by the concentric map, Shirley & Chiu 1997) and
//! `solid-angle` (uniform direction in the disk's spherical ellipse, by rejection from its
//! circumscribed square's spherical rectangle, with Ω from elliptic integrals:
//! [`SphericalDisk`]). Solid angle falls back to `area` where the spherical rectangle is
//! too small to be sampled safely; the fall-back depends only on the shading point, so
//! `sample` and `pdf` always agree on it.

use glam::{Vec2, Vec3};

use super::{LightPoint, LightSampling, uniform_area_pdf};
use crate::geometry::shape::Disk;
use crate::light::ShadingPoint;
use crate::sampling::Rng32;
use crate::sampling::warp::{
    MIN_SOLID_ANGLE, SphericalDisk, disk_solid_angle, square_to_uniform_disk_concentric,
};

/// A uniform point of `d` and its normal.
#[inline]
pub(super) fn sample_area(d: &Disk, u: Vec2) -> (Vec3, Vec3) {
    let q = square_to_uniform_disk_concentric(u);
    let f = d.frame();
    (d.center + d.radius * (f.s * q.x + f.t * q.y), d.normal)
}

/// Ω of `d` seen from `at` when solid-angle sampling applies there: the strategy asks
/// for it and Ω is at least [`MIN_SOLID_ANGLE`] (which the circumscribed square's
/// spherical rectangle then exceeds too).
#[inline]
fn solid_angle(d: &Disk, strategy: LightSampling, at: &ShadingPoint) -> Option<f64> {
    if strategy != LightSampling::SolidAngle {
        return None;
    }
    let omega = disk_solid_angle(at.p, d.center, d.normal, d.radius);
    (omega >= MIN_SOLID_ANGLE && omega.is_finite()).then_some(omega)
}

/// Draws a point of `d` with `strategy` (resolved: `area` or `solid-angle`).
#[inline]
pub(super) fn sample(
    d: &Disk,
    strategy: LightSampling,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    match solid_angle(d, strategy, at) {
        Some(omega) => {
            let sd =
                SphericalDisk::with_solid_angle(at.p, d.center, d.normal, d.radius, d.axes, omega)?;
            // Draws after a rejection come from a stream keyed by u, so the sample stays
            // a function of u.
            let mut more = Rng32::new(((u.x.to_bits() as u64) << 32) | u.y.to_bits() as u64);
            let (_, y, pdf) = sd.sample(u, &mut more)?;
            Some(LightPoint {
                y,
                ny: d.normal,
                pdf,
            })
        }
        None => {
            let (y, ny) = sample_area(d, u);
            Some(LightPoint {
                y,
                ny,
                pdf: uniform_area_pdf(at.p, y, ny, d.area()),
            })
        }
    }
}

/// Density per steradian at `at` of the direction towards `y` on `d`.
#[inline]
pub(super) fn pdf(d: &Disk, strategy: LightSampling, at: &ShadingPoint, y: Vec3, ny: Vec3) -> f32 {
    match solid_angle(d, strategy, at) {
        // y lies on the disk, so its direction is inside the spherical ellipse.
        Some(omega) => (1.0 / omega) as f32,
        None => uniform_area_pdf(at.p, y, ny, d.area()),
    }
}
