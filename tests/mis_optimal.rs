//! Optimal MIS weights (Kondapaneni et al. 2019) add no bias for any α and lower the
//! variance with the pixel's own α (split from `mis.rs`).

mod common;

use common::lambert::{RECTANGLE_RADIANCE as RADIANCE, floor_under_rectangle, lambert_irradiance};
use glam::Vec3;
use lightlab::bsdf::{Diffuse, Material, Phong};
use lightlab::geometry::Ray;
use lightlab::integrator::{Estimator, EstimatorKind, MisHeuristic, MisSettings, OptimalPixel};
use lightlab::light::select::LightSelect;
use lightlab::math::{PI, Spectrum};
use lightlab::sampling::Rng32;
use lightlab::scene::Scene;

/// Mean and variance of `n` camera-ray estimates at `x` (from straight above) carrying the
/// optimal-MIS pixel state `pixel` (its α is fixed: rounds end only in a render).
fn optimal_run(
    scene: &Scene,
    est: &Estimator,
    x: Vec3,
    pixel: &std::cell::RefCell<OptimalPixel>,
    n: usize,
    seed: u64,
) -> (f64, f64) {
    let mut rng = Rng32::new(seed);
    let ray = Ray::new(x + Vec3::Y, -Vec3::Y);
    let (mut sum, mut sum2) = (0f64, 0f64);
    for _ in 0..n {
        let v = est.radiance_in(scene, &ray, &mut rng, Some(pixel)).x as f64;
        assert!(v.is_finite());
        sum += v;
        sum2 += v * v;
    }
    let mean = sum / n as f64;
    (mean, (sum2 / n as f64 - mean * mean).max(0.0))
}

/// Optimal weights (Kondapaneni et al. 2019) are the balance heuristic plus a control
/// variate Σ α_t p_t: unbiased for any α, including α far from the optimum, and, with the
/// α that solves the pixel's technique system, of lower variance than the balance and
/// power heuristics.
#[test]
fn optimal_mis_is_unbiased_for_any_alpha_and_lowers_variance_with_its_own() {
    let (scene, corners) = floor_under_rectangle(Material::Diffuse(Diffuse {
        reflectance: Spectrum::ONE,
    }));
    let x = Vec3::new(-0.4, 0.0, -0.3);
    let exact = lambert_irradiance(x, Vec3::Y, &corners, RADIANCE) / PI as f64;
    let mis = MisSettings {
        heuristic: MisHeuristic::Optimal,
        light_samples: 2,
        bsdf_samples: 1,
        diffuse_bsdf_samples: None,
    };
    let est = Estimator::new(&scene, EstimatorKind::Mis, LightSelect::Uniform).with_mis(mis);
    let n = 200_000;
    for (i, alpha) in [[0.0, 0.0], [0.5, -0.3], [4.0, 2.5], [-3.0, 1.0]]
        .iter()
        .enumerate()
    {
        let pixel = std::cell::RefCell::new(OptimalPixel {
            alpha: [Spectrum::splat(alpha[0]), Spectrum::splat(alpha[1])],
            ..OptimalPixel::default()
        });
        let (mean, var) = optimal_run(&scene, &est, x, &pixel, n, 40 + i as u64);
        let z = (mean - exact) / (var / n as f64).sqrt();
        println!("alpha {alpha:?}: {mean:.5} vs {exact:.5} (z = {z:+.2})");
        assert!(z.abs() < 4.0, "alpha {alpha:?}: {mean} vs {exact}, z = {z}");
    }
    // The pixel's own α from a first run (the balance heuristic gathering moments); then,
    // on common random numbers (one seed for every run, so only the weights differ), the
    // variance at that α is below the balance heuristic's (α = 0), the power heuristic's,
    // and the variance at α scaled by ½ or 2 (it is a quadratic in α with its minimum at
    // the solution of the technique system).
    let glossy = floor_under_rectangle(Material::Phong(Phong {
        kd: Spectrum::splat(0.3),
        ks: Spectrum::splat(0.6),
        exponent: 20.0,
    }))
    .0;
    let est = Estimator::new(&glossy, EstimatorKind::Mis, LightSelect::Uniform).with_mis(mis);
    let pixel = std::cell::RefCell::new(OptimalPixel::default());
    optimal_run(&glossy, &est, x, &pixel, n, 50);
    pixel.borrow_mut().next_round();
    let alpha = pixel.borrow().alpha;
    assert!(alpha[0] != Spectrum::ZERO && alpha[1] != Spectrum::ZERO);
    let variance_at = |a: [Spectrum; 2]| {
        let p = std::cell::RefCell::new(OptimalPixel {
            alpha: a,
            ..OptimalPixel::default()
        });
        optimal_run(&glossy, &est, x, &p, n, 51).1
    };
    let var_opt = variance_at(alpha);
    let var_balance = variance_at([Spectrum::ZERO; 2]);
    let var_half = variance_at([alpha[0] * 0.5, alpha[1] * 0.5]);
    let var_double = variance_at([alpha[0] * 2.0, alpha[1] * 2.0]);
    let power =
        Estimator::new(&glossy, EstimatorKind::Mis, LightSelect::Uniform).with_mis(MisSettings {
            heuristic: MisHeuristic::Power,
            ..mis
        });
    let var_power = optimal_run(&glossy, &power, x, &std::cell::RefCell::default(), n, 51).1;
    println!(
        "alpha {alpha:?}: variance optimal {var_opt:.6e}, alpha/2 {var_half:.6e}, 2 alpha \
         {var_double:.6e}, balance {var_balance:.6e}, power {var_power:.6e}"
    );
    assert!(
        var_opt < var_balance && var_opt < var_half && var_opt < var_double && var_opt < var_power,
        "optimal {var_opt}: balance {var_balance}, alpha/2 {var_half}, 2 alpha {var_double}, \
         power {var_power}"
    );
}
