//! Compares lightlab's BVH with the `obvhs` crate's CWBVH on the benchmark mesh: build
//! time, closest-hit Mrays/s on primary rays and any-hit Mrays/s on shadow rays, on one
//! thread and on all threads (median of 5 runs each), with the hits of both checked
//! against each other.
//!
//! ```text
//! cargo run --release --features obvhs-compare --example bvh_compare [-- --dump DIR]
//! ```
//! `--dump DIR` also writes each mesh and the rays as raw little-endian files for
//! `benches/embree_compare.py`.
//!
//! Measured on the 2-core development machine on 2026-11-26, session 17 (AMD EPYC,
//! AVX-512 present but the build targets baseline x86-64, with AVX2 kernels chosen at run
//! time where they exist; Embree 4.4 via `embreex` picks its widest ISA), Mrays/s, the
//! median of three rounds of medians of 5, 2²⁰ rays of each kind; build times here are
//! single builds (`examples/bvh_build.rs` takes medians); see BENCHMARKS.md, session 17,
//! for Embree 3's single rays, packets and build on the same rays and meshes:
//!
//! | mesh | BVH | build s | closest 1 thr | closest 2 thr | any-hit 1 thr | any-hit 2 thr |
//! |---|---|---|---|---|---|---|
//! | 100k | lightlab BVH4 | 0.035 | 14.19 | 28.51 | 5.43 | 10.58 |
//! | 100k | lightlab BVH4, packets of 8 (coherent) | | 21.74 | 43.23 | | |
//! | 100k | obvhs CWBVH (medium_build) | 0.049 | 5.37 | 11.16 | 2.95 | 5.88 |
//! | 100k | Embree 4 (embreex) | 0.047 | 11.62 | 23.11 | 4.71 | 8.96 |
//! | 1M | lightlab BVH4 | 0.265 | 9.31 | 18.88 | 4.20 | 8.41 |
//! | 1M | lightlab BVH4, packets of 8 (coherent) | | 12.76 | 24.55 | | |
//! | 1M | obvhs CWBVH (medium_build) | 0.571 | 4.82 | 9.84 | 2.48 | 4.86 |
//! | 1M | Embree 4 (embreex) | 0.622 | 9.29 | 18.37 | 2.47 | 4.59 |
//!
//! The machine is shared, so 2-thread figures in particular vary by ±20 % between runs.

use std::time::Instant;

use glam::{Vec3, Vec3A};
use lightlab::geometry::bvh::PACKET;
use lightlab::geometry::bvh::bench_mesh::{BenchRays, bench_mesh, bench_rays};
use lightlab::geometry::{Ray, TriangleSet};
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::{BvhBuildParams, ray::RayHit, rt_triangle::RtTriangle, triangle::Triangle};
use rayon::prelude::*;

/// Timed runs per figure; the median is reported.
const RUNS: usize = 5;
/// Rays of each kind.
const RAY_COUNT: usize = 1 << 20;

/// obvhs's fastest CPU path: a compressed 8-wide BVH over triangles stored in its
/// primitive order with its own Möller–Trumbore layout.
struct Obvhs {
    bvh: obvhs::cwbvh::CwBvh,
    triangles: Vec<RtTriangle>,
}

impl Obvhs {
    fn new(positions: &[Vec3], indices: &[[u32; 3]]) -> Obvhs {
        let v = |i: u32| Vec3A::from(positions[i as usize]);
        let tris: Vec<Triangle> = indices
            .iter()
            .map(|t| Triangle {
                v0: v(t[0]),
                v1: v(t[1]),
                v2: v(t[2]),
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Default::default(),
        );
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| RtTriangle::from(&tris[i as usize]))
            .collect();
        Obvhs { bvh, triangles }
    }

    fn ray(ray: &Ray, t_max: f32) -> obvhs::ray::Ray {
        obvhs::ray::Ray::new(ray.o.into(), ray.d.into(), 0.0, t_max)
    }

