//! Uniform directions in a cone around +z (the solid angle a sphere light subtends).

use glam::{Vec2, Vec3};

use super::sphere::phi_of;
use crate::math::{PI, safe_sqrt};
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// The cone's 1 − cos θmax, with cos θmax clamped to [−1, 1 − ε/2] so the solid angle
/// 2π(1 − cos θmax) is never zero. Cones narrower than θmax ≈ 3·10⁻⁴ rad are therefore
/// widened to that size; callers with smaller cones should treat the light as a point.
#[inline]
fn one_minus_cos(cos_theta_max: f32) -> f32 {
    1.0 - cos_theta_max.clamp(-1.0, ONE_MINUS_EPSILON)
}

/// Uniform direction in the cone θ ≤ θmax around +z: cos θ = 1 − u₀(1 − cos θmax),
/// φ = 2πu₁ (Archimedes: equal steps in z cut equal areas). pdf = 1/(2π(1 − cos θmax))
/// per sr (pbrt-v4 §A.5.4, `SampleUniformCone`).
///
/// ```
/// use lightlab::sampling::warp::square_to_uniform_cone;
/// let (w, pdf) = square_to_uniform_cone(glam::Vec2::new(0.3, 0.6), 0.9);
/// assert!(w.z >= 0.9 && pdf > 0.0);
/// ```
#[inline]
pub fn square_to_uniform_cone(u: Vec2, cos_theta_max: f32) -> (Vec3, f32) {
    // Work with 1 − z (exact for narrow cones, where z rounds to 1): sin²θ = (1 − z)(1 + z).
    let one_minus_z = u.x * one_minus_cos(cos_theta_max);
    let z = 1.0 - one_minus_z;
    let sin_theta = safe_sqrt(one_minus_z * (2.0 - one_minus_z));
    let (sin_phi, cos_phi) = (2.0 * PI * u.y).sin_cos();
    let w = Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, z);
    (w, uniform_cone_pdf(w, cos_theta_max))
}

/// Density of [`square_to_uniform_cone`]: 1/(2π(1 − cos θmax)) per sr inside the cone,
/// else 0.
#[inline]
pub fn uniform_cone_pdf(w: Vec3, cos_theta_max: f32) -> f32 {
    let c = 1.0 - one_minus_cos(cos_theta_max);
    if w.z >= c {
        1.0 / (2.0 * PI * one_minus_cos(cos_theta_max))
    } else {
        0.0
    }
}

/// Inverse of [`square_to_uniform_cone`].
#[inline]
pub fn uniform_cone_to_square(w: Vec3, cos_theta_max: f32) -> Vec2 {
    // 1 − z = (x² + y²)/(1 + z): exact for narrow cones, where z rounds to 1.
    let one_minus_z = if w.z > 0.0 {
        (w.x * w.x + w.y * w.y) / (1.0 + w.z)
    } else {
        1.0 - w.z
    };
    let u0 = one_minus_z / one_minus_cos(cos_theta_max);
    Vec2::new(u0.clamp(0.0, 1.0), phi_of(w) / (2.0 * PI))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cone_round_trips_and_stays_inside() {
        for cos_max in [-1.0, 0.0, 0.5, 0.999, 1.0] {
            for u in [
                Vec2::new(0.3, 0.7),
                Vec2::new(0.9, 0.1),
                Vec2::ZERO,
                Vec2::ONE,
            ] {
                let (w, pdf) = square_to_uniform_cone(u, cos_max);
                assert!(
                    w.is_finite() && pdf.is_finite() && pdf > 0.0,
                    "{cos_max} {u}"
                );
                assert!((w.length() - 1.0).abs() < 1e-5);
            }
            let u = Vec2::new(0.3, 0.7);
            let (w, _) = square_to_uniform_cone(u, cos_max);
            if cos_max < 1.0 {
                assert!((uniform_cone_to_square(w, cos_max) - u).length() < 1e-4);
            }
        }
    }
}
