//! Environment lighting is unbiased with every estimator: the white furnace (a white
//! diffuse sphere inside a constant environment of radiance 1 looks exactly 1), the
//! irradiance π·L from a constant environment (as a constant and as a map) on an unoccluded
//! plane, and agreement of light, BSDF and MIS renders of `envmap` per pixel block.

mod common;
use common::blocks::{block_z, blocks, worst};

use glam::{Mat3, Vec3};
use lightlab::bsdf::{Diffuse, Material};
use lightlab::geometry::Ray;
use lightlab::image::Film;
use lightlab::integrator::{Estimator, EstimatorKind, MisHeuristic, MisSettings};
use lightlab::light::environment::LatLongImage;
use lightlab::light::select::{LightSelect, LightSelector};
use lightlab::light::{Environment, LightStrategy};
use lightlab::math::Spectrum;
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::sampling::{Rng32, SamplerKind};
use lightlab::scene::Camera;
use lightlab::scene::builder::Emission;
use lightlab::scene::{Scene, SceneBuilder, builtin};

fn camera() -> Camera {
    Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 40.0, 16, 16)
}

/// Mean and standard error of `n` estimates at the first hit of `ray`, seen along it.
fn estimate(scene: &Scene, kind: EstimatorKind, ray: &Ray, n: usize) -> (f64, f64) {
    estimate_with(
        &Estimator::new(scene, kind, LightSelect::Uniform),
        scene,
        ray,
        n,
    )
}

/// [`estimate`] with the estimator `est`.
fn estimate_with(est: &Estimator, scene: &Scene, ray: &Ray, n: usize) -> (f64, f64) {
    let kind = est.kind;
    let hit = scene.geometry.intersect(ray, f32::INFINITY).expect("hit");
    let mut rng = Rng32::new(1234 + kind as u64);
    let (mut sum, mut sum2) = (0f64, 0f64);
    for _ in 0..n {
        let v = est.direct(scene, &hit, -ray.d.normalize(), &mut rng).y as f64;
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

fn assert_close(what: &str, (mean, se): (f64, f64), exact: f64) {
    let z = (mean - exact) / se.max(1e-9);
    println!("{what}: {mean:.5} ± {se:.5} vs {exact} (z = {z:+.2})");
    // A zero-variance estimator must be exact to rounding.
    assert!(
        z.abs() < 4.0 || (mean - exact).abs() < 1e-4 * exact,
        "{what}: {mean} vs {exact}, z = {z}"
    );
}

#[test]
fn white_furnace_is_one_for_every_estimator() {
    for map in [false, true] {
        let mut b = SceneBuilder::new("furnace");
        let white = b.material(Material::Diffuse(Diffuse {
            reflectance: Spectrum::ONE,
        }));
        b.sphere(Vec3::ZERO, 1.0, white, None);
        b.environment(if map {
            let img = LatLongImage::new(8, 5, vec![Spectrum::ONE; 40]).expect("image");
            Environment::from_image(img, 1.0, Mat3::from_rotation_z(0.4)).expect("env")
        } else {
            Environment::constant(Spectrum::ONE)
        });
        let scene = b.build(camera(), 1).expect("scene");
        for kind in EstimatorKind::unbiased() {
            for target in [Vec3::ZERO, Vec3::new(0.6, 0.5, 0.0)] {
                let ray = Ray::new(Vec3::new(0.0, 0.0, 4.0), target - Vec3::new(0.0, 0.0, 4.0));
                assert_close(
                    &format!("furnace map={map} {kind} at {target}"),
                    estimate(&scene, kind, &ray, 100_000),
                    1.0,
                );
            }
        }
        // MIS compensation of a uniform environment leaves the BSDF samples alone, each
        // exactly one here: a zero-variance estimate (one-sample MIS included, which
        // then never picks the light technique).
        let ray = Ray::new(Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.6, 0.5, -4.0));
        for heuristic in [MisHeuristic::Power, MisHeuristic::OneSample] {
            let compensated = Estimator::new(&scene, EstimatorKind::Mis, LightSelect::Uniform)
                .with_mis(MisSettings {
                    heuristic,
                    ..MisSettings::default()
                })
                .with_light_strategy(&scene, compensated());
            let (mean, se) = estimate_with(&compensated, &scene, &ray, 10_000);
            assert!(
                (mean - 1.0).abs() < 1e-5 && se < 1e-6,
                "compensated furnace map={map} {heuristic}: {mean} ± {se}"
            );
        }
        // The background is the environment itself.
        let mut s = RenderSettings::for_scene(&scene);
        s.spp = 2;
        let film = render_quiet(&scene, &s).film;
        let corner = film.pixel(0, 0).mean;
        assert!(
            (corner - Spectrum::ONE).abs().max_element() < 1e-5,
            "background {corner}"
        );
    }
}

/// Lambertian points go without BSDF samples (`diffuse_bsdf_samples: Some(0)`) only where
/// light samples reach every emitter, never under a sky: sampled with MIS compensation,
/// its texels at or below the mean are left to BSDF samples; without it, its samples stop
/// at the geometric horizon, which a BSDF sample about a shading normal may cross. Both
/// ways the estimates are the same bits as with the BSDF samples.
#[test]
fn a_sky_keeps_the_bsdf_samples_of_lambertian_points() {
    let mut b = SceneBuilder::new("sky");
    let white = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::ONE,
    }));
    b.sphere(Vec3::ZERO, 1.0, white, None);
    // Bright and dim texels: compensation samples only the bright ones.
    let texels = (0..40)
        .map(|i| Spectrum::splat([0.2, 3.0][i % 3 / 2]))
        .collect();
    let img = LatLongImage::new(8, 5, texels).expect("image");
    b.environment(Environment::from_image(img, 1.0, Mat3::from_rotation_z(0.4)).expect("env"));
    let scene = b.build(camera(), 1).expect("scene");
    let ray = Ray::new(Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.3, 0.4, -4.0));
    for lights in [compensated(), LightStrategy::default()] {
        let mis = |diffuse_bsdf_samples| {
            Estimator::new(&scene, EstimatorKind::Mis, LightSelect::Uniform)
                .with_mis(MisSettings {
                    diffuse_bsdf_samples,
                    ..MisSettings::default()
                })
                .with_light_strategy(&scene, lights)
        };
        let both = estimate_with(&mis(None), &scene, &ray, 20_000);
        let alone = estimate_with(&mis(Some(0)), &scene, &ray, 20_000);
        assert_eq!(both, alone, "{lights:?}: the BSDF samples stay");
    }
}