    fn closest(&self, ray: &Ray) -> Option<f32> {
        let mut hit = RayHit::none();
        let found = self
            .bvh
            .ray_traverse(Self::ray(ray, f32::INFINITY), &mut hit, |r, id| {
                self.triangles[id].intersect(r)
            });
        found.then_some(hit.t)
    }

    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        !self.bvh.ray_traverse_miss(Self::ray(ray, t_max), |r, id| {
            self.triangles[id].intersect(r)
        })
    }
}

/// Median wall time of `RUNS` runs of `f`, in seconds.
fn median_seconds(mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..RUNS)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[RUNS / 2]
}

/// Mrays/s of `trace` over `rays` on a pool of `threads` threads (median of `RUNS`).
fn mrays<T: Sync>(rays: &[T], threads: usize, trace: impl Fn(&T) -> bool + Sync) -> f64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    let seconds = median_seconds(|| {
        let hits: usize = pool.install(|| {
            rays.par_chunks(4096)
                .map(|c| c.iter().filter(|r| trace(r)).count())
                .sum()
        });
        std::hint::black_box(hits);
    });
    rays.len() as f64 / seconds / 1e6
}

/// Mrays/s of closest-hit packets of eight consecutive primary rays (neighbouring pixels
/// of a row, as `benches/embree_packets.c` groups them for `rtcIntersect8`) on a pool of
/// `threads` threads (median of `RUNS`).
fn packet_mrays(set: &TriangleSet, packets: &[[Ray; PACKET]], threads: usize) -> f64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    let t_max = [f32::INFINITY; PACKET];
    let seconds = median_seconds(|| {
        let hits: usize = pool.install(|| {
            packets
                .par_chunks(4096 / PACKET)
                .map(|c| {
                    c.iter()
                        .map(|p| set.closest_hit_packet(p, &t_max).iter().flatten().count())
                        .sum::<usize>()
                })
                .sum()
        });
        std::hint::black_box(hits);
    });
    (packets.len() * PACKET) as f64 / seconds / 1e6
}

/// Rays on which the two closest-hit answers differ (hit vs miss, or t by more than 1e-4
/// relative), and shadow rays on which the any-hit answers differ.
fn disagreements(ours: &TriangleSet, theirs: &Obvhs, rays: &BenchRays) -> (usize, usize) {
    let closest = rays
        .primary
        .par_iter()
        .filter(|r| {
            match (
                ours.closest_hit(r, f32::INFINITY).map(|h| h.1.t),
                theirs.closest(r),
            ) {
                (Some(a), Some(b)) => (a - b).abs() > 1e-4 * a.max(b),
                (a, b) => a.is_some() != b.is_some(),
            }
        })
        .count();
    let shadow = rays
        .shadow
        .par_iter()
        .filter(|(r, t)| ours.any_hit(r, *t) != theirs.occluded(r, *t))
        .count();
    (closest, shadow)
}

/// Writes `values` as raw little-endian 32-bit words.
fn write_raw<T: Copy>(path: &std::path::Path, values: &[T], to_words: impl Fn(T) -> Vec<u32>) {
    let bytes: Vec<u8> = values
        .iter()
        .flat_map(|&v| to_words(v))
        .flat_map(u32::to_le_bytes)
        .collect();
    std::fs::write(path, bytes).unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
}

