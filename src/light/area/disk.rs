//! Disk emitters: `area` only (uniform point by the concentric map, Shirley & Chiu 1997).
//! Solid-angle sampling of a disk needs the spherical ellipse (Guillén et al. 2017,
//! "Area-Preserving Parameterizations for Spherical Ellipses"), whose inversion relies
//! on elliptic integrals solved numerically; lightlab does not implement it, so every
//! strategy name resolves to `area` on disks.

use glam::{Vec2, Vec3};

use super::{LightPoint, uniform_area_pdf};
use crate::geometry::shape::Disk;
use crate::light::ShadingPoint;
use crate::sampling::warp::square_to_uniform_disk_concentric;

/// A uniform point of `d` and its normal.
#[inline]
pub(super) fn sample_area(d: &Disk, u: Vec2) -> (Vec3, Vec3) {
    let q = square_to_uniform_disk_concentric(u);
    let f = d.frame();
    (d.center + d.radius * (f.s * q.x + f.t * q.y), d.normal)
}

/// Draws a uniform point of `d`.
#[inline]
pub(super) fn sample(d: &Disk, at: &ShadingPoint, u: Vec2) -> Option<LightPoint> {
    let (y, ny) = sample_area(d, u);
    Some(LightPoint {
        y,
        ny,
        pdf: uniform_area_pdf(at.p, y, ny, d.area()),
    })
}
