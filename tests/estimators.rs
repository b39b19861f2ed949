//! Unbiasedness of every direct-lighting estimator: against Lambert's polygon formula
//! for the irradiance under a rectangle (also partly below the horizon), and against a
//! high-spp light-sampling render of the assignment scene, per pixel block.

use glam::Vec3;
use lightlab::bsdf::{Diffuse, Material};
use lightlab::geometry::Ray;
use lightlab::image::Film;
use lightlab::integrator::{Estimator, EstimatorKind, MisHeuristic, MisSettings};
use lightlab::light::LightSampling;
use lightlab::light::select::LightSelect;
use lightlab::math::{PI, Spectrum};

use lightlab::sampling::Rng32;
use lightlab::scene::builtin;

mod common;
use common::blocks::{block_z, blocks, render_small, worst};
use common::lambert::{RECTANGLE_RADIANCE as RADIANCE, floor_under_rectangle, lambert_irradiance};

#[test]
fn irradiance_under_a_rectangle_matches_lambert_for_every_estimator() {
    // A white Lambertian floor patch (L_out = E/π) under a vertical rectangle light at
    // x = 0.6 facing −x, reaching below the floor's horizon.
    let (scene, corners) = floor_under_rectangle(Material::Diffuse(Diffuse {
        reflectance: Spectrum::ONE,
    }));
    for x in [
        Vec3::ZERO,
        Vec3::new(0.3, 0.0, 0.2),
        Vec3::new(-0.4, 0.0, -0.3),
    ] {
        let exact = lambert_irradiance(x, Vec3::Y, &corners, RADIANCE) / PI as f64;
        let ray = Ray::new(x + Vec3::Y, -Vec3::Y);
        let hit = scene.geometry.intersect(&ray, 10.0).expect("floor hit");
        for kind in EstimatorKind::unbiased() {
            let est = Estimator::new(&scene, kind, LightSelect::Uniform);
            let mut rng = Rng32::new(42 + kind as u64);
            let n = 200_000;
            let (mut sum, mut sum2) = (0f64, 0f64);
            for _ in 0..n {
                let v = est.direct(&scene, &hit, Vec3::Y, &mut rng).x as f64;
                assert!(v.is_finite());
                sum += v;
                sum2 += v * v;
            }
            let mean = sum / n as f64;
            let se = ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
            let z = (mean - exact) / se.max(1e-12);
            println!("{kind:>20} at {x}: {mean:.5} vs Lambert {exact:.5} (z = {z:+.2})");
            assert!(z.abs() < 4.0, "{kind} at {x}: {mean} vs {exact}, z = {z}");
        }
    }
}

fn render_assignment(estimator: EstimatorKind, spp: u32, seed: u64) -> Film {
    render_assignment_mis(estimator, MisSettings::default(), spp, seed)
}

fn render_assignment_mis(estimator: EstimatorKind, mis: MisSettings, spp: u32, seed: u64) -> Film {
    let scene = builtin::build("assignment").expect("scene");
    render_small(&scene, spp, seed, |s| {
        s.estimator = estimator;
        s.mis = mis;
    })
}

#[test]
fn all_estimators_agree_on_the_assignment_scene() {
    // The reference is BSDF-sampled: a light-sampled reference is heavy-tailed on the
    // Phong n = 1000 lobe (rare large f), its sample variance underestimates the error, and
    // sharp-lobe blocks then sit 4-5 "standard errors" away from every directional estimator.
    let reference = blocks(&render_assignment(EstimatorKind::Bsdf, 16384, 1));
    let mut failures = Vec::new();
    let mut runs: Vec<(String, EstimatorKind, MisSettings)> = EstimatorKind::unbiased()
        .map(|k| (k.to_string(), k, MisSettings::default()))
        .collect();
    for heuristic in [MisHeuristic::Balance, MisHeuristic::OneSample] {
        let mis = MisSettings {
            heuristic,
            light_samples: 2,
            bsdf_samples: 1,
            diffuse_bsdf_samples: None,
        };
        runs.push((format!("mis {heuristic} 2+1"), EstimatorKind::Mis, mis));
    }
    // Light samples alone at the Lambertian points (the diffuse sphere, the floor), both
    // techniques on the Phong spheres, in the renderer's staged shading.
    let diffuse_alone = MisSettings {
        diffuse_bsdf_samples: Some(0),
        ..MisSettings::default()
    };
    runs.push((
        "mis power, diffuse 1+0".into(),
        EstimatorKind::Mis,
        diffuse_alone,
    ));
    for (kind, estimator, mis) in runs {
        let spp = match estimator {
            EstimatorKind::Light | EstimatorKind::Mis => 512,
            _ => 8192,
        };
        let test = blocks(&render_assignment_mis(estimator, mis, spp, 7));
        let worst = worst(&block_z(&test, &reference));
        println!("{kind:>20}: worst block z = {worst:+.2}");
        failures.push((kind, worst));
    }
    failures.retain(|(_, z)| z.abs() >= 4.0);
    assert!(
        failures.is_empty(),
        "pixel blocks differ by ≥ 4 standard errors: {failures:?}"
    );
}

#[test]
fn images_are_bitwise_identical_for_any_thread_count() {
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .expect("pool");
    for kind in EstimatorKind::unbiased() {
        let a = one.install(|| render_assignment(kind, 4, 3));
        let b = two.install(|| render_assignment(kind, 4, 3));
        assert_eq!(a, b, "{kind}");
    }
}

#[test]
fn fast_paths_agree_with_the_reference_implementations() {
    // `--fast-paths off` samples the rectangle light with the readable f64 spherical
    // rectangle, and an emitting mesh's triangles with the f64 spherical triangle; on (the
    // default) with the fast ones. Independent seeds: the blocks must agree within noise
    // for the light and MIS estimators.
    for name in [
        "builtin:assignment",
        "builtin:sphere-near-plane?emitters=mesh",
    ] {
        let scene = lightlab::scene::load(name).expect("scene");
        fast_paths_agree_on(&scene, name);
    }
}

fn fast_paths_agree_on(scene: &lightlab::scene::Scene, name: &str) {
    for estimator in [EstimatorKind::Light, EstimatorKind::Mis] {
        let film = |fast: bool, seed: u64| {
            render_small(scene, 2048, seed, |s| {
                s.estimator = estimator;
                s.light_sampling = LightSampling::SolidAngle;
                s.fast_paths = fast;
            })
        };
        let (fast, reference) = (blocks(&film(true, 21)), blocks(&film(false, 22)));
        let worst = worst(&block_z(&fast, &reference));
        println!("{name} {estimator}: worst block z = {worst:+.2}");
        assert!(
            worst.abs() < 4.0,
            "{name} {estimator}: worst block z = {worst}"
        );
    }
}
