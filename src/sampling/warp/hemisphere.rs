//! Directions on the hemisphere around +z: uniform by (z, φ), uniform by rejection from
//! the cube, the biased "uniform (θ, φ)" teaching example, and cosine-weighted by
//! Malley's method (a disk point lifted to the hemisphere).

use glam::{Vec2, Vec3};

use super::disk::{
    disk_rejection, square_to_uniform_disk_concentric, uniform_disk_concentric_to_square,
};
use super::sphere::{cube_rejection_to_sphere, direction_from_z_phi, phi_of};
use crate::math::{INV_PI, INV_TWO_PI, PI, safe_sqrt};
use crate::sampling::Uniform;

/// Uniform direction on the hemisphere z ≥ 0: z = u₀, φ = 2πu₁ (the lecture's ω(z, φ)).
/// pdf = 1/(2π) per sr.
///
/// ```
/// use lightlab::sampling::warp::square_to_uniform_hemisphere;
/// let (w, pdf) = square_to_uniform_hemisphere(glam::Vec2::new(0.5, 0.25));
/// assert!(w.z >= 0.0 && (pdf - 1.0 / (2.0 * std::f32::consts::PI)).abs() < 1e-6);
/// ```
#[inline]
pub fn square_to_uniform_hemisphere(u: Vec2) -> (Vec3, f32) {
    let w = direction_from_z_phi(u.x, 2.0 * PI * u.y);
    (w, uniform_hemisphere_pdf(w))
}

/// Density of [`square_to_uniform_hemisphere`]: 1/(2π) per sr above the horizon, else 0.
#[inline]
pub fn uniform_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z >= 0.0 { INV_TWO_PI } else { 0.0 }
}

/// Inverse of [`square_to_uniform_hemisphere`].
#[inline]
pub fn uniform_hemisphere_to_square(w: Vec3) -> Vec2 {
    Vec2::new(w.z, phi_of(w) / (2.0 * PI))
}

/// Uniform hemisphere direction by rejection from the cube [-1, 1]³, mirrored into
/// z ≥ 0. pdf = 1/(2π) per sr.
pub fn cube_rejection_to_hemisphere(src: &mut impl Uniform) -> (Vec3, f32) {
    let (w, _) = cube_rejection_to_sphere(src);
    let w = Vec3::new(w.x, w.y, w.z.abs());
    (w, uniform_hemisphere_pdf(w))
}

/// The lecture's "1st try": θ = (π/2)u₀ and φ = 2πu₁ uniform. Not uniform in solid
/// angle — directions crowd at the pole — and its true pdf is 1/(π² sin θ) per sr.
/// Kept as a teaching example; an estimator must divide by this pdf to stay unbiased.
#[inline]
pub fn square_to_theta_phi_hemisphere(u: Vec2) -> (Vec3, f32) {
    let theta = 0.5 * PI * u.x;
    let w = direction_from_z_phi(theta.cos(), 2.0 * PI * u.y);
    (w, theta_phi_hemisphere_pdf(w))
}

/// Density of [`square_to_theta_phi_hemisphere`]: 1/(π² sin θ) per sr (the Jacobian of
/// (θ, φ) ↦ ω is sin θ and the (θ, φ) density is 1/π²).
#[inline]
pub fn theta_phi_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z < 0.0 {
        return 0.0;
    }
    let sin_theta = safe_sqrt(1.0 - w.z * w.z);
    if sin_theta == 0.0 {
        f32::INFINITY
    } else {
        INV_PI * INV_PI / sin_theta
    }
}

/// Inverse of [`square_to_theta_phi_hemisphere`].
#[inline]
pub fn theta_phi_hemisphere_to_square(w: Vec3) -> Vec2 {
    Vec2::new(
        w.z.clamp(-1.0, 1.0).acos() / (0.5 * PI),
        phi_of(w) / (2.0 * PI),
    )
}

/// Cosine-weighted direction by Malley's method: a uniform point (x, y) on the unit disk
/// (Shirley–Chiu concentric map) lifted to (x, y, √(1 − x² − y²)). pdf = cos θ/π per sr.
///
/// ```
/// use lightlab::sampling::warp::{square_to_cosine_hemisphere, cosine_hemisphere_pdf};
/// let (w, pdf) = square_to_cosine_hemisphere(glam::Vec2::new(0.1, 0.9));
/// assert!((pdf - cosine_hemisphere_pdf(w)).abs() < 1e-6);
/// ```
#[inline]
pub fn square_to_cosine_hemisphere(u: Vec2) -> (Vec3, f32) {
    let d = square_to_uniform_disk_concentric(u);
    let w = lift_to_hemisphere(d);
    (w, cosine_hemisphere_pdf(w))
}

/// Density of the cosine-weighted hemisphere: cos θ/π per sr above the horizon, else 0.
#[inline]
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    w.z.max(0.0) * INV_PI
}

/// Inverse of [`square_to_cosine_hemisphere`].
#[inline]
pub fn cosine_hemisphere_to_square(w: Vec3) -> Vec2 {
    uniform_disk_concentric_to_square(Vec2::new(w.x, w.y))
}

/// Malley's method exactly as on the slide: a point on the square [-1, 1]², rejected
/// outside the unit disk, lifted to the hemisphere. pdf = cos θ/π per sr.
pub fn malley_rejection_hemisphere(src: &mut impl Uniform) -> (Vec3, f32) {
    let w = lift_to_hemisphere(disk_rejection(src));
    (w, cosine_hemisphere_pdf(w))
}

/// Malley's lift: the uniform disk projects to the cosine-weighted hemisphere because
/// the area element of the disk is cos θ dω.
#[inline]
fn lift_to_hemisphere(d: Vec2) -> Vec3 {
    Vec3::new(d.x, d.y, safe_sqrt(1.0 - d.length_squared()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverses_round_trip() {
        for u in [
            Vec2::new(0.3, 0.7),
            Vec2::new(0.9, 0.1),
            Vec2::new(0.05, 0.6),
        ] {
            let (w, _) = square_to_uniform_hemisphere(u);
            assert!((uniform_hemisphere_to_square(w) - u).length() < 1e-4);
            let (w, _) = square_to_cosine_hemisphere(u);
            assert!((cosine_hemisphere_to_square(w) - u).length() < 1e-4);
            let (w, _) = square_to_theta_phi_hemisphere(u);
            assert!((theta_phi_hemisphere_to_square(w) - u).length() < 1e-4);
        }
    }

    #[test]
    fn edges_are_finite() {
        for u in [
            Vec2::ZERO,
            Vec2::ONE,
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ] {
            for (w, pdf) in [
                square_to_uniform_hemisphere(u),
                square_to_cosine_hemisphere(u),
            ] {
                assert!(w.is_finite() && pdf.is_finite() && w.z >= 0.0);
            }
        }
    }
}