/// Writes the mesh (`NAME.vertices.f32`, `NAME.indices.u32`) and rays (`NAME.primary.f32`
/// and `NAME.shadow.f32`, 7 floats per ray: o, d, t_max) into `dir`.
fn dump(
    dir: &std::path::Path,
    name: &str,
    positions: &[Vec3],
    indices: &[[u32; 3]],
    rays: &BenchRays,
) {
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("creating {}: {e}", dir.display()));
    let file = |kind: &str| dir.join(format!("{name}.{kind}"));
    write_raw(&file("vertices.f32"), positions, |p| {
        p.to_array().map(f32::to_bits).to_vec()
    });
    write_raw(&file("indices.u32"), indices, |t| t.to_vec());
    let ray_words = |(r, t): (Ray, f32)| {
        [r.o.to_array(), r.d.to_array()]
            .concat()
            .into_iter()
            .chain([t])
            .map(f32::to_bits)
            .collect()
    };
    let primary: Vec<(Ray, f32)> = rays.primary.iter().map(|r| (*r, f32::INFINITY)).collect();
    write_raw(&file("primary.f32"), &primary, ray_words);
    write_raw(&file("shadow.f32"), &rays.shadow, ray_words);
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dump_dir = args
        .iter()
        .position(|a| a == "--dump")
        .and_then(|i| args.get(i + 1))
        .map(std::path::PathBuf::from);
    let all_threads = rayon::current_num_threads();
    let rays = bench_rays(RAY_COUNT, 1);
    println!(
        "{RAY_COUNT} primary (closest hit) and {RAY_COUNT} shadow (any hit) rays, median of {RUNS} runs"
    );
    println!(
        "| mesh | BVH | build s | closest Mrays/s 1 thr | closest {all_threads} thr | any-hit 1 thr | any-hit {all_threads} thr |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, target) in [("100k", 100_000), ("1M", 1_000_000)] {
        let (positions, indices) = bench_mesh(target);
        if let Some(dir) = &dump_dir {
            dump(dir, name, &positions, &indices, &rays);
        }
        let start = Instant::now();
        let ours = TriangleSet::new(&positions, &indices);
        let our_build = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let theirs = Obvhs::new(&positions, &indices);
        let their_build = start.elapsed().as_secs_f64();
        let row = |label: &str,
                   build: f64,
                   closest: &(dyn Fn(&Ray) -> bool + Sync),
                   any: &(dyn Fn(&(Ray, f32)) -> bool + Sync)| {
            let c: Vec<f64> = [1, all_threads]
                .iter()
                .map(|&t| mrays(&rays.primary, t, closest))
                .collect();
            let a: Vec<f64> = [1, all_threads]
                .iter()
                .map(|&t| mrays(&rays.shadow, t, any))
                .collect();
            let tris = indices.len();
            println!(
                "| {name} ({tris} tris) | {label} | {build:.3} | {:.2} | {:.2} | {:.2} | {:.2} |",
                c[0], c[1], a[0], a[1]
            );
        };
        row(
            &format!("lightlab BVH4 ({} nodes)", ours.bvh().node_count()),
            our_build,
            &|r| ours.closest_hit(r, f32::INFINITY).is_some(),
            &|(r, t)| ours.any_hit(r, *t),
        );
        let packets: Vec<[Ray; PACKET]> = rays
            .primary
            .chunks_exact(PACKET)
            .map(|c| std::array::from_fn(|l| c[l]))
            .collect();
        let p: Vec<f64> = [1, all_threads]
            .iter()
            .map(|&t| packet_mrays(&ours, &packets, t))
            .collect();
        println!(
            "| {name} | lightlab BVH4, packets of {PACKET} (coherent) | | {:.2} | {:.2} | | |",
            p[0], p[1]
        );
        row(
            "obvhs CWBVH (medium_build)",
            their_build,
            &|r| theirs.closest(r).is_some(),
            &|(r, t)| theirs.occluded(r, *t),
        );
        let hit = rays
            .primary
            .par_iter()
            .filter(|r| ours.closest_hit(r, f32::INFINITY).is_some())
            .count();
        let blocked = rays
            .shadow
            .par_iter()
            .filter(|(r, t)| ours.any_hit(r, *t))
            .count();
        println!("|  | rays that hit | | primary: {hit} | | shadow: {blocked} | |");
        println!(
            "|  | lightlab memory | {:.1} bytes per triangle (tree and triangles) | | | | |",
            ours.bytes_per_triangle()
        );
        let (closest, shadow) = disagreements(&ours, &theirs, &rays);
        println!("|  | disagreements | | closest: {closest} rays | | any-hit: {shadow} rays | |");
    }
}
