//! Mitsuba 3's `roughconductor`: a Torrance–Sparrow microfacet metal (Walter et al. 2007,
//! eq. 20) f = F(w_out·h)·D(h)·G(w_in, w_out, h)/(4 cos θ_in cos θ_out), with conductor
//! Fresnel, Smith's separable G, and h = (w_in + w_out)/|w_in + w_out|.
//! Sampling draws a microfacet normal m (visible normals for GGX) and reflects w_out
//! about it; the solid-angle density of w_in is p(m)/(4 |w_out·m|) (Walter et al. 2007,
//! eq. 14), which for visible normals is G1(w_out, m)·D(m)/(4 cos θ_out).

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_conductor;
use super::microfacet::{Microfacet, MicrofacetType, half_vector, reflect};
use super::{Bsdf, BsdfSample, ConductorMaterial, sample_at};
use crate::math::Spectrum;

/// A rough conductor with Mitsuba 3's parameter names.
#[derive(Clone, Debug)]
pub struct RoughConductor {
    /// Beckmann (Mitsuba's default) or GGX.
    pub distribution: MicrofacetType,
    /// Roughness α (the RMS slope for Beckmann); clamped to 10⁻⁴.
    pub alpha: f32,
    /// Real part of the relative index of refraction.
    pub eta: Spectrum,
    /// Imaginary part (absorption).
    pub k: Spectrum,
    /// Tint multiplying the Fresnel term (Mitsuba's `specular_reflectance`).
    pub specular_reflectance: Spectrum,
}

impl Default for RoughConductor {
    /// Mitsuba 3's defaults: Beckmann, α = 0.1, material "none" (Fresnel = 1), no tint.
    fn default() -> RoughConductor {
        RoughConductor::from_material(MicrofacetType::Beckmann, 0.1, ConductorMaterial::None)
    }
}

impl RoughConductor {
    /// A named material with no tint.
    pub fn from_material(
        distribution: MicrofacetType,
        alpha: f32,
        material: ConductorMaterial,
    ) -> RoughConductor {
        let (eta, k) = material.ior();
        RoughConductor {
            distribution,
            alpha,
            eta,
            k,
            specular_reflectance: Spectrum::ONE,
        }
    }

    /// The microfacet distribution with the clamped roughness.
    pub fn microfacet(&self) -> Microfacet {
        Microfacet::isotropic(self.distribution, self.alpha)
    }
}

impl RoughConductor {
    /// f (when `F`) and the sampling density (when `P`) at (w_in, w_out), from one half
    /// vector, one D(h) and one G1(w_out, h): `eval`, `pdf` and `eval_pdf` are this one
    /// formula, so they agree bit for bit.
    #[inline(always)]
    fn terms<const F: bool, const P: bool>(&self, w_in: Vec3, w_out: Vec3) -> (Spectrum, f32) {
        if w_in.z <= 0.0 || w_out.z <= 0.0 {
            return (Spectrum::ZERO, 0.0);
        }
        let Some(h) = half_vector(w_in, w_out) else {
            return (Spectrum::ZERO, 0.0);
        };
        let mf = self.microfacet();
        let d = mf.d(h);
        let g1_out = mf.g1(w_out, h);
        let f = if !F || d == 0.0 {
            Spectrum::ZERO
        } else {
            let g = mf.g1(w_in, h) * g1_out;
            let fresnel = fresnel_conductor(w_out.dot(h), self.eta, self.k);
            fresnel * self.specular_reflectance * (d * g / (4.0 * w_in.z * w_out.z))
        };
        // p(h)/(4 w_out·h) per steradian, p the microfacet sampling density.
        let cos_out = w_out.dot(h);
        let pdf = if !P || cos_out <= 0.0 || w_in.dot(h) <= 0.0 {
            0.0
        } else {
            mf.sample_pdf_from(w_out, h, d, g1_out) / (4.0 * cos_out)
        };
        (f, pdf)
    }
}

impl Bsdf for RoughConductor {
    fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum {
        self.terms::<true, false>(w_in, w_out).0
    }

    /// Draws m (u as is), reflects w_out about it; `None` when m faces away from w_out or
    /// the reflection goes below the surface (that mass is lost, not renormalised).
    fn sample(&self, w_out: Vec3, u: Vec2) -> Option<BsdfSample> {
        if w_out.z <= 0.0 {
            return None;
        }
        let m = self.microfacet().sample_normal(w_out, u);
        if w_out.dot(m) <= 0.0 {
            return None;
        }
        let w_in = reflect(w_out, m);
        if w_in.z <= 0.0 {
            return None;
        }
        sample_at(self, w_in, w_out)
    }

    /// p(h)/(4 w_out·h) per steradian, p the microfacet sampling density.
    fn pdf(&self, w_in: Vec3, w_out: Vec3) -> f32 {
        self.terms::<false, true>(w_in, w_out).1
    }

    fn eval_pdf(&self, w_in: Vec3, w_out: Vec3) -> (Spectrum, f32) {
        self.terms::<true, true>(w_in, w_out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_agrees_with_eval_and_pdf() {
        for distribution in MicrofacetType::ALL {
            for alpha in [0.005, 0.05, 0.3, 1.0] {
                let b = RoughConductor::from_material(distribution, alpha, ConductorMaterial::Au);
                let w_out = Vec3::new(0.5, 0.2, 0.6).normalize();
                for i in 0..400 {
                    let u = Vec2::new(
                        (i % 20) as f32 / 20.0 + 0.025,
                        (i / 20) as f32 / 20.0 + 0.025,
                    );
                    if let Some(s) = b.sample(w_out, u) {
                        assert!(s.w_in.z > 0.0 && !s.delta);
                        assert_eq!(s.pdf, b.pdf(s.w_in, w_out));
                        assert_eq!(s.f, b.eval(s.w_in, w_out));
                    }
                }
            }
        }
    }

    #[test]
    fn reciprocal_and_zero_below() {
        let b = RoughConductor::from_material(MicrofacetType::Ggx, 0.3, ConductorMaterial::Cu);
        let (a, c) = (
            Vec3::new(0.3, -0.2, 0.9).normalize(),
            Vec3::new(-0.6, 0.1, 0.5).normalize(),
        );
        assert!(
            (b.eval(a, c) - b.eval(c, a)).abs().max_element() < 1e-5 * b.eval(a, c).max_element()
        );
        assert_eq!(b.eval(-a, c), Spectrum::ZERO);
        assert_eq!(b.pdf(a, -c), 0.0);
        assert!(b.sample(-c, Vec2::splat(0.5)).is_none());
    }
}
