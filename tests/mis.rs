//! The `mis` estimator adds no bias: Lambert's irradiance for every heuristic and for
//! unequal sample counts, exact irradiance from a point light (a delta light gets weight 1
//! from light sampling, divided by the light-sample count), and the same image as the light
//! estimator where only light sampling can find the light.

mod common;
use common::blocks::{block_z, blocks, render_small, worst};

use common::lambert::{RECTANGLE_RADIANCE as RADIANCE, floor_under_rectangle, lambert_irradiance};
use glam::Vec3;
use lightlab::bsdf::{Diffuse, Material, Phong};
use lightlab::geometry::{Ray, SurfaceHit};
use lightlab::integrator::{Estimator, EstimatorKind, MisHeuristic, MisSettings, OptimalPixel};
use lightlab::light::select::LightSelect;
use lightlab::math::{PI, Spectrum};
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::sampling::{Rng32, SamplerKind};
use lightlab::scene::Camera;
use lightlab::scene::builder::Emission;
use lightlab::scene::{Scene, SceneBuilder};

fn floor_hit(scene: &Scene, x: Vec3) -> SurfaceHit {
    let ray = Ray::new(x + Vec3::Y, -Vec3::Y);
    scene.geometry.intersect(&ray, 10.0).expect("floor hit")
}

/// Mean and standard error of `n` estimates of L_out at `hit`, seen from straight above.
fn estimate(scene: &Scene, est: &Estimator, hit: &SurfaceHit, n: usize, seed: u64) -> (f64, f64) {
    let mut rng = Rng32::new(seed);
    let (mut sum, mut sum2) = (0f64, 0f64);
    for _ in 0..n {
        let v = est.direct(scene, hit, Vec3::Y, &mut rng).x as f64;
        assert!(v.is_finite());
        sum += v;
        sum2 += v * v;
    }
    let mean = sum / n as f64;
    (
        mean,
        ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt(),
    )
}

fn every_mis() -> Vec<MisSettings> {
    let mut out = Vec::new();
    for heuristic in MisHeuristic::ALL {
        for (light_samples, bsdf_samples) in [(1, 1), (2, 3), (4, 1)] {
            out.push(MisSettings {
                heuristic,
                light_samples,
                bsdf_samples,
            });
        }
    }
    out
}

#[test]
fn mis_matches_lambert_for_every_heuristic_and_sample_count() {
    // A white floor (diffuse, then a glossy Phong) under a vertical rectangle light that
    // reaches below the floor's horizon.
    for glossy in [false, true] {
        let (scene, corners) = floor_under_rectangle(if glossy {
            Material::Phong(Phong {
                kd: Spectrum::splat(0.3),
                ks: Spectrum::splat(0.6),
                exponent: 20.0,
            })
        } else {
            Material::Diffuse(Diffuse {
                reflectance: Spectrum::ONE,
            })
        });
        for x in [Vec3::ZERO, Vec3::new(-0.4, 0.0, -0.3)] {
            let hit = floor_hit(&scene, x);
            // The diffuse answer is analytic; the glossy one comes from a long BSDF-sampled
            // run (itself unbiased by the estimator tests), with both errors in the bound.
            let (exact, exact_se) = if glossy {
                let bsdf = Estimator::new(&scene, EstimatorKind::Bsdf, LightSelect::Uniform);
                estimate(&scene, &bsdf, &hit, 2_000_000, 99)
            } else {
                (
                    lambert_irradiance(x, Vec3::Y, &corners, RADIANCE) / PI as f64,
                    0.0,
                )
            };
            // Every MIS variant, with plain light sampling and with light samples resampled
            // from 4 candidates (RIS); and the light estimator resampling 1, 4 or 16.
            let mut estimators: Vec<(String, Estimator)> = Vec::new();
            for mis in every_mis() {
                for select in [LightSelect::Uniform, LightSelect::Ris] {
                    let est = Estimator::new(&scene, EstimatorKind::Mis, select)
                        .with_mis(mis)
                        .with_ris_candidates(4);
                    estimators.push((format!("{select} {mis:?}"), est));
                }
            }
            for m in [1, 4, 16] {
                let est = Estimator::new(&scene, EstimatorKind::Light, LightSelect::Ris)
                    .with_ris_candidates(m);
                estimators.push((format!("light ris M={m}"), est));
            }
            for (i, (name, est)) in estimators.iter().enumerate() {
                let (mean, se) = estimate(&scene, est, &hit, 100_000, 7 + i as u64);
                let z = (mean - exact) / (se * se + exact_se * exact_se).sqrt().max(1e-12);
                println!("glossy {glossy} {name} at {x}: {mean:.5} vs {exact:.5} (z = {z:+.2})");
                assert!(z.abs() < 4.0, "{name} at {x}: {mean} vs {exact}, z = {z}");
            }
        }
    }
}