#[test]
fn constant_environment_gives_irradiance_pi_l_on_a_plane() {
    let (rho, l) = (0.8f32, 1.5f32);
    for map in [false, true] {
        let mut b = SceneBuilder::new("plane");
        let m = b.material(Material::Diffuse(Diffuse {
            reflectance: Spectrum::splat(rho),
        }));
        b.rectangle(
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -2.0),
            m,
            None,
        );
        b.environment(if map {
            let img = LatLongImage::new(16, 9, vec![Spectrum::splat(l); 144]).expect("image");
            Environment::from_image(img, 1.0, Mat3::IDENTITY).expect("env")
        } else {
            Environment::constant(Spectrum::splat(l))
        });
        let scene = b.build(camera(), 1).expect("scene");
        let ray = Ray::new(Vec3::new(0.2, 2.0, 0.3), Vec3::new(-0.1, -1.0, 0.05));
        // E = π·L, so L_out = ρ/π · π·L = ρ·L.
        for kind in EstimatorKind::unbiased() {
            assert_close(
                &format!("plane map={map} {kind}"),
                estimate(&scene, kind, &ray, 100_000),
                (rho * l) as f64,
            );
        }
        let compensated = Estimator::new(&scene, EstimatorKind::Mis, LightSelect::Bvh)
            .with_light_strategy(&scene, compensated());
        assert_close(
            &format!("plane map={map} mis, compensated"),
            estimate_with(&compensated, &scene, &ray, 100_000),
            (rho * l) as f64,
        );
    }
}

/// Light sampling as `render` sets it up under `--estimator mis`: environments with MIS
/// compensation.
fn compensated() -> LightStrategy {
    LightStrategy {
        env_compensation: true,
        ..LightStrategy::default()
    }
}

/// A plane under a constant environment and a sphere light straight above the shading
/// point. The sphere (radius r at distance d) hides a cap of the sky of projected solid
/// angle π(r/d)² and shows its own radiance there instead, so
/// L_out = ρ·(L_env·(1 − (r/d)²) + L_s·(r/d)²). Under MIS compensation the constant
/// draws no light samples and every selector gives the sphere all of them (the
/// environment's probability is zero): unbiased under every heuristic and selector, and
/// the sphere's estimates carry more of the budget than with the environment selected.
#[test]
fn compensated_constant_environment_gives_its_turns_to_the_other_lights() {
    let (rho, l_env, l_s, r, d) = (0.7f32, 0.5f32, 20.0f32, 0.3f32, 1.5f32);
    let mut b = SceneBuilder::new("plane, sphere and sky");
    let m = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::splat(rho),
    }));
    b.rectangle(
        Vec3::new(-3.0, 0.0, 3.0),
        Vec3::new(6.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -6.0),
        m,
        None,
    );
    let black = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::ZERO,
    }));
    b.sphere(
        Vec3::new(0.0, d, 0.0),
        r,
        black,
        Some(Emission {
            radiance: Spectrum::splat(l_s),
            texture: None,
            two_sided: false,
        }),
    );
    b.environment(Environment::constant(Spectrum::splat(l_env)));
    let scene = b.build(camera(), 1).expect("scene");
    let sin2 = ((r / d) * (r / d)) as f64;
    let exact = rho as f64 * (l_env as f64 * (1.0 - sin2) + l_s as f64 * sin2);
    // Seen from (0.5, 2, 2) towards the origin, past the sphere.
    let ray = Ray::new(Vec3::new(0.5, 2.0, 2.0), Vec3::new(-0.5, -2.0, -2.0));
    let env = scene
        .lights
        .iter()
        .position(|l| l.is_infinite())
        .expect("sky");
    let at = lightlab::light::ShadingPoint {
        p: Vec3::ZERO,
        ng: Vec3::Y,
        n: Vec3::Y,
    };
    for select in [
        LightSelect::Uniform,
        LightSelect::Power,
        LightSelect::Adaptive,
        LightSelect::Bvh,
        LightSelect::Ris,
    ] {
        for heuristic in [
            MisHeuristic::Balance,
            MisHeuristic::Power,
            MisHeuristic::OneSample,
        ] {
            let est = Estimator::new(&scene, EstimatorKind::Mis, select)
                .with_mis(MisSettings {
                    heuristic,
                    ..MisSettings::default()
                })
                .with_light_strategy(&scene, compensated());
            assert_eq!(est.selector.pmf(&at, env), 0.0, "{select}");
            assert_close(
                &format!("sphere and sky, {select}, {heuristic}"),
                estimate_with(&est, &scene, &ray, 200_000),
                exact,
            );
        }
    }
}

