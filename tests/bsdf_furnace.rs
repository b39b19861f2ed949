//! White furnace: the directional albedo ∫ f·cos θ_in dω_in of every white BSDF
//! configuration (Fresnel-1 conductors, unit diffuse albedo) at four angles is at most
//! 1 (+ 1%), measured twice — by quadrature of `eval` over half vectors and by Monte
//! Carlo with the BSDF's own samples (f·cos/pdf) — and the two agree, which ties
//! `sample`'s weights to `eval`. A white smooth conductor reflects exactly 1, and a
//! white rough conductor nearly 1 at small α.

mod common;

use common::bsdfs::{ANGLES, Case, cases, integrate_over_half_vectors, w_out};
use glam::{Vec2, Vec3};
use lightlab::bsdf::fresnel::fresnel_dielectric;
use lightlab::bsdf::{
    AIR_IOR, Bsdf, Conductor, ConductorMaterial, Material, MicrofacetType, POLYPROPYLENE_IOR,
    RoughConductor,
};
use lightlab::math::spectrum::luminance;
use lightlab::sampling::Rng32;

/// Monte Carlo draws per albedo.
const DRAWS: usize = 200_000;

/// Albedo by importance sampling: mean and standard error of luminance(f·cos/pdf).
fn sampled_albedo(material: &Material, w: Vec3) -> (f64, f64) {
    let mut rng = Rng32::new(0x00f0_7ace);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..DRAWS {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let x = material.sample(w, u).map_or(0.0, |s| {
            luminance(s.f) as f64 * s.w_in.z as f64 / s.pdf as f64
        });
        sum += x;
        sum2 += x * x;
    }
    let mean = sum / DRAWS as f64;
    let var = (sum2 / DRAWS as f64 - mean * mean).max(0.0);
    (mean, (var / DRAWS as f64).sqrt())
}

/// Albedo of the Dirac lobes `eval` does not cover: the smooth plastic's coat reflection.
fn delta_albedo(case: &Case, w: Vec3) -> f64 {
    match case.material {
        Material::Plastic(_) => fresnel_dielectric(w.z, POLYPROPYLENE_IOR / AIR_IOR) as f64,
        _ => 0.0,
    }
}

#[test]
fn white_albedo_is_at_most_one_and_sampling_agrees_with_eval() {
    let mut failures = Vec::new();
    for case in cases(true).iter().filter(|c| c.name != "conductor") {
        for angle in ANGLES {
            let w = w_out(angle);
            let eval = |w_in: Vec3| luminance(case.material.eval(w_in, w)) as f64 * w_in.z as f64;
            let quadrature =
                integrate_over_half_vectors(case.alpha, w, eval) + delta_albedo(case, w);
            let (sampled, sigma) = sampled_albedo(&case.material, w);
            println!(
                "{:28} {angle:4}°: albedo {quadrature:.5} (quadrature), {sampled:.5} ± {sigma:.5} (sampled)",
                case.name
            );
            if quadrature > 1.01 || sampled > 1.01 + 4.0 * sigma {
                failures.push(format!(
                    "{} at {angle}°: albedo {quadrature} / {sampled}",
                    case.name
                ));
            }
            if (quadrature - sampled).abs() > 4.0 * sigma + 2e-3 {
                failures.push(format!(
                    "{} at {angle}°: quadrature {quadrature} but sampling {sampled} ± {sigma}",
                    case.name
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn white_smooth_conductor_reflects_everything() {
    let mirror = Conductor::default();
    for angle in ANGLES {
        let w = w_out(angle);
        let s = mirror.sample(w, Vec2::new(0.3, 0.7)).expect("sample");
        let throughput = s.f * s.w_in.z / s.pdf;
        assert!(
            (throughput - Vec3::ONE).abs().max_element() < 1e-5,
            "{angle}°: {throughput}"
        );
    }
    // A real metal reflects less than everything, and more at grazing angles.
    let gold = Conductor::from_material(ConductorMaterial::Au);
    let weight = |deg: f32| {
        let s = gold.sample(w_out(deg), Vec2::ZERO).expect("sample");
        luminance(s.f * s.w_in.z / s.pdf)
    };
    assert!(weight(0.0) < weight(89.0) && weight(89.0) < 1.0);
}

#[test]
fn white_rough_conductor_is_nearly_lossless_when_nearly_smooth() {
    // Energy is lost only to masking, which vanishes as α → 0 away from grazing.
    for distribution in MicrofacetType::ALL {
        for alpha in [0.005, 0.05] {
            let rc = Material::RoughConductor(RoughConductor::from_material(
                distribution,
                alpha,
                ConductorMaterial::None,
            ));
            for angle in [0.0, 45.0] {
                let w = w_out(angle);
                let eval = |w_in: Vec3| luminance(rc.eval(w_in, w)) as f64 * w_in.z as f64;
                let albedo = integrate_over_half_vectors(alpha, w, eval);
                println!("{distribution} α = {alpha} at {angle}°: albedo {albedo:.5}");
                assert!(
                    albedo > 0.99 && albedo < 1.001,
                    "{distribution} {alpha} {angle}: {albedo}"
                );
            }
        }
    }
}