/// A diffuse floor of reflectance ρ under a point light: L_out = ρ/π · I·cos θ / d².
#[test]
fn point_light_is_exact_with_any_number_of_light_samples() {
    let rho = 0.7;
    let intensity = 5.0;
    let light = Vec3::new(0.3, 1.5, -0.2);
    let mut b = SceneBuilder::new("point-mis");
    let floor = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::splat(rho),
    }));
    b.rectangle(
        Vec3::new(-2.0, 0.0, 2.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -4.0),
        floor,
        None,
    );
    b.point_light(light, Spectrum::splat(intensity));
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 0.1), Vec3::ZERO, Vec3::Y, 40.0, 8, 8);
    let scene = b.build(camera, 1).expect("scene");
    for x in [Vec3::ZERO, Vec3::new(1.2, 0.0, 0.9)] {
        let d = light - x;
        let exact = rho / PI * intensity * d.normalize().y / d.length_squared();
        let hit = floor_hit(&scene, x);
        for mis in every_mis() {
            let est =
                Estimator::new(&scene, EstimatorKind::Mis, LightSelect::Uniform).with_mis(mis);
            let mut rng = Rng32::new(3);
            for _ in 0..16 {
                let v = est.direct(&scene, &hit, Vec3::Y, &mut rng).x;
                // One-sample MIS picks light sampling with probability N/(N+M) and scores
                // 0 or the value over that probability; the multi-sample model is exact.
                if mis.heuristic == MisHeuristic::OneSample {
                    let c =
                        mis.light_samples as f32 / (mis.light_samples + mis.bsdf_samples) as f32;
                    assert!(
                        v == 0.0 || (v * c - exact).abs() < 1e-5 * exact,
                        "{mis:?}: {v}"
                    );
                } else {
                    assert!((v - exact).abs() < 1e-5 * exact, "{mis:?}: {v} vs {exact}");
                }
            }
        }
    }
}

/// Where only light sampling can find the light (a point light), one light sample and
/// one BSDF sample give the light estimator's image, sample by sample.
#[test]
fn mis_equals_light_sampling_when_only_light_sampling_can_find_the_light() {
    let mut b = SceneBuilder::new("point-image");
    let floor = b.material(Material::Phong(Phong {
        kd: Spectrum::splat(0.4),
        ks: Spectrum::splat(0.4),
        exponent: 50.0,
    }));
    b.rectangle(
        Vec3::new(-2.0, 0.0, 2.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -4.0),
        floor,
        None,
    );
    b.sphere(Vec3::new(0.0, 0.5, 0.0), 0.5, floor, None);
    b.point_light(Vec3::new(0.5, 2.0, 0.5), Spectrum::splat(8.0));
    let camera = Camera::look_at(Vec3::new(0.0, 2.0, 4.0), Vec3::ZERO, Vec3::Y, 40.0, 24, 16);
    let scene = b.build(camera, 4).expect("scene");
    let render = |kind: EstimatorKind| {
        let mut s = RenderSettings::for_scene(&scene);
        s.estimator = kind;
        s.mis = MisSettings::default();
        s.sampler = SamplerKind::Independent;
        render_quiet(&scene, &s).film
    };
    let (light, mis) = (render(EstimatorKind::Light), render(EstimatorKind::Mis));
    let mut lit = 0;
    for (a, b) in light.pixels.iter().zip(&mis.pixels) {
        assert!((a.mean - b.mean).abs().max_element() <= 1e-5 * a.mean.max_element().max(1e-3));
        lit += (a.mean.max_element() > 0.0) as u32;
    }
    assert!(lit > 100, "the test scene must be lit ({lit} lit pixels)");
}

