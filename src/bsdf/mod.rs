//! BSDFs with the lecture's interface: `eval`, and a `sample`/`pdf` pair whose default
//! draws uniform directions on the hemisphere, so any BSDF that overrides them with
//! importance sampling "just gets better" without touching the estimators.
//!
//! Directions are in the local shading frame (normal = +z) and both point away from the
//! surface. Knows nothing of lights or the renderer.

pub mod coat;
mod conductor;
mod conductor_ior;
mod diffuse;
pub mod fresnel;
pub mod microfacet;
mod phong;
mod plastic;
mod rough_conductor;
mod rough_plastic;

pub use conductor::Conductor;
pub use conductor_ior::ConductorMaterial;
pub use diffuse::Diffuse;
pub use microfacet::{Microfacet, MicrofacetType};
pub use phong::Phong;
pub use plastic::Plastic;
pub use rough_conductor::RoughConductor;
pub use rough_plastic::{AIR_IOR, POLYPROPYLENE_IOR, PlasticParams, RoughPlastic};

use glam::{Vec2, Vec3};

use crate::math::Spectrum;
use crate::sampling::sampler::ONE_MINUS_EPSILON;
use crate::sampling::warp::{square_to_uniform_hemisphere, uniform_hemisphere_pdf};

/// A direction drawn from a BSDF. `pdf` is per unit solid angle.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Incident direction (local frame).
    pub w_in: Vec3,
    /// BSDF value f(w_in, w_out), cosine not included.
    pub f: Spectrum,
    /// Density of `w_in` per steradian.
    pub pdf: f32,
    /// `f` and `pdf` are Dirac weights.
    pub delta: bool,
}

/// A BSDF. The lecture's `BRDF::sample(normal, w_out, w_in&, pdf&)` is
/// `sample(w_out, u)` in the local frame, where the normal is +z.
pub trait Bsdf {
    /// f(w_in, w_out); zero for delta lobes and below the surface.
    fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum;

    /// Draws w_in for a given w_out. Default: uniform on the hemisphere (z, φ).
    /// Override `sample` and `pdf` together.
    fn sample(&self, w_out: Vec3, u: Vec2) -> Option<BsdfSample> {
        if w_out.z <= 0.0 {
            return None;
        }
        let (w_in, pdf) = square_to_uniform_hemisphere(u);
        Some(BsdfSample {
            w_in,
            f: self.eval(w_in, w_out),
            pdf,
            delta: false,
        })
    }

    /// Density of `sample` choosing `w_in` given `w_out`, per steradian.
    fn pdf(&self, w_in: Vec3, w_out: Vec3) -> f32 {
        if w_out.z <= 0.0 {
            0.0
        } else {
            uniform_hemisphere_pdf(w_in)
        }
    }

    /// True when every lobe is a Dirac delta (light sampling cannot help).
    fn is_delta(&self) -> bool {
        false
    }

    /// True when some lobe is a Dirac delta (`sample` may return `delta: true` samples,
    /// which `eval` and `pdf` do not cover). Default: [`Bsdf::is_delta`].
    fn has_delta_lobe(&self) -> bool {
        self.is_delta()
    }
}

/// The sample of `bsdf` at `w_in` for `w_out`, with the BSDF's own `eval` and `pdf`, so a
/// sample and a later `pdf` query agree to the last bit (what MIS weights need); `None`
/// where that density is zero or not finite.
#[inline]
pub(crate) fn sample_at(bsdf: &impl Bsdf, w_in: Vec3, w_out: Vec3) -> Option<BsdfSample> {
    let pdf = bsdf.pdf(w_in, w_out);
    (pdf > 0.0 && pdf.is_finite()).then(|| BsdfSample {
        w_in,
        f: bsdf.eval(w_in, w_out),
        pdf,
        delta: false,
    })
}

/// After a lobe was chosen by `u < p` being false, the part of `u` above `p` rescaled to
/// [0, 1), free for the lobe's own sampling (the lecture's "one random number reused").
#[inline]
pub(crate) fn reuse_above(u: f32, p: f32) -> f32 {
    ((u - p) / (1.0 - p)).clamp(0.0, ONE_MINUS_EPSILON)
}

/// The closed set of materials a scene can use: one `match` forwards each call.
#[derive(Clone, Debug)]
pub enum Material {
    /// Lambertian.
    Diffuse(Diffuse),
    /// Energy-normalised modified Phong.
    Phong(Phong),
    /// Smooth conductor: a mirror (Dirac lobe).
    Conductor(Conductor),
    /// Microfacet conductor.
    RoughConductor(RoughConductor),
    /// Smooth dielectric coat (Dirac lobe) over a diffuse base.
    Plastic(Plastic),
    /// Rough dielectric coat over a diffuse base.
    RoughPlastic(RoughPlastic),
}

macro_rules! forward {
    ($self:ident, $m:ident => $e:expr) => {
        match $self {
            Material::Diffuse($m) => $e,
            Material::Phong($m) => $e,
            Material::Conductor($m) => $e,
            Material::RoughConductor($m) => $e,
            Material::Plastic($m) => $e,
            Material::RoughPlastic($m) => $e,
        }
    };
}

impl Bsdf for Material {
    #[inline]
    fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum {
        forward!(self, m => m.eval(w_in, w_out))
    }

    #[inline]
    fn sample(&self, w_out: Vec3, u: Vec2) -> Option<BsdfSample> {
        forward!(self, m => m.sample(w_out, u))
    }

    #[inline]
    fn pdf(&self, w_in: Vec3, w_out: Vec3) -> f32 {
        forward!(self, m => m.pdf(w_in, w_out))
    }

    fn is_delta(&self) -> bool {
        forward!(self, m => m.is_delta())
    }

    fn has_delta_lobe(&self) -> bool {
        forward!(self, m => m.has_delta_lobe())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A BSDF that only knows how to evaluate itself gets the uniform default.
    struct EvalOnly;
    impl Bsdf for EvalOnly {
        fn eval(&self, w_in: Vec3, w_out: Vec3) -> Spectrum {
            Spectrum::splat(((w_in.z > 0.0) && (w_out.z > 0.0)) as u8 as f32 * 0.25)
        }
    }

    #[test]
    fn default_sampling_is_uniform_hemisphere() {
        let w_out = Vec3::Z;
        let s = EvalOnly.sample(w_out, Vec2::new(0.3, 0.6)).expect("sample");
        assert!((s.w_in.z - 0.3).abs() < 1e-6);
        assert!((s.pdf - 0.5 / std::f32::consts::PI).abs() < 1e-6);
        assert_eq!(s.pdf, EvalOnly.pdf(s.w_in, w_out));
        assert!(EvalOnly.sample(-Vec3::Z, Vec2::splat(0.5)).is_none());
    }
}
