//! Mitsuba 3's `roughplastic`: a diffuse base under a rough dielectric coat,
//!
//! f = F(w_out·h, η)·D·G/(4 cos θ_in cos θ_out)·k_s
//!     + k_d/(1 − k_d^[nonlinear]·R_int)·T(cos θ_in)·T(cos θ_out)/(π η²),
//!
//! with T the coat's transmittance and R_int its internal reflectance (Weidlich &
//! Wilkie 2007, "Arbitrarily Layered Micro-Facet Surfaces", with Mitsuba's normalisation
//! of the base). The specular lobe is sampled with probability ∝ (1 − T(cos θ_out))·s
//! against T(cos θ_out)·(1 − s), s = mean k_s/(mean k_d + mean k_s), as Mitsuba does.

use glam::{Vec2, Vec3};

use super::coat::CoatTables;
use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetType, half_vector, reflect};
use super::{Bsdf, BsdfSample, reuse_above, sample_at};
use crate::math::{INV_PI, Spectrum};
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};

/// Index of refraction of polypropylene, Mitsuba's default `int_ior`.
pub const POLYPROPYLENE_IOR: f32 = 1.49;
/// Index of refraction of air, Mitsuba's default `ext_ior`.
pub const AIR_IOR: f32 = 1.000_277;

/// The parameters of a (rough or smooth) plastic, with Mitsuba 3's names.
#[derive(Clone, Debug, PartialEq)]
pub struct PlasticParams {
    /// Albedo of the diffuse base.
    pub diffuse_reflectance: Spectrum,
    /// Tint of the coat's reflection (not physical).
    pub specular_reflectance: Spectrum,
    /// Coat roughness (ignored by the smooth `Plastic`).
    pub alpha: f32,
    /// Coat distribution (ignored by the smooth `Plastic`).
    pub distribution: MicrofacetType,
    /// Index of refraction inside the coat.
    pub int_ior: f32,
    /// Index of refraction outside.
    pub ext_ior: f32,
    /// Account for the colour shift of internal scattering: divide by 1 − k_d·R_int
    /// rather than 1 − R_int.
    pub nonlinear: bool,
}

impl Default for PlasticParams {
    /// Mitsuba 3's defaults: k_d = 0.5, k_s = 1, Beckmann α = 0.1, polypropylene in air.
    fn default() -> PlasticParams {
        PlasticParams {
            diffuse_reflectance: Spectrum::splat(0.5),
            specular_reflectance: Spectrum::ONE,
            alpha: 0.1,
            distribution: MicrofacetType::Beckmann,
            int_ior: POLYPROPYLENE_IOR,
            ext_ior: AIR_IOR,
            nonlinear: false,
        }
    }
}

impl PlasticParams {
    /// η = int_ior/ext_ior, or an error naming the bad indices (Mitsuba's check).
    pub fn eta(&self) -> Result<f32, String> {
        let (i, e) = (self.int_ior, self.ext_ior);
        if !(i > 0.0 && e > 0.0 && i.is_finite() && e.is_finite()) || i == e {
            return Err(format!(
                "plastic: int_ior ({i}) and ext_ior ({e}) must be positive, finite and differ"
            ));
        }
        Ok(i / e)
    }

    /// The share s = mean k_s/(mean k_d + mean k_s) steering lobe choice (½ if both are 0).
    pub fn specular_sampling_weight(&self) -> f32 {
        let d = self.diffuse_reflectance.element_sum() / 3.0;
        let s = self.specular_reflectance.element_sum() / 3.0;
        if d + s > 0.0 { s / (d + s) } else { 0.5 }
    }

    /// k_d/(1 − R·(k_d or 1)), the base albedo renormalised for internal scattering.
    pub fn normalised_diffuse(&self, internal_reflectance: f32) -> Spectrum {
        let kd = self.diffuse_reflectance;
        let r = if self.nonlinear {
            kd * internal_reflectance
        } else {
            Spectrum::splat(internal_reflectance)
        };
        kd / (Spectrum::ONE - r)
    }
}

/// A rough plastic; build it with [`RoughPlastic::new`], which tabulates the coat.
#[derive(Clone, Debug)]
pub struct RoughPlastic {
    params: PlasticParams,
    eta: f32,
    tables: CoatTables,
}

impl RoughPlastic {
    /// Validates the indices and precomputes the coat's albedo tables (about 10⁶
    /// microfacet evaluations).
    pub fn new(params: PlasticParams) -> Result<RoughPlastic, String> {
        let eta = params.eta()?;
        if !(params.alpha >= 0.0 && params.alpha.is_finite()) {
            return Err(format!(
                "roughplastic: alpha ({}) must be ≥ 0",
                params.alpha
            ));
        }
        let mf = Microfacet::isotropic(params.distribution, params.alpha);
        let tables = CoatTables::new(&mf, eta);
        Ok(RoughPlastic {
            params,
            eta,
            tables,
        })
    }

