//! Times the light BVH's construction (`Selector::new(LightSelect::Bvh)`) on
//! `many-lights?n=N`: the median and the fastest of K builds in one process.
//!
//! `cargo run --release --example light_bvh_build -- [N] [K]` (defaults 100000 and 9);
//! `RAYON_NUM_THREADS=1` for one thread. BENCHMARKS.md, session 12.

use std::time::Instant;

use lightlab::light::select::{LightSelect, Selector};
use lightlab::scene::builtin;

fn main() {
    let mut args = std::env::args().skip(1);
    let mut next = |default: usize| {
        args.next()
            .map(|s| s.parse().expect("a count"))
            .unwrap_or(default)
    };
    let (n, builds) = (next(100_000), next(9).max(1));
    let scene = builtin::build(&format!("many-lights?n={n}")).expect("scene");
    let mut ms: Vec<f64> = (0..builds)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(Selector::new(LightSelect::Bvh, &scene.lights));
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    ms.sort_by(f64::total_cmp);
    println!(
        "light BVH over {n} lights: median {:.1} ms, fastest {:.1} ms ({builds} builds)",
        ms[ms.len() / 2],
        ms[0]
    );
}
