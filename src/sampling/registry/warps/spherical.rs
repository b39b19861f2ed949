//! Registry rows for the spherical warps: solid-angle and projected-solid-angle sampling
//! of triangles, rectangles and polygons, seen from near, far and grazing points and
//! around the zenith.

use glam::Vec3;

use super::{entry, square, with_inverse};
use crate::sampling::chi2::Domain;
use crate::sampling::registry::{Entry, boxed};
use crate::sampling::warp::*;

/// The smallest cap around the mean direction that holds the outline through `points`
/// (seen from `from`), sampled densely along each edge, with a small margin.
fn cap_around(from: Vec3, points: &[Vec3]) -> Domain {
    let dirs: Vec<Vec3> = (0..points.len())
        .flat_map(|i| {
            let (a, b) = (points[i], points[(i + 1) % points.len()]);
            (0..64).map(move |k| (a + (b - a) * (k as f32 / 64.0) - from).normalize())
        })
        .collect();
    let axis = dirs.iter().copied().sum::<Vec3>().normalize();
    let z_min = dirs.iter().map(|d| d.dot(axis)).fold(1.0f32, f32::min);
    Domain::cap(axis, 1.0 - (1.0 - z_min) * 1.02)
}

pub(super) fn spherical_entries() -> Vec<Entry> {
    let mut list = Vec::new();
    // (case, shading point, a triangle's vertices / a rectangle's corner and edges)
    let cases = [
        (
            "near",
            Vec3::ZERO,
            [
                Vec3::new(-1.0, -0.5, 0.3),
                Vec3::new(1.2, -0.8, 0.5),
                Vec3::new(0.2, 1.0, 0.4),
            ],
        ),
        (
            "far",
            Vec3::new(0.3, -0.2, -60.0),
            [
                Vec3::new(-0.5, -0.4, 1.0),
                Vec3::new(0.6, -0.3, 1.2),
                Vec3::new(0.1, 0.7, 0.8),
            ],
        ),
        (
            "grazing",
            Vec3::new(0.0, 0.0, 0.25),
            [
                Vec3::new(1.0, -1.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(2.5, 0.0, 0.0),
            ],
        ),
    ];
    for (case, from, [v0, v1, v2]) in cases {
        let Some(t) = SphericalTriangle::new(from, v0, v1, v2) else {
            continue;
        };
        let e = entry(
            &format!("spherical-triangle-{case}"),
            &format!(
                "triangle uniform in solid angle (Arvo 1995), {case} view, {:.2e} sr",
                t.solid_angle()
            ),
            cap_around(from, &[v0, v1, v2]),
            square(move |u| t.sample(u)),
            boxed(move |w| t.pdf(w)),
        );
        list.push(with_inverse(e, boxed(move |w| t.to_square(w))));
        // The renderer's fast path of the same map (no libm trigonometry).
        if let Some(f) = FastSphericalTriangle::new(from, v0, v1, v2) {
            list.push(entry(
                &format!("spherical-triangle-fast-{case}"),
                &format!(
                    "the renderer's fast path of spherical-triangle (no libm atan2, sin_cos), {case} view, {:.2e} sr",
                    f.solid_angle()
                ),
                cap_around(from, &[v0, v1, v2]),
                square(move |u| {
                    let w = f.sample(u).0;
                    (w, f.pdf(w))
                }),
                boxed(move |w| f.pdf(w)),
            ));
        }
        // A rectangle on the triangle's first two edges' plane: corner v0, edges along v1 − v0 and its perpendicular.
        let ex = v1 - v0;
        let ey = (v2 - v0) - (v2 - v0).dot(ex) / ex.length_squared() * ex;
        let corners = [v0, v0 + ex, v0 + ex + ey, v0 + ey];
        let Some(r) = SphericalRectangle::new(from, v0, ex, ey) else {
            continue;
        };
        let e = entry(
            &format!("spherical-rectangle-{case}"),
            &format!(
                "rectangle uniform in solid angle (Urena et al. 2013), {case} view, {:.2e} sr",
                r.solid_angle()
            ),
            cap_around(from, &corners),
            square(move |u| r.sample(u)),
            boxed(move |w| r.pdf(w)),
        );
        list.push(with_inverse(e, boxed(move |w| r.to_square(w))));
        // The renderer's fast path of the same map (no inverse of its own).
        let Some(f) = FastSphericalRectangle::new(from, v0, ex, ey) else {
            continue;
        };
        list.push(entry(
            &format!("spherical-rectangle-fast-{case}"),
            &format!(
                "the renderer's fast path of spherical-rectangle (no f64 acos), {case} view, {:.2e} sr",
                f.solid_angle()
            ),
            cap_around(from, &corners),
            // As for the f64 map: a far edge point's f32 direction may round to just
            // outside, and its density is what `pdf` says of the direction returned.
            square(move |u| {
                let w = f.sample(u).0;
                (w, f.pdf(w))
            }),
            boxed(move |w| f.pdf(w)),
        ));
    }
    list
}

/// Convex outlines sampled ∝ cos θ (projected solid angle): near, far, cut by the
/// horizon, and around the zenith.
pub(super) fn projected_entries() -> Vec<Entry> {
    let near = [
        Vec3::new(-1.0, -0.5, 0.3),
        Vec3::new(1.2, -0.8, 0.5),
        Vec3::new(0.2, 1.0, 0.4),
    ];
    let far_rectangle = [
        Vec3::new(-0.5, -0.4, 1.0),
        Vec3::new(0.6, -0.4, 1.0),
        Vec3::new(0.6, 0.5, 1.2),
        Vec3::new(-0.5, 0.5, 1.2),
    ];
    let grazing = [
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(2.5, 0.0, 0.0),
    ];
    let around_zenith = [
        Vec3::new(-0.3, -0.6, 0.5),
        Vec3::new(0.7, -0.6, 0.5),
        Vec3::new(0.7, 0.4, 0.5),
        Vec3::new(-0.3, 0.4, 0.5),
    ];
    let cases: [(&str, Vec3, Vec3, &[Vec3]); 4] = [
        ("triangle-near", Vec3::ZERO, Vec3::Z, &near),
        (
            "rectangle-far",
            Vec3::new(0.3, -0.2, -60.0),
            Vec3::Z,
            &far_rectangle,
        ),
        (
            "triangle-horizon",
            Vec3::new(0.0, 0.0, 0.25),
            Vec3::new(0.2, 0.0, 1.0).normalize(),
            &grazing,
        ),
        ("rectangle-zenith", Vec3::ZERO, Vec3::Z, &around_zenith),
    ];
    let mut list = Vec::new();
    for (case, from, normal, outline) in cases {
        let vertices: Vec<_> = outline.iter().map(|v| v.as_dvec3()).collect();
        let Some(p) = ProjectedPolygon::new(from.as_dvec3(), normal.as_dvec3(), &vertices) else {
            continue;
        };
        let description = format!(
            "convex polygon ∝ cos θ above the horizon (projected solid angle, after Peters 2021), {case}, Ω⊥ {:.2e} sr",
            p.projected_solid_angle()
        );
        let q = p.clone();
        list.push(entry(
            &format!("projected-polygon-{case}"),
            &description,
            cap_around(from, outline),
            // The density is what `pdf` says of the f32 direction returned.
            square(move |u| {
                let w = p.sample(u.as_dvec2()).0.as_vec3();
                (w, p.pdf(w.as_dvec3()) as f32)
            }),
            boxed(move |w: Vec3| q.pdf(w.as_dvec3()) as f32),
        ));
    }
    list
}
