//! Spatial reuse of RIS reservoirs (`--ris-spatial K`) adds no bias.
//!
//! At the estimator: a pixel's estimate combined with its neighbours' reservoirs, over
//! independent trials, against Lambert's irradiance from a rectangle light, a point light
//! and a constant environment together (every kind of point a reservoir can hold), under
//! the light estimator and every MIS heuristic; exact where a point light is the only
//! light. In the renderer: per-block means of independent spatial renders against a long
//! render without reuse, on a hundred sphere and rectangle lights.

mod common;
use common::blocks::{blocks, render_small};
use common::lambert::{add_floor_under_rectangle, lambert_irradiance};

use glam::Vec3;
use lightlab::bsdf::{Diffuse, Material, Phong};
use lightlab::geometry::Ray;
use lightlab::integrator::{
    Estimator, EstimatorKind, MisHeuristic, MisSettings, Reuse, SpatialReservoir, SpatialSurface,
};
use lightlab::light::select::LightSelect;
use lightlab::light::{Environment, LightStrategy};
use lightlab::math::{PI, Spectrum};
use lightlab::sampling::Rng32;
use lightlab::scene::{Camera, Scene, SceneBuilder};

const RHO: f32 = 0.8;
const RECT_RADIANCE: f32 = 3.0;
const SKY: f32 = 0.25;
const INTENSITY: f32 = 0.6;
const POINT: Vec3 = Vec3::new(-0.3, 0.9, 0.4);
/// Where the camera rays start: the pixels see the floor from different directions.
const EYE: Vec3 = Vec3::new(0.2, 2.0, 1.5);

/// A floor of `floor` under a vertical rectangle light that reaches below its horizon, a
/// point light and a constant sky; returns the scene and the rectangle's corners.
fn lit_floor(floor: Material) -> (Scene, [Vec3; 4]) {
    let mut b = SceneBuilder::new("spatial-floor");
    let m = b.material(floor);
    let corners = add_floor_under_rectangle(&mut b, m, RECT_RADIANCE);
    plate(&mut b, m);
    b.point_light(POINT, Spectrum::splat(INTENSITY));
    b.environment(Environment::constant(Spectrum::splat(SKY)));
    let camera = Camera::look_at(EYE, Vec3::ZERO, Vec3::Y, 40.0, 8, 8);
    (b.build(camera, 1).expect("scene"), corners)
}

/// A plate beside the floor, tilted 50° towards −x and entirely below the floor's
/// horizon (it hides nothing from it): neighbours there see other parts of the lights and
/// the sky than the pixel does, and their targets differ from its own.
fn plate(b: &mut SceneBuilder, m: u32) {
    let (s, c) = 50f32.to_radians().sin_cos();
    b.rectangle(
        Vec3::new(-1.0, 0.0, 0.5),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(-c, -s, 0.0) * 0.8,
        m,
        None,
    );
}

/// L_out of the diffuse floor at `x`: ρ/π · (E_rectangle + L_sky·(π − Ω⊥) + I·cos/d²),
/// where the rectangle hides Ω⊥ = E_rectangle / L of the sky.
fn diffuse_exact(x: Vec3, corners: &[Vec3; 4]) -> f64 {
    let e_rect = lambert_irradiance(x, Vec3::Y, corners, RECT_RADIANCE);
    let hidden = e_rect / RECT_RADIANCE as f64;
    let d = POINT - x;
    let e_point = (INTENSITY * d.normalize().y / d.length_squared()) as f64;
    RHO as f64 / PI as f64 * (e_rect + SKY as f64 * (PI as f64 - hidden) + e_point)
}

/// The shading points: the first is the pixel, the others its neighbours, four on the
/// floor and three on the tilted plate.
fn points() -> Vec<Vec3> {
    let mut p = vec![Vec3::new(-0.1, 0.0, 0.05)];
    for (dx, dz) in [(-1, -1), (1, -1), (-1, 1), (1, 1)] {
        p.push(p[0] + Vec3::new(dx as f32 * 0.12, 0.0, dz as f32 * 0.12));
    }
    let (s, c) = 50f32.to_radians().sin_cos();
    for z in [0.3, 0.0, -0.3] {
        p.push(Vec3::new(-1.0 - 0.4 * c, -0.4 * s, z));
    }
    p
}

