//! Measures every light-sampling strategy of every emitter shape of `sphere-near-plane`:
//! relMSE at 16 spp against a high-spp reference (one emitter shape per scene, light
//! estimator), and the cost of one `Light::sample` call in ns at random floor points.
//!
//! `cargo run --release --example light_strategies [REFERENCE_SPP]` (default 1024; the
//! images are 192 × 128).

use std::hint::black_box;
use std::time::Instant;

use glam::{Vec2, Vec3};
use lightlab::image::metrics::compare;
use lightlab::light::{LightSampling, ShadingPoint};
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::sampling::{Rng32, Uniform};
use lightlab::scene::builtin::sphere_near_plane::{NearPlaneEmitter, build_with};

fn strategies(emitter: NearPlaneEmitter) -> &'static [LightSampling] {
    use LightSampling::*;
    match emitter {
        NearPlaneEmitter::Sphere => &[Area, VisibleArea, SolidAngle, Geometric],
        _ => &[Area, SolidAngle],
    }
}

/// ns per `sample` call at random points of the floor within 2 of the light's centre.
fn cost_ns(scene: &lightlab::scene::Scene, strategy: LightSampling) -> f64 {
    let center = scene.lights.iter().fold(Vec3::ZERO, |c, l| match l {
        lightlab::light::Light::Area(a) => {
            let b = a.shape.bounds();
            c + 0.5 * (b.min + b.max)
        }
        lightlab::light::Light::Polygon(p) => c + p.polygon.vertices()[0],
        lightlab::light::Light::Point(p) => c + p.position,
        lightlab::light::Light::Environment(_) => c,
    }) / scene.lights.len() as f32;
    let mut rng = Rng32::new(7);
    let n = 400_000;
    let points: Vec<(ShadingPoint, usize, Vec2)> = (0..n)
        .map(|_| {
            let q = (rng.next_2d() * 4.0 - 2.0) + Vec2::new(center.x, center.z);
            let at = ShadingPoint {
                p: Vec3::new(q.x, 0.0, q.y),
                ng: Vec3::Y,
                n: Vec3::Y,
            };
            let index = (rng.next_1d() * scene.lights.len() as f32) as usize;
            (at, index.min(scene.lights.len() - 1), rng.next_2d())
        })
        .collect();
    let start = Instant::now();
    let mut hits = 0u32;
    for (at, index, u) in &points {
        hits += black_box(scene.lights[*index].sample(at, *u, strategy.into())).is_some() as u32;
    }
    black_box(hits);
    start.elapsed().as_secs_f64() * 1e9 / n as f64
}

fn main() {
    let reference_spp: u32 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1024);
    println!("| emitter | strategy | relMSE @16 spp | ns / sample |");
    println!("|---|---|---|---|");
    for emitter in [
        NearPlaneEmitter::Sphere,
        NearPlaneEmitter::Rectangle,
        NearPlaneEmitter::Mesh,
        NearPlaneEmitter::Polygon,
        NearPlaneEmitter::Disk,
    ] {
        let scene = build_with(&[emitter]).expect("scene");
        let mut settings = RenderSettings::for_scene(&scene);
        settings.resolution = Some((192, 128));
        settings.light_sampling = LightSampling::SolidAngle;
        settings.spp = reference_spp;
        settings.seed = 1_000_003;
        let reference = render_quiet(&scene, &settings).film.means();
        for &strategy in strategies(emitter) {
            settings.light_sampling = strategy;
            settings.spp = 16;
            settings.seed = 0;
            let out = render_quiet(&scene, &settings);
            let e = compare(&out.film.means(), None, &reference, None);
            println!(
                "| {emitter:?} | {strategy} | {:.4e} | {:.1} |",
                e.rel_mse,
                cost_ns(&scene, strategy)
            );
        }
    }
}
