//! The Lambertian BRDF, sampled by Malley's method.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample};
use crate::math::{INV_PI, Spectrum};
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};

/// f = ρ/π above the surface (one-sided, as Mitsuba's `diffuse`).
#[derive(Clone, Debug)]
pub struct Diffuse {
    /// Reflectance ρ in [0, 1].
    pub reflectance: Spectrum,
}

impl Bsdf for Diffuse {
    #[inline]
    fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum {
        if w_in.z <= 0.0 || w_out.z <= 0.0 {
            return Spectrum::ZERO;
        }
        self.reflectance * INV_PI
    }

    /// Cosine-weighted: f·cos/pdf = ρ exactly.
    #[inline]
    fn sample(&self, w_out: Vec3, u: Vec2) -> Option<BsdfSample> {
        if w_out.z <= 0.0 {
            return None;
        }
        let (w_in, pdf) = square_to_cosine_hemisphere(u);
        (pdf > 0.0).then(|| BsdfSample {
            w_in,
            f: self.eval(w_in, w_out),
            pdf,
            delta: false,
        })
    }

    #[inline]
    fn pdf(&self, w_in: Vec3, w_out: Vec3) -> f32 {
        if w_out.z <= 0.0 {
            0.0
        } else {
            cosine_hemisphere_pdf(w_in)
        }
    }
}
