//! Many-light selection benchmark (issue 6; not a timed test):
//!
//! 1. the cost of one `select` (and of one `pmf`) per selector against the light count
//!    n = 10 … 10⁵ on `many-lights?n=N`, averaged over shading points seen by the camera;
//! 2. relMSE at 49 spp and render time per selector on `shirley-100` against a
//!    high-spp reference, with the equal-time relMSE (relMSE · time / time of `bvh`,
//!    since the error of an unbiased estimator falls as 1/spp).
//!
//! `cargo run --release --example light_select_bench [-- scaling | shirley]` (each part
//! about a minute on the shared 2-core machine). Writes PNGs to /tmp/light_select_bench/.

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use glam::Vec2;
use lightlab::image::io::write_film;
use lightlab::image::metrics::compare;
use lightlab::integrator::EstimatorKind;
use lightlab::light::ShadingPoint;
use lightlab::light::select::{LightSelect, LightSelector, Selector};
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::sampling::Rng32;
use lightlab::scene::{Scene, builtin};

/// Up to `count` shading points where camera rays through random pixels hit something.
fn shading_points(scene: &Scene, count: usize) -> Vec<ShadingPoint> {
    let c = &scene.camera;
    let mut rng = Rng32::new(7);
    let mut out = Vec::new();
    for _ in 0..count * 4 {
        let p = Vec2::new(
            rng.next_f32() * c.width as f32,
            rng.next_f32() * c.height as f32,
        );
        if let Some(hit) = scene.geometry.intersect(&c.ray(p), f32::INFINITY) {
            out.push(ShadingPoint {
                p: hit.p,
                ng: hit.ng,
                n: hit.frame.n,
            });
            if out.len() == count {
                break;
            }
        }
    }
    out
}

/// Nanoseconds per `select` and per `pmf` of the selected light, over `calls` calls
/// cycling through `points`.
fn time_selector(s: &Selector, points: &[ShadingPoint], calls: usize) -> (f64, f64) {
    let mut rng = Rng32::new(11);
    let mut chosen = Vec::with_capacity(calls);
    let start = Instant::now();
    for i in 0..calls {
        let at = &points[i % points.len()];
        chosen.push(black_box(s.select(at, rng.next_f32())).map(|x| x.index));
    }
    let select_ns = start.elapsed().as_secs_f64() * 1e9 / calls as f64;
    let start = Instant::now();
    let mut sum = 0.0f32;
    for (i, c) in chosen.iter().enumerate() {
        if let Some(index) = c {
            sum += s.pmf(&points[i % points.len()], *index);
        }
    }
    black_box(sum);
    let pmf_ns = start.elapsed().as_secs_f64() * 1e9 / calls as f64;
    (select_ns, pmf_ns)
}

fn scaling() {
    println!("## Selection cost per sample (ns; select / pmf), many-lights?n=N\n");
    println!("| n | uniform | power | adaptive | bvh | bvh build ms | bvh depth |");
    println!("|---|---|---|---|---|---|---|");
    for n in [10, 100, 1000, 10_000, 100_000] {
        let scene = builtin::build(&format!("many-lights?n={n}")).expect("scene");
        let points = shading_points(&scene, 256);
        let mut row = format!("| {n} |");
        let mut build_ms = 0.0;
        let mut depth = 0;
        for kind in LightSelect::ALL {
            let start = Instant::now();
            let s = Selector::new(kind, &scene.lights);
            if let Selector::Bvh(b) = &s {
                build_ms = start.elapsed().as_secs_f64() * 1e3;
                depth = b.depth();
            }
            // About 10⁷ light evaluations for the O(n) selector, 2·10⁵ calls otherwise.
            let calls = if kind == LightSelect::Adaptive {
                (10_000_000 / n).clamp(50, 200_000)
            } else {
                200_000
            };
            let (sel, pmf) = time_selector(&s, &points, calls);
            row += &format!(" {sel:.0} / {pmf:.0} |");
        }
        println!("{row} {build_ms:.1} | {depth} |");
    }
}

fn shirley() {
    let scene = builtin::build("shirley-100").expect("scene");
    let dir = Path::new("/tmp/light_select_bench");
    std::fs::create_dir_all(dir).expect("output directory");
    let (w, h) = (192, 128);
    let settings = |select: LightSelect, spp: u32, seed: u64| {
        let mut s = RenderSettings::for_scene(&scene);
        s.estimator = EstimatorKind::Light;
        s.light_select = select;
        s.spp = spp;
        s.seed = seed;
        s.resolution = Some((w, h));
        s
    };
    let ref_spp = 1024;
    let reference = render_quiet(&scene, &settings(LightSelect::Bvh, ref_spp, 1000));
    write_film(&reference.film, &dir.join("reference.png"), 0.0).expect("png");
    let ref_means = reference.film.means();

    // Dead ends of the BVH traversal: the probability that `select` returns no light.
    let bvh = Selector::new(LightSelect::Bvh, &scene.lights);
    let points = shading_points(&scene, 2000);
    let lost: f64 = points
        .iter()
        .map(|at| {
            1.0 - (0..scene.lights.len())
                .map(|i| bvh.pmf(at, i) as f64)
                .sum::<f64>()
        })
        .sum::<f64>()
        / points.len() as f64;

    println!(
        "\n## shirley-100 at 49 spp ({w}×{h}, light estimator, area sampling, Sobol), \
         reference: bvh at {ref_spp} spp ({:.1} s)\n",
        reference.time.as_secs_f64()
    );
    println!("| selector | relMSE | time s | relMSE at bvh's time | MSE vs uniform |");
    println!("|---|---|---|---|---|");
    let mut rows = Vec::new();
    for kind in LightSelect::ALL {
        // Median time of three renders (the machine is shared).
        let mut times = Vec::new();
        let mut out = None;
        for _ in 0..3 {
            let o = render_quiet(&scene, &settings(kind, 49, 0));
            times.push(o.time.as_secs_f64());
            out = Some(o);
        }
        times.sort_by(f64::total_cmp);
        let out = out.expect("rendered");
        let e = compare(&out.film.means(), None, &ref_means, None);
        write_film(&out.film, &dir.join(format!("{kind}.png")), 0.0).expect("png");
        rows.push((kind, e.rel_mse, e.mse, times[1]));
    }
    let bvh_time = rows
        .iter()
        .find(|r| r.0 == LightSelect::Bvh)
        .map_or(1.0, |r| r.3);
    let uniform_mse = rows[0].2;
    for (kind, rel, mse, t) in rows {
        println!(
            "| {kind} | {rel:.4} | {t:.3} | {:.4} | {:.2}× lower |",
            rel * t / bvh_time,
            uniform_mse / mse
        );
    }
    println!(
        "\nBVH dead ends on shirley-100: P(select returns no light) = {lost:.4} averaged over {} camera points",
        points.len()
    );
}

fn main() {
    let part = std::env::args().nth(1);
    if part.as_deref() != Some("shirley") {
        scaling();
    }
    if part.as_deref() != Some("scaling") {
        shirley();
    }
}
