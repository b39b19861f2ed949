//! relMSE of every estimator (and every MIS variant) at a low spp against a high-spp
//! reference, per material seen by the camera: the lecture's claim that BSDF sampling wins
//! on glossy lobes and light sampling on diffuse surfaces, and Veach's per-plate figure,
//! measured.
//!
//! `cargo run --release --example estimator_regions -- [SCENE] [SPP] [REF_SPP] [WIDTH]`
//! (defaults: builtin:assignment 16 4096 192).

use glam::Vec2;
use lightlab::bsdf::Material;
use lightlab::image::metrics::compare;
use lightlab::integrator::{EstimatorKind, MisHeuristic, MisSettings};
use lightlab::math::Spectrum;
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::scene;

/// A short label for a material.
fn label(m: &Material) -> String {
    match m {
        Material::Diffuse(_) => "diffuse".into(),
        Material::Phong(p) => format!("Phong n={}", p.exponent),
        other => format!("{other:?}")
            .split(['(', ' '])
            .next()
            .unwrap_or("?")
            .to_string(),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("builtin:assignment", |s| s.as_str());
    let spp: u32 = args.get(2).map_or(16, |s| s.parse().expect("SPP"));
    let ref_spp: u32 = args.get(3).map_or(4096, |s| s.parse().expect("REF_SPP"));
    let width: u32 = args.get(4).map_or(192, |s| s.parse().expect("WIDTH"));
    let scene = scene::load(name).expect("scene");
    let height = width * scene.camera.height / scene.camera.width;
    let mut base = RenderSettings::for_scene(&scene);
    base.resolution = Some((width, height));
    let camera = base.camera(&scene);

    // Region of each pixel: the material its centre ray sees (emitters and background
    // are left out).
    let region: Vec<Option<u32>> = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let ray = camera.ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            match scene.geometry.intersect(&ray, f32::INFINITY) {
                Some(h) if h.light == lightlab::geometry::NO_LIGHT => Some(h.material),
                _ => None,
            }
        })
        .collect();
    let mut materials: Vec<u32> = region.iter().flatten().copied().collect();
    materials.sort_unstable();
    materials.dedup();

    let mut reference = base.clone();
    reference.spp = ref_spp;
    reference.seed = 1_000_003;
    let t = std::time::Instant::now();
    let r = render_quiet(&scene, &reference).film;
    eprintln!(
        "reference: {ref_spp} spp in {:.1} s",
        t.elapsed().as_secs_f64()
    );
    let r_means = r.means();

    let mut runs: Vec<(String, RenderSettings)> = Vec::new();
    for kind in EstimatorKind::unbiased() {
        if kind == EstimatorKind::Mis {
            continue;
        }
        let mut s = base.clone();
        s.estimator = kind;
        runs.push((kind.to_string(), s));
    }
    for heuristic in MisHeuristic::ALL {
        let mut s = base.clone();
        s.estimator = EstimatorKind::Mis;
        s.mis = MisSettings {
            heuristic,
            ..MisSettings::default()
        };
        runs.push((format!("mis {heuristic}"), s));
    }

    println!(
        "{name}, {width}x{height}, {spp} spp vs a {ref_spp}-spp reference ({})",
        reference.patch()
    );
    let header: Vec<String> = materials
        .iter()
        .map(|&m| format!("{} #{m}", label(&scene.materials[m as usize])))
        .collect();
    println!("| strategy | {} | all | time (s) |", header.join(" | "));
    println!("|---|{}---|---|", "---|".repeat(materials.len()));
    for (label, mut s) in runs {
        s.spp = spp;
        let out = render_quiet(&scene, &s);
        let means = out.film.means();
        let rel = |want: Option<u32>| {
            let (a, b): (Vec<Spectrum>, Vec<Spectrum>) = means
                .iter()
                .zip(&r_means)
                .zip(&region)
                .filter(|(_, g)| g.is_some() && (want.is_none() || **g == want))
                .map(|((a, b), _)| (*a, *b))
                .unzip();
            compare(&a, None, &b, None).rel_mse
        };
        let cells: Vec<String> = materials
            .iter()
            .map(|&m| format!("{:.3e}", rel(Some(m))))
            .collect();
        println!(
            "| {label} | {} | {:.3e} | {:.2} |",
            cells.join(" | "),
            rel(None),
            out.time.as_secs_f64()
        );
    }
}