/// Mean and standard error over `n` trials of the first point's spatially combined
/// estimate (all points' reservoirs filled anew in every trial).
fn spatial_mean(scene: &Scene, est: &Estimator, n: usize, seed: u64) -> (f64, f64) {
    let pts = points();
    let per = est.spatial_reservoirs();
    let mut rng = Rng32::new(seed);
    let mut reservoirs = vec![SpatialReservoir::default(); pts.len() * per];
    let (mut sum, mut sum2) = (0f64, 0f64);
    for _ in 0..n {
        let surfaces: Vec<SpatialSurface> = pts
            .iter()
            .zip(reservoirs.chunks_mut(per))
            .map(|(&p, r)| {
                let ray = Ray::new(EYE, (p - EYE).normalize());
                let (emitted, s) = est.spatial_primary(scene, &ray, &mut rng, r);
                assert_eq!(emitted, Spectrum::ZERO);
                s.expect("the floor")
            })
            .collect();
        let reuse: Vec<Reuse> = surfaces
            .iter()
            .zip(reservoirs.chunks(per))
            .map(|(surface, reservoirs)| Reuse {
                surface,
                reservoirs,
            })
            .collect();
        let v = est.spatial_direct(scene, reuse[0], &reuse[1..], &mut rng).x as f64;
        assert!(v.is_finite() && v >= 0.0, "{v}");
        sum += v;
        sum2 += v * v;
    }
    let mean = sum / n as f64;
    let se = ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
    (mean, se)
}

/// The estimators under test: the light estimator and MIS with every heuristic but
/// optimal (which refuses RIS), with `m` candidates per reservoir.
fn estimators(scene: &Scene) -> Vec<(String, Estimator)> {
    let mut out = Vec::new();
    for m in [1, 4] {
        let est =
            Estimator::new(scene, EstimatorKind::Light, LightSelect::Ris).with_ris_candidates(m);
        out.push((format!("light M={m}"), est));
    }
    for heuristic in [
        MisHeuristic::Balance,
        MisHeuristic::Power,
        MisHeuristic::OneSample,
    ] {
        for (light_samples, bsdf_samples) in [(1, 1), (2, 3)] {
            let mis = MisSettings {
                heuristic,
                light_samples,
                bsdf_samples,
                diffuse_bsdf_samples: None,
            };
            let est = Estimator::new(scene, EstimatorKind::Mis, LightSelect::Ris)
                .with_mis(mis)
                .with_ris_candidates(2);
            if (light_samples, bsdf_samples) == (1, 1) {
                // MIS compensation, as `render` sets it: the constant sky draws no light
                // samples and no candidates, and the BSDF samples light it alone.
                let compensated = LightStrategy {
                    env_compensation: true,
                    ..LightStrategy::default()
                };
                let est = est.clone().with_light_strategy(scene, compensated);
                out.push((format!("{mis:?}, compensated"), est));
            }
            out.push((format!("{mis:?}"), est));
        }
    }
    out
}

