//! relMSE of every estimator at a low spp against a high-spp reference, split into the
//! pixels whose camera ray sees a diffuse surface and those that see a glossy (Phong) one:
//! the lecture's claim that BSDF sampling wins on glossy lobes and light sampling on
//! diffuse surfaces, measured.
//!
//! `cargo run --release --example estimator_regions -- [SCENE] [SPP] [REF_SPP] [WIDTH]`
//! (defaults: builtin:assignment 16 4096 192).

use glam::Vec2;
use lightlab::bsdf::Material;
use lightlab::image::metrics::compare;
use lightlab::integrator::EstimatorKind;
use lightlab::math::Spectrum;
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::scene;

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

    // Region of each pixel: what its centre ray sees.
    let region: Vec<&str> = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let ray = camera.ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            match scene.geometry.intersect(&ray, f32::INFINITY) {
                Some(h) if h.light != lightlab::geometry::NO_LIGHT => "emitter",
                Some(h) => match scene.materials[h.material as usize] {
                    Material::Diffuse(_) => "diffuse",
                    _ => "glossy",
                },
                None => "background",
            }
        })
        .collect();

    let mut reference = base.clone();
    reference.spp = ref_spp;
    reference.seed = 1_000_003;
    let t = std::time::Instant::now();
    let r = render_quiet(&scene, &reference).film;
    eprintln!(
        "reference: {ref_spp} spp ({}) in {:.1} s",
        reference.estimator,
        t.elapsed().as_secs_f64()
    );
    let r_means = r.means();

    println!(
        "{name}, {width}x{height}, {spp} spp vs a {ref_spp}-spp {} reference",
        reference.estimator
    );
    println!("| estimator | relMSE diffuse | relMSE glossy | relMSE all | time (s) |");
    println!("|---|---|---|---|---|");
    for kind in EstimatorKind::ALL {
        let mut s = base.clone();
        s.estimator = kind;
        s.spp = spp;
        let out = render_quiet(&scene, &s);
        let means = out.film.means();
        let pick = |want: &str| -> (Vec<Spectrum>, Vec<Spectrum>) {
            means
                .iter()
                .zip(&r_means)
                .zip(&region)
                .filter(|(_, g)| want == "all" || **g == want)
                .map(|((a, b), _)| (*a, *b))
                .unzip()
        };
        let rel = |want: &str| {
            let (a, b) = pick(want);
            compare(&a, None, &b, None).rel_mse
        };
        println!(
            "| {kind} | {:.4e} | {:.4e} | {:.4e} | {:.2} |",
            rel("diffuse"),
            rel("glossy"),
            rel("all"),
            out.time.as_secs_f64()
        );
    }
}
