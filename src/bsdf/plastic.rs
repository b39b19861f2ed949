//! Mitsuba 3's smooth `plastic`: a Dirac specular reflection off a smooth dielectric coat
//! over a diffuse base, f_diffuse = k_d/(1 − k_d^[nonlinear]·F_dr)·(1 − F_in)(1 − F_out)/(π η²),
//! F_dr the coat's diffuse Fresnel reflectance from inside. `eval` and `pdf` cover the
//! diffuse part only; `sample` flags `delta` when it picks the mirror lobe.

use glam::{Vec2, Vec3};

use super::fresnel::{fresnel_dielectric, fresnel_diffuse_reflectance};
use super::rough_plastic::PlasticParams;
use super::{Bsdf, BsdfSample, reuse_above, sample_at};
use crate::math::{INV_PI, Spectrum};
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};

/// A smooth plastic (its `alpha` and `distribution` are ignored).
#[derive(Clone, Debug)]
pub struct Plastic {
    params: PlasticParams,
    eta: f32,
}

impl Plastic {
    /// Validates the indices of refraction.
    pub fn new(params: PlasticParams) -> Result<Plastic, String> {
        let eta = params.eta()?;
        Ok(Plastic { params, eta })
    }

    /// The parameters it was built from.
    pub fn params(&self) -> &PlasticParams {
        &self.params
    }

    /// Probability of the mirror lobe for light leaving at cos θ_out: F·s against
    /// (1 − F)(1 − s), as Mitsuba does.
    fn specular_probability(&self, cos_out: f32) -> f32 {
        let f = fresnel_dielectric(cos_out, self.eta);
        let s = self.params.specular_sampling_weight();
        let (ps, pd) = (f * s, (1.0 - f) * (1.0 - s));
        if ps + pd > 0.0 { ps / (ps + pd) } else { 0.5 }
    }
}

impl Bsdf for Plastic {
    /// The diffuse part only (the mirror lobe is a Dirac delta).
    fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum {
        if w_in.z <= 0.0 || w_out.z <= 0.0 {
            return Spectrum::ZERO;
        }
        let f_in = fresnel_dielectric(w_in.z, self.eta);
        let f_out = fresnel_dielectric(w_out.z, self.eta);
        let fdr_int = fresnel_diffuse_reflectance(1.0 / self.eta);
        self.params.normalised_diffuse(fdr_int)
            * (INV_PI * (1.0 - f_in) * (1.0 - f_out) / (self.eta * self.eta))
    }

    /// u.x picks the lobe and is rescaled for the cosine warp. The mirror sample has
    /// Dirac weights pdf = p_s and f = F·k_s/cos θ, so f·cos θ/pdf = F·k_s/p_s.
    fn sample(&self, w_out: Vec3, u: Vec2) -> Option<BsdfSample> {
        if w_out.z <= 0.0 {
            return None;
        }
        let ps = self.specular_probability(w_out.z);
        if u.x < ps {
            let w_in = Vec3::new(-w_out.x, -w_out.y, w_out.z);
            let f = fresnel_dielectric(w_out.z, self.eta) * self.params.specular_reflectance;
            return Some(BsdfSample {
                w_in,
                f: f / w_in.z,
                pdf: ps,
                delta: true,
            });
        }
        let u = Vec2::new(reuse_above(u.x, ps), u.y);
        let (w_in, _) = square_to_cosine_hemisphere(u);
        sample_at(self, w_in, w_out)
    }

    /// (1 − p_s)·cos θ_in/π: the density of the diffuse lobe's samples.
    fn pdf(&self, w_in: Vec3, w_out: Vec3) -> f32 {
        if w_in.z <= 0.0 || w_out.z <= 0.0 {
            return 0.0;
        }
        (1.0 - self.specular_probability(w_out.z)) * cosine_hemisphere_pdf(w_in)
    }

    fn has_delta_lobe(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_lobes_are_sampled_consistently() {
        let p = Plastic::new(PlasticParams::default()).expect("valid");
        assert!(!p.is_delta() && p.has_delta_lobe());
        let w_out = Vec3::new(0.6, 0.0, 0.8);
        let ps = p.specular_probability(w_out.z);
        let mirror = p.sample(w_out, Vec2::new(ps * 0.5, 0.3)).expect("mirror");
        assert!(mirror.delta);
        let weight = mirror.f * mirror.w_in.z / mirror.pdf;
        assert!((weight.x - fresnel_dielectric(0.8, 1.49 / 1.000_277) / ps).abs() < 1e-5);
        let diffuse = p
            .sample(w_out, Vec2::new(0.5 + ps * 0.5, 0.3))
            .expect("diffuse");
        assert!(!diffuse.delta);
        assert_eq!(diffuse.pdf, p.pdf(diffuse.w_in, w_out));
        assert_eq!(diffuse.f, p.eval(diffuse.w_in, w_out));
    }
}