fn render_envmap(kind: EstimatorKind, spp: u32, seed: u64) -> Film {
    render_envmap_with(kind, false, spp, seed)
}

fn render_envmap_with(kind: EstimatorKind, compensation: bool, spp: u32, seed: u64) -> Film {
    let scene = builtin::build("envmap").expect("scene");
    let mut s = RenderSettings::for_scene(&scene);
    s.estimator = kind;
    s.envmap_compensation = compensation;
    s.spp = spp;
    s.seed = seed;
    s.sampler = SamplerKind::Independent;
    s.resolution = Some((48, 32));
    let film = render_quiet(&scene, &s).film;
    assert!(film.pixels.iter().all(|p| p.mean.is_finite()), "{kind}");
    film
}

/// Light sampling is heavy-tailed on the glossy spheres (it spends its samples on the sun
/// while the lobe reflects the sky), so its blocks sit up to about 3 standard errors from
/// the reference at 1024 spp with no bias found by 4·10⁶-sample pixel checks; hence 2048.
#[test]
fn envmap_light_bsdf_and_mis_agree() {
    let reference = blocks(&render_envmap(EstimatorKind::Mis, 4096, 2));
    let mut failures = Vec::new();
    for (kind, compensation, spp) in [
        (EstimatorKind::Light, false, 2048),
        (EstimatorKind::Bsdf, false, 4096),
        (EstimatorKind::Mis, false, 512),
        (EstimatorKind::Mis, true, 512),
    ] {
        let seed = 10 + kind as u64 + 5 * compensation as u64;
        let test = blocks(&render_envmap_with(kind, compensation, spp, seed));
        let worst = worst(&block_z(&test, &reference));
        println!("{kind:>8} (compensation {compensation}): worst block z = {worst:+.2}");
        if worst.abs() >= 4.0 {
            failures.push((kind, compensation, worst));
        }
    }
    assert!(
        failures.is_empty(),
        "blocks differ by ≥ 4 standard errors: {failures:?}"
    );
}

#[test]
fn environment_maps_load_from_exr_and_hdr() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("envmaps");
    std::fs::create_dir_all(&dir).expect("dir");
    let (w, h) = (8u32, 4u32);
    let value = |x: u32, y: u32| Spectrum::new(x as f32 * 0.5, y as f32 + 0.25, 2.0);
    let mut film = Film::new(w, h);
    for y in 0..h {
        for x in 0..w {
            film.pixels[(y * w + x) as usize].add(value(x, y));
        }
    }
    let exr = dir.join("map.exr");
    lightlab::image::io::write_film(&film, &exr, 1.0).expect("write exr");
    let hdr = dir.join("map.hdr");
    let pixels: Vec<image::Rgb<f32>> = (0..h)
        .flat_map(|y| (0..w).map(move |x| image::Rgb(value(x, y).to_array())))
        .collect();
    let file = std::fs::File::create(&hdr).expect("hdr file");
    image::codecs::hdr::HdrEncoder::new(file)
        .encode(&pixels, w as usize, h as usize)
        .expect("write hdr");
    for (path, tolerance) in [(exr, 1e-6), (hdr, 1e-2)] {
        let env = lightlab::scene::environment_from_file(&path, 2.0, Mat3::IDENTITY).expect("load");
        // Texel (3, 1) sits at u = 3.5/8, v = 1/3: direction (sin θ sin φ, cos θ, −sin θ cos φ).
        let (theta, phi) = (
            std::f32::consts::PI / 3.0,
            2.0 * std::f32::consts::PI * 3.5 / 8.0,
        );
        let d = Vec3::new(
            theta.sin() * phi.sin(),
            theta.cos(),
            -theta.sin() * phi.cos(),
        );
        let got = env.eval(d);
        let want = value(3, 1) * 2.0;
        assert!(
            (got - want).abs().max_element() <= tolerance * want.max_element() * 4.0,
            "{}: {got} vs {want}",
            path.display()
        );
    }
    let missing =
        lightlab::scene::environment_from_file(&dir.join("missing.exr"), 1.0, Mat3::IDENTITY);
    assert!(missing.unwrap_err().contains("missing.exr"));
}
