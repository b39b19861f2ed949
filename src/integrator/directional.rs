//! Directional estimators: draw ω_in, trace it, and score f·cos θ·Le/p(ω_in) if it
//! reaches an emitter (the lecture's `DirectIllumination` loop with a pdf).

use super::probe::{ProbeSample, no_direction};
use super::{Context, EstimatorKind, emitted_at, f_cos};
use crate::bsdf::Bsdf;
use crate::geometry::{Along, Ray, offset_origin};
use crate::math::Spectrum;
use crate::sampling::Uniform;
use crate::sampling::warp::{
    cube_rejection_to_hemisphere, square_to_cosine_hemisphere, square_to_theta_phi_hemisphere,
    square_to_uniform_hemisphere,
};

/// One sample of a directional estimator.
pub(super) fn estimate(ctx: &Context<'_>, kind: EstimatorKind, src: &mut impl Uniform) -> Spectrum {
    let Context {
        scene,
        hit,
        material,
        w_out,
        ..
    } = *ctx;
    // (direction, its density as the estimator divides by it, f·cos/p)
    let (w_in, pdf, weight) = match kind {
        EstimatorKind::Hemisphere => {
            let (w, pdf) = square_to_uniform_hemisphere(src.next_2d());
            (w, pdf, f_cos(material, w, w_out) / pdf)
        }
        EstimatorKind::HemisphereThetaPhi => {
            // The lecture's pitfall: the weight 2π of uniform directions, kept although
            // (θ, φ) crowds the pole (true pdf 1/(π² sin θ)): biased on purpose.
            let (w, _) = square_to_theta_phi_hemisphere(src.next_2d());
            let assumed = 1.0 / std::f32::consts::TAU;
            (w, assumed, f_cos(material, w, w_out) / assumed)
        }
        EstimatorKind::HemisphereRejection => {
            let (w, pdf) = cube_rejection_to_hemisphere(src);
            (w, pdf, f_cos(material, w, w_out) / pdf)
        }
        EstimatorKind::Cosine => {
            let (w, pdf) = square_to_cosine_hemisphere(src.next_2d());
            if pdf <= 0.0 {
                ctx.record(|| no_direction(kind.name()));
                return Spectrum::ZERO;
            }
            (w, pdf, f_cos(material, w, w_out) / pdf)
        }
        EstimatorKind::Bsdf => match material.sample(w_out, src.next_2d()) {
            Some(s) if s.pdf > 0.0 => (s.w_in, s.pdf, s.f * s.w_in.z.abs() / s.pdf),
            _ => {
                ctx.record(|| no_direction(kind.name()));
                return Spectrum::ZERO;
            }
        },
        EstimatorKind::Light | EstimatorKind::Mis => {
            unreachable!("the light and MIS estimators are not directional")
        }
    };
    let w_world = hit.frame.to_world(w_in);
    let (value, light, point) = if weight == Spectrum::ZERO {
        (Spectrum::ZERO, None, None)
    } else {
        let ray = Ray::new(offset_origin(hit.p, hit.ng, w_world), w_world);
        match scene
            .geometry
            .first_emitter(&ray, scene.environment.is_some())
        {
            Along::Emitter(y) => (
                weight * emitted_at(scene, &y, -w_world),
                Some(y.light as usize),
                Some(y.p),
            ),
            Along::Escapes => (weight * scene.escaped(w_world), scene.environment, None),
            Along::Blocked => (Spectrum::ZERO, None, None),
        }
    };
    ctx.record(|| ProbeSample {
        sample: 0,
        technique: kind.name(),
        w_in: Some(w_world),
        pdf,
        mis_weight: 1.0,
        contribution: value,
        light,
        light_point: point.filter(|_| light.is_some()),
        occluded: false,
    });
    value
}
