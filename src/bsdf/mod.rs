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

    /// `(eval(w_in, w_out), pdf(w_in, w_out))`, bit for bit; a BSDF whose two share terms
    /// (a microfacet lobe's D and G1, a Phong lobe's cosⁿ) computes them once.
    #[inline]
    fn eval_pdf(&self, w_in: Vec3, w_out: Vec3) -> (Spectrum, f32) {
        (self.eval(w_in, w_out), self.pdf(w_in, w_out))
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
    let (f, pdf) = bsdf.eval_pdf(w_in, w_out);
    (pdf > 0.0 && pdf.is_finite()).then_some(BsdfSample {
        w_in,
        f,
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

    #[inline]
    fn eval_pdf(&self, w_in: Vec3, w_out: Vec3) -> (Spectrum, f32) {
        forward!(self, m => m.eval_pdf(w_in, w_out))
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

    /// `eval_pdf` is `(eval, pdf)` bit for bit for every material, at random directions
    /// and at each material's own samples (where the shared terms are what MIS sees).
    #[test]
    fn eval_pdf_is_eval_and_pdf() {
        use crate::sampling::warp::square_to_uniform_sphere;
        use crate::sampling::{Rng32, Uniform};
        let mut materials = vec![
            Material::Diffuse(Diffuse {
                reflectance: Spectrum::splat(0.5),
            }),
            Material::Conductor(Conductor::default()),
            Material::Plastic(Plastic::new(PlasticParams::default()).expect("valid")),
        ];
        for exponent in [1.0, 30.0, 1000.0] {
            materials.push(Material::Phong(Phong {
                kd: Spectrum::splat(0.3),
                ks: Spectrum::new(0.6, 0.5, 0.4),
                exponent,
            }));
        }
        for distribution in MicrofacetType::ALL {
            for alpha in [0.01, 0.2, 0.8] {
                let material = ConductorMaterial::Au;
                let rough = RoughConductor::from_material(distribution, alpha, material);
                materials.push(Material::RoughConductor(rough));
                let params = PlasticParams {
                    distribution,
                    alpha,
                    ..PlasticParams::default()
                };
                let plastic = RoughPlastic::new(params).expect("valid");
                materials.push(Material::RoughPlastic(plastic));
            }
        }
        let bits = |(f, pdf): (Spectrum, f32)| (f.to_array().map(f32::to_bits), pdf.to_bits());
        let mut rng = Rng32::new(17);
        let mut nonzero = 0;
        for material in &materials {
            for _ in 0..4000 {
                let w_out = square_to_uniform_sphere(rng.next_2d()).0;
                let w_out = Vec3::new(w_out.x, w_out.y, w_out.z.abs().max(1e-3)).normalize();
                let sampled = material.sample(w_out, rng.next_2d()).map(|s| s.w_in);
                let random = square_to_uniform_sphere(rng.next_2d()).0;
                let nan = Vec3::new(f32::NAN, 0.0, 1.0);
                for w_in in [Some(random), sampled, Some(nan)].into_iter().flatten() {
                    let both = material.eval_pdf(w_in, w_out);
                    let apart = (material.eval(w_in, w_out), material.pdf(w_in, w_out));
                    assert_eq!(bits(both), bits(apart), "{material:?} at {w_in}, {w_out}");
                    nonzero += (both.1 > 0.0) as u32;
                }
            }
        }
        assert!(nonzero > 40_000, "{nonzero}");
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