#[test]
fn spatial_reuse_matches_lambert_and_a_bsdf_sampled_reference() {
    for glossy in [false, true] {
        let floor = if glossy {
            Material::Phong(Phong {
                kd: Spectrum::splat(0.3),
                ks: Spectrum::splat(0.5),
                exponent: 12.0,
            })
        } else {
            Material::Diffuse(Diffuse {
                reflectance: Spectrum::splat(RHO),
            })
        };
        let (scene, corners) = lit_floor(floor);
        let x = points()[0];
        // Diffuse: analytic. Glossy: BSDF sampling for the area light and the sky plus
        // the point light's exact term from a light estimate (one light, pmf known).
        let (exact, exact_se) = if glossy {
            let hit = scene
                .geometry
                .intersect(&Ray::new(EYE, (x - EYE).normalize()), 10.0)
                .expect("hit");
            let w_out = (EYE - x).normalize();
            let bsdf = Estimator::new(&scene, EstimatorKind::Bsdf, LightSelect::Uniform);
            let mut rng = Rng32::new(99);
            let (mut s, mut s2, n) = (0f64, 0f64, 2_000_000);
            for _ in 0..n {
                let v = bsdf.direct(&scene, &hit, w_out, &mut rng).x as f64;
                s += v;
                s2 += v * v;
            }
            let mean = s / n as f64;
            let d = POINT - x;
            let w_in = hit.frame.to_local(d.normalize());
            let f = lightlab::bsdf::Bsdf::eval(
                &scene.materials[hit.material as usize],
                w_in,
                hit.frame.to_local(w_out),
            );
            let point = (f.x * w_in.z * INTENSITY / d.length_squared()) as f64;
            (
                mean + point,
                ((s2 / n as f64 - mean * mean) / n as f64).sqrt(),
            )
        } else {
            (diffuse_exact(x, &corners), 0.0)
        };
        for (i, (name, est)) in estimators(&scene).iter().enumerate() {
            let (mean, se) = spatial_mean(&scene, est, 60_000, 11 + i as u64);
            let z = (mean - exact) / (se * se + exact_se * exact_se).sqrt();
            println!("glossy {glossy} {name}: {mean:.5} vs {exact:.5} (z = {z:+.2})");
            assert!(
                z.abs() < 4.0,
                "glossy {glossy} {name}: {mean} vs {exact}, z = {z}"
            );
        }
    }
}

/// With one point light every reservoir holds the same light and the combination's
/// weights cancel exactly: f·I/d² at every trial, for the light estimator and for MIS.
#[test]
fn a_point_light_alone_is_exact_for_every_pixel_combination() {
    let mut b = SceneBuilder::new("spatial-point");
    let m = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::splat(RHO),
    }));
    b.rectangle(
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0),
        m,
        None,
    );
    plate(&mut b, m);
    b.point_light(POINT, Spectrum::splat(INTENSITY));
    let camera = Camera::look_at(EYE, Vec3::ZERO, Vec3::Y, 40.0, 8, 8);
    let scene = b.build(camera, 1).expect("scene");
    let x = points()[0];
    let d = POINT - x;
    let exact = RHO / PI * INTENSITY * d.normalize().y / d.length_squared();
    for (name, est) in estimators(&scene) {
        if name.contains("OneSample") {
            continue; // scores 0 or the value over the choice probability
        }
        let (mean, se) = spatial_mean(&scene, &est, 64, 3);
        assert!(
            (mean as f32 - exact).abs() < 1e-5 * exact && se < 1e-6,
            "{name}: {mean} ± {se} vs {exact}"
        );
    }
}

/// Independent renders with reuse (48×32, 12 seeds) against a long render without: the
/// per-block spread over the seeds bounds the spatial renders' error (their pixels are
/// correlated within an image, so the films' per-pixel variances would not).
#[test]
fn spatial_renders_agree_with_plain_ris_per_block() {
    let scene = lightlab::scene::builtin::build("shirley-100").expect("scene");
    let reference = blocks(&render_small(&scene, 2048, 1, |s| {
        s.light_select = LightSelect::Bvh;
    }));
    let seeds = 12;
    let runs: Vec<Vec<(f64, f64)>> = (0..seeds)
        .map(|seed| {
            blocks(&render_small(&scene, 16, 100 + seed, |s| {
                s.light_select = LightSelect::Ris;
                s.ris_spatial = 6;
                s.ris_radius = 6;
            }))
        })
        .collect();
    let mut worst = 0f64;
    for (b, r) in reference.iter().enumerate() {
        let values: Vec<f64> = runs.iter().map(|run| run[b].0).collect();
        let mean = values.iter().sum::<f64>() / seeds as f64;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (seeds - 1) as f64;
        let z = (mean - r.0) / (var / seeds as f64 + r.1).sqrt();
        println!("block {b}: {mean:.3} vs {:.3} (t = {z:+.2})", r.0);
        if z.abs() > worst.abs() {
            worst = z;
        }
    }
    // Student's t with 11 degrees of freedom: |t| > 5.5 has probability 1.8e-4 per block.
    assert!(worst.abs() < 5.5, "worst block t = {worst}");
}
