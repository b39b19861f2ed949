//! `solid-angle-cos`: uniform solid-angle sampling of a spherical rectangle or triangle
//! after a bilinear warp of its unit square whose corner weights are cos θ at the corner
//! directions (Hart et al. 2020; pbrt-v4 §6.5.2). The density then follows the cosine of
//! a Lambertian receiver approximately: p(ω) = bilinear(u(ω)) / Ω, where u(ω) is the
//! point of the square that the spherical map sends to ω.

use glam::{Vec2, Vec3};

use crate::sampling::warp::{
    SphericalRectangle, SphericalTriangle, bilinear_pdf, square_to_bilinear,
};

/// Smallest corner weight: keeps the density positive over the whole light (directions
/// below the horizon are rejected later, before any shadow ray).
const MIN_WEIGHT: f32 = 0.01;

/// A spherical polygon sampled uniformly in solid angle through a map of the unit square.
pub(crate) trait SphericalMap {
    /// Direction and density (per steradian) of the point `u` of the square.
    fn sample(&self, u: Vec2) -> (Vec3, f32);
    /// The point of the square that maps to direction `w`.
    fn to_square(&self, w: Vec3) -> Vec2;
    /// Solid angle Ω.
    fn solid_angle(&self) -> f32;
}

impl SphericalMap for SphericalRectangle {
    fn sample(&self, u: Vec2) -> (Vec3, f32) {
        SphericalRectangle::sample(self, u)
    }
    fn to_square(&self, w: Vec3) -> Vec2 {
        SphericalRectangle::to_square(self, w)
    }
    fn solid_angle(&self) -> f32 {
        SphericalRectangle::solid_angle(self)
    }
}

impl SphericalMap for SphericalTriangle {
    fn sample(&self, u: Vec2) -> (Vec3, f32) {
        SphericalTriangle::sample(self, u)
    }
    fn to_square(&self, w: Vec3) -> Vec2 {
        SphericalTriangle::to_square(self, w)
    }
    fn solid_angle(&self) -> f32 {
        SphericalTriangle::solid_angle(self)
    }
}

/// The bilinear weights for a shading point at `x` with normal `n`: cos θ towards each of
/// the `corners` that the square's corners (0, 0), (1, 0), (0, 1), (1, 1) map to.
pub(crate) fn corner_cosines(x: Vec3, n: Vec3, corners: [Vec3; 4]) -> [f32; 4] {
    corners.map(|c| n.dot((c - x).normalize_or_zero()).max(MIN_WEIGHT))
}

/// A direction from `map`, warped by `weights` first when given; with its density.
#[inline]
pub(crate) fn sample(map: &impl SphericalMap, weights: Option<[f32; 4]>, u: Vec2) -> (Vec3, f32) {
    match weights {
        None => map.sample(u),
        Some(w) => {
            let (v, pdf_square) = square_to_bilinear(u, w);
            let (dir, pdf) = map.sample(v);
            (dir, pdf * pdf_square)
        }
    }
}

/// The density of [`sample`] for direction `w` (inside the spherical polygon).
#[inline]
pub(crate) fn pdf(map: &impl SphericalMap, weights: Option<[f32; 4]>, w: Vec3) -> f32 {
    let uniform = 1.0 / map.solid_angle();
    match weights {
        None => uniform,
        Some(weights) => {
            uniform * bilinear_pdf(map.to_square(w).clamp(Vec2::ZERO, Vec2::ONE), weights)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corner orders the callers rely on: the rectangle's square corners map to o,
    /// o + ea, o + eb, o + ea + eb; the triangle's (Arvo's parametrisation) to p1, p1, p0, p2.
    #[test]
    fn square_corners_map_to_the_expected_vertices() {
        let x = Vec3::new(0.1, -0.2, -1.0);
        let (o, ea, eb) = (
            Vec3::new(-0.5, -0.4, 0.3),
            Vec3::new(1.2, 0.0, 0.0),
            Vec3::new(0.0, 0.9, 0.2),
        );
        let square = [Vec2::ZERO, Vec2::X, Vec2::Y, Vec2::splat(0.9999)];
        let sr = SphericalRectangle::new(x, o, ea, eb).expect("rectangle");
        for (u, c) in square.iter().zip([o, o + ea, o + eb, o + ea + eb]) {
            let d = SphericalMap::sample(&sr, *u).0;
            assert!(d.dot((c - x).normalize()) > 0.9999, "rectangle {u}");
        }
        let (p0, p1, p2) = (
            Vec3::new(-0.5, 0.0, 0.3),
            Vec3::new(0.7, -0.2, 0.4),
            Vec3::new(0.1, 0.9, 0.2),
        );
        let st = SphericalTriangle::new(x, p0, p1, p2).expect("triangle");
        for (u, c) in square.iter().zip([p1, p1, p0, p2]) {
            let d = SphericalMap::sample(&st, *u).0;
            assert!(d.dot((c - x).normalize()) > 0.9999, "triangle {u}");
        }
    }
}
