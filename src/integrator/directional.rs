//! Directional estimators: draw ω_in, trace it, and score f·cos θ·Le/p(ω_in) if it
//! reaches an emitter (the lecture's `DirectIllumination` loop with a pdf).

use glam::Vec3;

use super::{EstimatorKind, emitted_at, f_cos};
use crate::bsdf::{Bsdf, Material};
use crate::geometry::{Ray, SurfaceHit, offset_origin};
use crate::math::Spectrum;
use crate::sampling::Uniform;
use crate::sampling::warp::{
    cube_rejection_to_hemisphere, square_to_cosine_hemisphere, square_to_theta_phi_hemisphere,
    square_to_uniform_hemisphere,
};
use crate::scene::Scene;

/// One sample of a directional estimator.
pub(super) fn estimate(
    scene: &Scene,
    kind: EstimatorKind,
    hit: &SurfaceHit,
    material: &Material,
    w_out: Vec3,
    src: &mut impl Uniform,
) -> Spectrum {
    let (w_in, weight) = match kind {
        EstimatorKind::Hemisphere => {
            let (w, pdf) = square_to_uniform_hemisphere(src.next_2d());
            (w, f_cos(material, w, w_out) / pdf)
        }
        EstimatorKind::HemisphereThetaPhi => {
            // The lecture's pitfall: the weight 2π of uniform directions, kept although
            // (θ, φ) crowds the pole (true pdf 1/(π² sin θ)): biased on purpose.
            let (w, _) = square_to_theta_phi_hemisphere(src.next_2d());
            (w, f_cos(material, w, w_out) * std::f32::consts::TAU)
        }
        EstimatorKind::HemisphereRejection => {
            let (w, pdf) = cube_rejection_to_hemisphere(src);
            (w, f_cos(material, w, w_out) / pdf)
        }
        EstimatorKind::Cosine => {
            let (w, pdf) = square_to_cosine_hemisphere(src.next_2d());
            if pdf <= 0.0 {
                return Spectrum::ZERO;
            }
            (w, f_cos(material, w, w_out) / pdf)
        }
        EstimatorKind::Bsdf => match material.sample(w_out, src.next_2d()) {
            Some(s) if s.pdf > 0.0 => (s.w_in, s.f * s.w_in.z.abs() / s.pdf),
            _ => return Spectrum::ZERO,
        },
        EstimatorKind::Light | EstimatorKind::Mis => {
            unreachable!("the light and MIS estimators are not directional")
        }
    };
    if weight == Spectrum::ZERO {
        return Spectrum::ZERO;
    }
    let w_world = hit.frame.to_world(w_in);
    let ray = Ray::new(offset_origin(hit.p, hit.ng, w_world), w_world);
    match scene.geometry.intersect(&ray, f32::INFINITY) {
        Some(y) => weight * emitted_at(scene, &y, -w_world),
        None => weight * scene.escaped(w_world),
    }
}
