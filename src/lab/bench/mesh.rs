//! BVH figures on the procedural bumpy-sphere mesh (the same mesh and rays as
//! `examples/bvh_compare.rs` and `benches/embree_compare.py`, so the figures compare).

use rayon::prelude::*;

use super::{Figure, median_rate};
use crate::geometry::TriangleSet;
use crate::geometry::bvh::bench_mesh::{bench_mesh, bench_rays};

/// Most triangles of the benchmark mesh: ~100 bytes each with its BVH, so 2 GB.
pub const MAX_BENCH_TRIANGLES: usize = 20_000_000;

/// Most rays of each kind (~50 bytes each).
pub const MAX_BENCH_RAYS: usize = 1 << 26;

/// Build time, closest-hit and any-hit throughput on a mesh of about `triangles`
/// triangles with `rays` rays of each kind, each the median of `runs` runs.
pub fn mesh_figures(triangles: usize, rays: usize, runs: usize) -> Vec<Figure> {
    let (positions, indices) = bench_mesh(triangles);
    let on = format!("bumpy sphere, {} triangles", indices.len());
    let mut set = None;
    let (build, build_range) = median_rate(
        runs,
        || set = Some(TriangleSet::new(&positions, &indices)),
        |s| s,
    );
    let set = set.expect("at least one run");
    let rays = bench_rays(rays, 1);
    let n = rays.primary.len() as f64;
    let (closest, closest_range) = median_rate(
        runs,
        || {
            let hits: usize = rays
                .primary
                .par_chunks(4096)
                .map(|c| {
                    c.iter()
                        .filter(|r| set.closest_hit(r, f32::INFINITY).is_some())
                        .count()
                })
                .sum();
            std::hint::black_box(hits);
        },
        |s| n / s / 1e6,
    );
    let m = rays.shadow.len() as f64;
    let (any, any_range) = median_rate(
        runs,
        || {
            let hits: usize = rays
                .shadow
                .par_chunks(4096)
                .map(|c| c.iter().filter(|(r, t)| set.any_hit(r, *t)).count())
                .sum();
            std::hint::black_box(hits);
        },
        |s| m / s / 1e6,
    );
    vec![
        Figure {
            what: "BVH build (binned SAH, 4-wide)".into(),
            on: on.clone(),
            median: build,
            range: build_range,
            unit: "s",
        },
        Figure {
            what: "closest-hit rays (random origins)".into(),
            on: on.clone(),
            median: closest,
            range: closest_range,
            unit: "Mrays/s",
        },
        Figure {
            what: "any-hit shadow rays (random)".into(),
            on,
            median: any,
            range: any_range,
            unit: "Mrays/s",
        },
    ]
}
