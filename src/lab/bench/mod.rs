//! Throughput figures for `lightlab bench`: rays per second on a built-in scene and on a
//! large procedural mesh, BVH build time, and samples per second per estimator. Every
//! figure is the median of several runs (machines are shared and noisy); ratios against
//! peers (Embree, Mitsuba 3) come from scripts under `benches/` run on the same machine.

mod mesh;
mod scene;

pub use mesh::{MAX_BENCH_RAYS, MAX_BENCH_TRIANGLES, mesh_figures};
pub use scene::{estimator_figures, scene_ray_figures};

use std::time::Instant;

/// One measured figure: what, on what, the median and the spread of the runs.
#[derive(Clone, Debug)]
pub struct Figure {
    /// What is measured, e.g. "closest-hit rays".
    pub what: String,
    /// On what, e.g. "builtin:assignment" or "bumpy sphere, 1000000 triangles".
    pub on: String,
    /// Median of the runs.
    pub median: f64,
    /// Smallest and largest run.
    pub range: (f64, f64),
    /// Unit of `median`, e.g. "Mrays/s".
    pub unit: &'static str,
}

impl Figure {
    /// A markdown table row.
    pub fn row(&self) -> String {
        format!(
            "| {} | {} | {:.3} {} | {:.3} – {:.3} |",
            self.what, self.on, self.median, self.unit, self.range.0, self.range.1
        )
    }
}

/// Header of the markdown table [`Figure::row`] fills.
pub const TABLE_HEADER: &str = "| measure | on | median | range of runs |\n|---|---|---|---|";

/// Runs `f` `runs` times; returns the median, min and max of `rate(seconds)`.
pub(crate) fn median_rate(
    runs: usize,
    mut f: impl FnMut(),
    rate: impl Fn(f64) -> f64,
) -> (f64, (f64, f64)) {
    let mut v: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            rate(start.elapsed().as_secs_f64())
        })
        .collect();
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], (v[0], v[v.len() - 1]))
}
