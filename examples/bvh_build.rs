//! Times the BVH build of the benchmark meshes (`TriangleSet::new`: boxes, binned SAH,
//! collapse to BVH4, leaf blocks), median of `--runs` (default 9), on 1 and all threads.
//!
//! ```text
//! cargo run --release --example bvh_build [-- --runs N] [--mesh 100k|1M]
//! ```

use std::time::Instant;

use lightlab::geometry::TriangleSet;
use lightlab::geometry::bvh::bench_mesh::bench_mesh;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let runs: usize = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .map_or(9, |s| s.parse().expect("--runs takes a count"));
    assert!(runs > 0, "--runs takes a count of at least 1");
    let only = args
        .iter()
        .position(|a| a == "--mesh")
        .and_then(|i| args.get(i + 1));
    let all_threads = rayon::current_num_threads();
    println!("| mesh | build s, 1 thread | build s, {all_threads} threads |");
    println!("|---|---|---|");
    for (name, target) in [("100k", 100_000), ("1M", 1_000_000)] {
        if only.is_some_and(|o| o != name) {
            continue;
        }
        let (positions, indices) = bench_mesh(target);
        let median = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            let mut times: Vec<f64> = (0..runs)
                .map(|_| {
                    let start = Instant::now();
                    let set = pool.install(|| TriangleSet::new(&positions, &indices));
                    let seconds = start.elapsed().as_secs_f64();
                    std::hint::black_box(set);
                    seconds
                })
                .collect();
            times.sort_by(f64::total_cmp);
            times[runs / 2]
        };
        println!("| {name} | {:.3} | {:.3} |", median(1), median(all_threads));
    }
}