    /// The parameters it was built from.
    pub fn params(&self) -> &PlasticParams {
        &self.params
    }

    /// The coat's tables.
    pub fn tables(&self) -> &CoatTables {
        &self.tables
    }

    fn microfacet(&self) -> Microfacet {
        Microfacet::isotropic(self.params.distribution, self.params.alpha)
    }

    /// Probability of sampling the specular lobe when looking from `w_out`.
    fn specular_probability(&self, w_out: Vec3) -> f32 {
        let t = self.tables.transmittance(w_out.z);
        let s = self.params.specular_sampling_weight();
        let (ps, pd) = ((1.0 - t) * s, t * (1.0 - s));
        if ps + pd > 0.0 { ps / (ps + pd) } else { 0.5 }
    }
}

impl RoughPlastic {
    /// f (when `F`) and the sampling density (when `P`) at (w_in, w_out), from one half
    /// vector, one D(h) and one G1(w_out, h): `eval`, `pdf` and `eval_pdf` are this one
    /// formula, so they agree bit for bit.
    #[inline(always)]
    fn terms<const F: bool, const P: bool>(&self, w_in: Vec3, w_out: Vec3) -> (Spectrum, f32) {
        if w_in.z <= 0.0 || w_out.z <= 0.0 {
            return (Spectrum::ZERO, 0.0);
        }
        let (mut value, mut specular) = (Spectrum::ZERO, 0.0);
        if let Some(h) = half_vector(w_in, w_out) {
            let mf = self.microfacet();
            let d = mf.d(h);
            let g1_out = mf.g1(w_out, h);
            if F && d > 0.0 {
                let fresnel = fresnel_dielectric(w_out.dot(h), self.eta);
                let g = mf.g1(w_in, h) * g1_out;
                value =
                    self.params.specular_reflectance * (fresnel * d * g / (4.0 * w_in.z * w_out.z));
            }
            if P && w_out.dot(h) > 0.0 && w_in.dot(h) > 0.0 {
                specular = mf.sample_pdf_from(w_out, h, d, g1_out) / (4.0 * w_out.dot(h));
            }
        }
        let f = if F {
            let (t_in, t_out) = (
                self.tables.transmittance(w_in.z),
                self.tables.transmittance(w_out.z),
            );
            let diffuse = self
                .params
                .normalised_diffuse(self.tables.internal_reflectance);
            value + diffuse * (INV_PI * t_in * t_out / (self.eta * self.eta))
        } else {
            Spectrum::ZERO
        };
        // p_s·p(h)/(4 w_out·h) + (1 − p_s)·cos θ_in/π per steradian.
        let pdf = if P {
            let ps = self.specular_probability(w_out);
            ps * specular + (1.0 - ps) * cosine_hemisphere_pdf(w_in)
        } else {
            0.0
        };
        (f, pdf)
    }
}

impl Bsdf for RoughPlastic {
    fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum {
        self.terms::<true, false>(w_in, w_out).0
    }

    /// u.x picks the lobe and is rescaled to [0, 1) for reuse by that lobe's warp.
    fn sample(&self, w_out: Vec3, u: Vec2) -> Option<BsdfSample> {
        if w_out.z <= 0.0 {
            return None;
        }
        let ps = self.specular_probability(w_out);
        let w_in = if u.x < ps {
            let m = self
                .microfacet()
                .sample_normal(w_out, Vec2::new(u.x / ps, u.y));
            reflect(w_out, m)
        } else {
            let u = Vec2::new(reuse_above(u.x, ps), u.y);
            square_to_cosine_hemisphere(u).0
        };
        sample_at(self, w_in, w_out)
    }

    /// p_s·p(h)/(4 w_out·h) + (1 − p_s)·cos θ_in/π per steradian.
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
            let b = RoughPlastic::new(PlasticParams {
                distribution,
                alpha: 0.2,
                ..PlasticParams::default()
            })
            .expect("valid");
            let w_out = Vec3::new(0.5, 0.2, 0.6).normalize();
            let mut specular = 0;
            for i in 0..400 {
                let u = Vec2::new(
                    (i % 20) as f32 / 20.0 + 0.025,
                    (i / 20) as f32 / 20.0 + 0.025,
                );
                if let Some(s) = b.sample(w_out, u) {
                    assert_eq!(s.pdf, b.pdf(s.w_in, w_out));
                    assert_eq!(s.f, b.eval(s.w_in, w_out));
                    specular += (u.x < b.specular_probability(w_out)) as usize;
                }
            }
            assert!(specular > 0 && specular < 400);
        }
    }

    #[test]
    fn bad_indices_are_errors() {
        for (int_ior, ext_ior) in [(1.0, 1.0), (-1.5, 1.0), (f32::NAN, 1.0), (1.5, 0.0)] {
            let p = PlasticParams {
                int_ior,
                ext_ior,
                ..PlasticParams::default()
            };
            assert!(RoughPlastic::new(p).is_err());
        }
    }
}