/// Veach's scene: BSDF sampling and every MIS variant agree per pixel block with a long
/// MIS render (MIS adds no bias), within 4 standard errors; light sampling agrees on the
/// image mean. Per block, light sampling is heavy-tailed on the sharpest plate (the mirror
/// lobe of n = 30000 meets the large light in a tiny solid angle that light samples find
/// about once in a thousand): its sample variance underestimates its error, and blocks
/// there sit at z ≈ −13 at 2048 spp but −3.5 at 32768 spp — the signature of a heavy tail,
/// not of bias, which would grow with the sample count.
#[test]
fn veach_mis_estimators_agree() {
    let scene = lightlab::scene::builtin::build("veach-mis").expect("scene");
    let render = |estimator: EstimatorKind, mis: MisSettings, spp: u32, seed: u64| {
        blocks(&render_small(&scene, spp, seed, |s| {
            s.estimator = estimator;
            s.mis = mis;
        }))
    };
    let reference = render(EstimatorKind::Mis, MisSettings::default(), 8192, 1);
    let mut runs = vec![("bsdf", EstimatorKind::Bsdf, MisSettings::default(), 4096)];
    for heuristic in MisHeuristic::ALL {
        let mis = MisSettings {
            heuristic,
            light_samples: 1,
            bsdf_samples: 2,
        };
        runs.push((heuristic.name(), EstimatorKind::Mis, mis, 1024));
    }
    let light = render(EstimatorKind::Light, MisSettings::default(), 4096, 5);
    let total = |b: &[(f64, f64)]| b.iter().fold((0.0, 0.0), |t, x| (t.0 + x.0, t.1 + x.1));
    let ((l, lv), (r, rv)) = (total(&light), total(&reference));
    let z_light = (l - r) / (lv + rv).sqrt();
    println!("       light: image mean z = {z_light:+.2}");
    assert!(
        z_light.abs() < 4.0,
        "light sampling's image mean: z = {z_light}"
    );
    let mut failures = Vec::new();
    for (label, estimator, mis, spp) in runs {
        let test = render(estimator, mis, spp, 5);
        let worst = worst(&block_z(&test, &reference));
        println!("{label:>12}: worst block z = {worst:+.2}");
        if worst.abs() >= 4.0 {
            failures.push((label, worst));
        }
    }
    assert!(
        failures.is_empty(),
        "blocks differ by ≥ 4 standard errors: {failures:?}"
    );
}

/// A mirror floor (a delta lobe) with a sphere light and a matte sphere, or with only a
/// point light (delta lobe and delta light together).
fn mirror_scene(point_light: bool) -> Scene {
    use lightlab::bsdf::{Conductor, ConductorMaterial};
    let mut b = SceneBuilder::new("mirror");
    let mirror = b.material(Material::Conductor(Conductor::from_material(
        ConductorMaterial::None,
    )));
    let matte = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::splat(0.6),
    }));
    b.rectangle(
        Vec3::new(-3.0, 0.0, 3.0),
        Vec3::new(6.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -6.0),
        mirror,
        None,
    );
    b.sphere(Vec3::new(-0.6, 0.5, 0.0), 0.5, matte, None);
    if point_light {
        b.point_light(Vec3::new(0.5, 1.5, 0.5), Spectrum::splat(6.0));
    } else {
        let e = Emission::new(Spectrum::splat(8.0));
        b.sphere(Vec3::new(0.8, 0.9, -0.4), 0.3, matte, Some(e));
    }
    let camera = Camera::look_at(Vec3::new(0.0, 1.2, 4.0), Vec3::ZERO, Vec3::Y, 45.0, 48, 32);
    b.build(camera, 1).expect("scene")
}

