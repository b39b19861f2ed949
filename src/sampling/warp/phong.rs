//! The Phong lobe cosⁿ α around +z, the importance-sampling part of the Phong BRDF
//! (lecture: θ = arccos ξ₁^(1/(n+1)), φ = 2πξ₂).

use glam::{Vec2, Vec3};

use super::sphere::{direction_from_z_phi, phi_of};
use crate::math::{INV_TWO_PI, PI};

/// Direction around +z distributed ∝ cosⁿ θ: cos θ = u₀^(1/(n+1)), φ = 2πu₁.
/// pdf = (n + 1)/(2π) · cosⁿ θ per sr.
#[inline]
pub fn square_to_phong_lobe(u: Vec2, exponent: f32) -> (Vec3, f32) {
    let cos_theta = u.x.powf(1.0 / (exponent + 1.0));
    let w = direction_from_z_phi(cos_theta, 2.0 * PI * u.y);
    (w, phong_lobe_pdf(w, exponent))
}

/// Density of [`square_to_phong_lobe`]: (n + 1)/(2π) · cosⁿ θ per sr for cos θ > 0.
#[inline]
pub fn phong_lobe_pdf(w: Vec3, exponent: f32) -> f32 {
    if w.z <= 0.0 {
        return 0.0;
    }
    (exponent + 1.0) * INV_TWO_PI * w.z.powf(exponent)
}

/// Inverse of [`square_to_phong_lobe`].
#[inline]
pub fn phong_lobe_to_square(w: Vec3, exponent: f32) -> Vec2 {
    Vec2::new(w.z.max(0.0).powf(exponent + 1.0), phi_of(w) / (2.0 * PI))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phong_lobe_round_trips() {
        for n in [1.0, 10.0, 1000.0] {
            let u = Vec2::new(0.4, 0.3);
            let (w, pdf) = square_to_phong_lobe(u, n);
            assert!(pdf > 0.0 && pdf.is_finite());
            assert!((phong_lobe_to_square(w, n) - u).length() < 2e-3);
        }
    }
}
