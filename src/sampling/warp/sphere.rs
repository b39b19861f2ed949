//! Uniform directions on the whole sphere: by the (z, φ) parameterisation and by
//! rejection from the cube [-1, 1]³ (the lecture's "random directions").

use glam::{Vec2, Vec3};

use crate::math::{INV_FOUR_PI, PI, safe_sqrt};
use crate::sampling::Uniform;

/// The direction ω(z, φ) = (√(1−z²) cos φ, √(1−z²) sin φ, z): equal steps in z cut
/// equal areas from the sphere (Archimedes' hat-box theorem), so uniform z and φ give
/// uniform directions.
#[inline]
pub fn direction_from_z_phi(z: f32, phi: f32) -> Vec3 {
    let r = safe_sqrt(1.0 - z * z);
    let (sin_phi, cos_phi) = phi.sin_cos();
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// φ of a direction in [0, 2π).
#[inline]
pub fn phi_of(w: Vec3) -> f32 {
    let phi = w.y.atan2(w.x);
    if phi < 0.0 { phi + 2.0 * PI } else { phi }
}

/// Uniform direction on the unit sphere, z = 1 − 2u₀, φ = 2πu₁. pdf = 1/(4π) per sr.
///
/// ```
/// use lightlab::sampling::warp::square_to_uniform_sphere;
/// let (w, pdf) = square_to_uniform_sphere(glam::Vec2::new(0.25, 0.5));
/// assert!((w.length() - 1.0).abs() < 1e-6 && pdf > 0.0);
/// ```
#[inline]
pub fn square_to_uniform_sphere(u: Vec2) -> (Vec3, f32) {
    let w = direction_from_z_phi(1.0 - 2.0 * u.x, 2.0 * PI * u.y);
    (w, uniform_sphere_pdf(w))
}

/// Density of [`square_to_uniform_sphere`]: 1/(4π) per steradian.
#[inline]
pub fn uniform_sphere_pdf(_w: Vec3) -> f32 {
    INV_FOUR_PI
}

/// Inverse of [`square_to_uniform_sphere`].
#[inline]
pub fn uniform_sphere_to_square(w: Vec3) -> Vec2 {
    Vec2::new((1.0 - w.z) * 0.5, phi_of(w) / (2.0 * PI))
}

/// Uniform direction on the sphere by rejection: draw points in [-1, 1]³ until one lies
/// inside the unit ball (acceptance π/6 ≈ 52%), then normalise. pdf = 1/(4π) per sr.
pub fn cube_rejection_to_sphere(src: &mut impl Uniform) -> (Vec3, f32) {
    loop {
        let a = src.next_2d();
        let b = src.next_1d();
        let p = Vec3::new(2.0 * a.x - 1.0, 2.0 * a.y - 1.0, 2.0 * b - 1.0);
        let r2 = p.length_squared();
        // Reject the outside and a tiny core where normalising loses precision.
        if r2 <= 1.0 && r2 > 1e-6 {
            let w = p / r2.sqrt();
            return (w, uniform_sphere_pdf(w));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::rng::Rng32;

    #[test]
    fn sphere_round_trips_and_edges_are_finite() {
        for u in [
            Vec2::new(0.3, 0.7),
            Vec2::new(0.9, 0.1),
            Vec2::new(0.5, 0.999),
        ] {
            let (w, _) = square_to_uniform_sphere(u);
            assert!((uniform_sphere_to_square(w) - u).length() < 1e-4);
        }
        for u in [Vec2::ZERO, Vec2::ONE, Vec2::new(0.0, 1.0)] {
            let (w, pdf) = square_to_uniform_sphere(u);
            assert!(w.is_finite() && pdf.is_finite());
        }
    }

    #[test]
    fn cube_rejection_gives_unit_vectors() {
        let mut rng = Rng32::new(3);
        for _ in 0..1000 {
            let (w, _) = cube_rejection_to_sphere(&mut rng);
            assert!((w.length() - 1.0).abs() < 1e-5);
        }
    }
}
