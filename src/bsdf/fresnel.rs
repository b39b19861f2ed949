//! Fresnel reflectance of smooth interfaces: dielectric (real η) and conductor (complex
//! η + ik per RGB channel), plus the hemispherical average of the dielectric one.
//! Unpolarised light throughout (the mean of the s and p reflectances).

use glam::Vec4;

use crate::math::Spectrum;

/// Unpolarised Fresnel reflectance of a dielectric interface with relative index
/// `eta` = η_inside/η_outside, for light at cos θ_i = `cos_theta_i` (negative from the
/// inside). Returns 1 under total internal reflection and 0 for index-matched media
/// (Born & Wolf, "Principles of Optics", §1.5.2; Mitsuba 3's `fresnel`).
pub fn fresnel_dielectric(cos_theta_i: f32, eta: f32) -> f32 {
    if eta == 1.0 {
        return 0.0;
    }
    // From the inside the roles of the two media swap.
    let eta_it = if cos_theta_i >= 0.0 { eta } else { 1.0 / eta };
    let cos_i = cos_theta_i.abs().min(1.0);
    if cos_i == 0.0 {
        return 1.0;
    }
    // Snell: sin²θ_t = sin²θ_i / η².
    let sin2_t = (1.0 - cos_i * cos_i) / (eta_it * eta_it);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_s = (cos_i - eta_it * cos_t) / (cos_i + eta_it * cos_t);
    let r_p = (eta_it * cos_i - cos_t) / (eta_it * cos_i + cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// Unpolarised Fresnel reflectance of a conductor with complex relative index
/// η + ik per channel, at cos θ_i = `cos_theta_i` ≥ 0 (the closed form of
/// K. D. Moeller, "Optics", 1988, as Mitsuba 3's `fresnel_conductor` uses it).
/// η = 0, k = 1 gives 1 at every angle: Mitsuba's material "none".
///
/// The three channels run in the lanes of one vector (the fourth repeats the first): the
/// operations of the one-channel formula (`conductor_channel` in the tests, which the
/// lanes match bit for bit) in the same order, one division per step for all channels
/// instead of three (glam takes the square roots lane by lane).
pub fn fresnel_conductor(cos_theta_i: f32, eta: Spectrum, k: Spectrum) -> Spectrum {
    let c = cos_theta_i.clamp(0.0, 1.0);
    let lanes = |v: Spectrum| Vec4::new(v.x, v.y, v.z, v.x);
    let r = conductor_lanes(c, lanes(eta), lanes(k));
    Spectrum::new(r.x, r.y, r.z)
}

/// With a² + b² = |η̂² − sin²θ| and a = √((|η̂² − sin²θ| + Re(η̂² − sin²θ))/2),
/// R_s = (a² + b² + cos²θ − 2a cos θ)/(a² + b² + cos²θ + 2a cos θ),
/// R_p = R_s ((a² + b²) cos²θ + sin⁴θ − 2a cos θ sin²θ)/((a² + b²) cos²θ + sin⁴θ + 2a cos θ sin²θ),
/// R = (R_s + R_p)/2 per lane.
#[inline]
fn conductor_lanes(cos: f32, eta: Vec4, k: Vec4) -> Vec4 {
    let cos2 = cos * cos;
    let sin2 = 1.0 - cos2;
    let sin4 = sin2 * sin2;
    let t1 = eta * eta - k * k - sin2;
    let a2_plus_b2 = (t1 * t1 + 4.0 * k * k * eta * eta).max(Vec4::ZERO).sqrt();
    let a = (0.5 * (a2_plus_b2 + t1)).max(Vec4::ZERO).sqrt();
    let term1 = a2_plus_b2 + cos2;
    let term2 = 2.0 * cos * a;
    let r_s = (term1 - term2) / (term1 + term2);
    let term3 = a2_plus_b2 * cos2 + sin4;
    let term4 = term2 * sin2;
    let r_p = r_s * (term3 - term4) / (term3 + term4);
    let r = 0.5 * (r_s + r_p);
    // 0/0 only at grazing incidence on an index-matched conductor, or at normal
    // incidence with η = k = 0: reflect fully.
    Vec4::select(
        r.is_finite_mask(),
        r.clamp(Vec4::ZERO, Vec4::ONE),
        Vec4::ONE,
    )
}

/// Hemispherical average 2∫ F(cos θ) cos θ d(cos θ) of [`fresnel_dielectric`] for
/// relative index `eta`, by the polynomial fits Mitsuba 3 uses: Egan & Hilgeman (1973)
/// for η < 1 and d'Eon & Irving (2011) otherwise (relative error ≤ 0.2% for η ∈ [1, 10]).
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        // Horner in 1/η.
        let c = [0.919_317, -3.4793, 6.753_35, -7.809_89, 4.985_54, -1.368_81];
        c.iter().rev().fold(0.0, |acc, &ci| acc * inv + ci)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dielectric_known_values() {
        // Normal incidence: ((η − 1)/(η + 1))² = 0.04 for η = 1.5.
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        // Same from the inside.
        assert!((fresnel_dielectric(-1.0, 1.5) - 0.04).abs() < 1e-6);
        // Total internal reflection beyond the critical angle asin(1/1.5) ≈ 41.8°.
        assert_eq!(fresnel_dielectric(-(50f32.to_radians().cos()), 1.5), 1.0);
        // Brewster angle atan(1.5): R_p = 0, so R = R_s/2 with R_s = (5/13)².
        let cos_b = 1.5f32.atan().cos();
        let r = fresnel_dielectric(cos_b, 1.5);
        assert!((r - 0.5 * (5.0f32 / 13.0).powi(2)).abs() < 1e-5, "{r}");
        assert_eq!(fresnel_dielectric(0.0, 1.5), 1.0);
        assert_eq!(fresnel_dielectric(0.3, 1.0), 0.0);
    }

    /// One channel of [`fresnel_conductor`], the formula as written (see
    /// `conductor_lanes`).
    fn conductor_channel(cos: f32, eta: f32, k: f32) -> f32 {
        let cos2 = cos * cos;
        let sin2 = 1.0 - cos2;
        let sin4 = sin2 * sin2;
        let t1 = eta * eta - k * k - sin2;
        let a2_plus_b2 = (t1 * t1 + 4.0 * k * k * eta * eta).max(0.0).sqrt();
        let a = (0.5 * (a2_plus_b2 + t1)).max(0.0).sqrt();
        let term1 = a2_plus_b2 + cos2;
        let term2 = 2.0 * cos * a;
        let r_s = (term1 - term2) / (term1 + term2);
        let term3 = a2_plus_b2 * cos2 + sin4;
        let term4 = term2 * sin2;
        let r_p = r_s * (term3 - term4) / (term3 + term4);
        let r = 0.5 * (r_s + r_p);
        if r.is_finite() {
            r.clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    #[test]
    fn lanes_match_the_one_channel_formula_bit_for_bit() {
        let etas = [0.0f32, 0.05, 0.2, 0.9, 1.0, 1.5, 2.7, 40.0];
        let ks = [0.0f32, 0.3, 1.0, 3.9, 7.5, 100.0, 1e20];
        let coss = [-0.0f32, 0.0, 1e-23, 1e-6, 0.01, 0.2, 0.5, 0.77, 0.999, 1.0];
        for (i, &cos) in coss.iter().enumerate() {
            for (j, &eta) in etas.iter().enumerate() {
                for (l, &k) in ks.iter().enumerate() {
                    // Each channel a different (η, k) pair, so a lane mix-up shows.
                    let e =
                        Spectrum::new(eta, etas[(j + 3) % etas.len()], etas[(j + i) % etas.len()]);
                    let kk = Spectrum::new(k, ks[(l + 1) % ks.len()], ks[(l + 4) % ks.len()]);
                    let got = fresnel_conductor(cos, e, kk);
                    for c in 0..3 {
                        let want = conductor_channel(cos, e[c], kk[c]);
                        assert_eq!(got[c].to_bits(), want.to_bits(), "cos {cos} η {e} k {kk}");
                    }
                }
            }
        }
    }

    #[test]
    fn conductor_reduces_to_dielectric_for_zero_k() {
        for cos in [1.0f32, 0.7, 0.3, 0.05] {
            let c = fresnel_conductor(cos, Spectrum::splat(1.5), Spectrum::ZERO).x;
            assert!((c - fresnel_dielectric(cos, 1.5)).abs() < 1e-5, "{cos}");
        }
    }

    #[test]
    fn conductor_none_is_a_perfect_mirror() {
        for cos in [1.0f32, 0.5, 0.01, 0.0] {
            let f = fresnel_conductor(cos, Spectrum::ZERO, Spectrum::ONE);
            assert!((f - Spectrum::ONE).abs().max_element() < 1e-6, "{cos}: {f}");
        }
    }

    #[test]
    fn conductor_normal_incidence() {
        // ((η − 1)² + k²)/((η + 1)² + k²).
        let (eta, k) = (0.2f32, 3.9f32);
        let expected = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        let f = fresnel_conductor(1.0, Spectrum::splat(eta), Spectrum::splat(k));
        assert!((f.x - expected).abs() < 1e-5);
    }

    #[test]
    fn diffuse_reflectance_matches_quadrature() {
        for eta in [1.2f32, 1.49, 2.0, 1.0 / 1.49] {
            let n = 20_000;
            let integral: f32 = (0..n)
                .map(|i| {
                    let mu = (i as f32 + 0.5) / n as f32;
                    2.0 * fresnel_dielectric(mu, eta) * mu / n as f32
                })
                .sum();
            let fit = fresnel_diffuse_reflectance(eta);
            assert!(
                (fit - integral).abs() < 0.01 * integral.max(0.05),
                "{eta}: {fit} vs {integral}"
            );
        }
    }
}