fn render_film(scene: &Scene, kind: EstimatorKind, spp: u32, seed: u64) -> lightlab::image::Film {
    let mut s = RenderSettings::for_scene(scene);
    s.estimator = kind;
    s.spp = spp;
    s.seed = seed;
    s.sampler = SamplerKind::Independent;
    let film = render_quiet(scene, &s).film;
    assert!(film.pixels.iter().all(|p| p.mean.is_finite()), "{kind}");
    film
}

/// Pixels that see only the mirror floor (every corner of the pixel does).
fn mirror_pixels(scene: &Scene) -> Vec<usize> {
    let cam = &scene.camera;
    let sees_mirror = |p: glam::Vec2| {
        let hit = scene.geometry.intersect(&cam.ray(p), f32::INFINITY);
        hit.is_some_and(|h| h.material == 0)
    };
    (0..cam.width * cam.height)
        .filter(|&i| {
            let corner = glam::Vec2::new((i % cam.width) as f32, (i / cam.width) as f32);
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .all(|&(dx, dy)| sees_mirror(corner + glam::Vec2::new(dx, dy) * 0.999))
        })
        .map(|i| i as usize)
        .collect()
}

/// With a delta lobe only BSDF sampling can find the light in the mirror: MIS gives the
/// BSDF estimator's image there (per block, within 4 standard errors), and light sampling
/// sees nothing in the mirror.
#[test]
fn mis_equals_bsdf_sampling_on_a_mirror() {
    let scene = mirror_scene(false);
    let mirror = mirror_pixels(&scene);
    assert!(
        mirror.len() > 300,
        "the mirror must fill the view ({})",
        mirror.len()
    );
    let bsdf = render_film(&scene, EstimatorKind::Bsdf, 256, 1);
    let mis = render_film(&scene, EstimatorKind::Mis, 256, 2);
    let light = render_film(&scene, EstimatorKind::Light, 16, 3);
    let lit = mirror
        .iter()
        .filter(|&&i| bsdf.pixels[i].mean.max_element() > 0.0)
        .count();
    assert!(
        lit > 20,
        "the light must be seen in the mirror ({lit} pixels)"
    );
    for &i in &mirror {
        assert_eq!(
            light.pixels[i].mean,
            Spectrum::ZERO,
            "light sampling in a mirror"
        );
    }
    // Compare the mirror pixels, 16 at a time (elsewhere the BSDF estimator meets the
    // sphere light at grazing angles too rarely for its variance estimate to hold).
    for (k, chunk) in mirror.chunks(16).enumerate() {
        let sum = |f: &lightlab::image::Film| {
            chunk.iter().fold((0f64, 0f64), |(m, v), &i| {
                let p = &f.pixels[i];
                (
                    m + p.mean.element_sum() as f64,
                    v + p.variance_of_mean().element_sum() as f64,
                )
            })
        };
        let (x, y) = (sum(&bsdf), sum(&mis));
        let z = (x.0 - y.0) / (x.1 + y.1).sqrt().max(1e-9);
        assert!(
            z.abs() < 4.0,
            "mirror pixels {k}: bsdf {} vs mis {} (z = {z})",
            x.0,
            y.0
        );
    }
}

/// A point light seen in a mirror: no strategy can find it, and MIS, light and BSDF
/// sampling agree on black; off the mirror MIS equals light sampling sample by sample.
#[test]
fn mis_with_delta_light_and_delta_lobe() {
    let scene = mirror_scene(true);
    let mirror = mirror_pixels(&scene);
    let mis = render_film(&scene, EstimatorKind::Mis, 8, 4);
    let light = render_film(&scene, EstimatorKind::Light, 8, 4);
    let bsdf = render_film(&scene, EstimatorKind::Bsdf, 8, 4);
    for &i in &mirror {
        for film in [&mis, &light, &bsdf] {
            assert_eq!(film.pixels[i].mean, Spectrum::ZERO);
        }
    }
    let mut lit = 0;
    for (a, b) in light.pixels.iter().zip(&mis.pixels) {
        assert!((a.mean - b.mean).abs().max_element() <= 1e-5 * a.mean.max_element().max(1e-3));
        lit += (a.mean.max_element() > 0.0) as u32;
    }
    assert!(lit > 50, "the matte sphere must be lit ({lit} pixels)");
}

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
