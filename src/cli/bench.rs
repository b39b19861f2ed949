//! `lightlab bench`: throughput figures (rays/s, BVH build, samples/s per estimator) as a
//! markdown table, medians of several runs. Peers (Embree, Mitsuba 3) are measured by the
//! scripts in `benches/` on the same machine.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::integrator::EstimatorKind;
use crate::lab::bench::{
    Figure, MAX_BENCH_RAYS, MAX_BENCH_TRIANGLES, TABLE_HEADER, estimator_figures, mesh_figures,
    scene_ray_figures,
};
use crate::render::RenderSettings;
use crate::scene;

/// Arguments of `bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Runs per figure; the table shows the median and the range.
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Triangles of the procedural mesh for the BVH figures (0 skips them).
    #[arg(long, default_value_t = 1_000_000)]
    pub triangles: usize,
    /// Rays of each kind traced on the mesh.
    #[arg(long, default_value_t = 1 << 20)]
    pub rays: usize,
    /// Scenes for the ray and estimator figures.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "builtin:assignment,builtin:veach-mis"
    )]
    pub scenes: Vec<String>,
    /// Samples per pixel of the estimator figures.
    #[arg(long, default_value_t = 16)]
    pub spp: u32,
    /// Also write the table to this markdown file.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Runs `bench`.
pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    if args.runs == 0 || args.spp == 0 {
        return Err(CliError::input("--runs and --spp must be at least 1"));
    }
    // Caps before allocating: the mesh and the rays are generated in memory.
    for (flag, value, max) in [
        ("--triangles", args.triangles, MAX_BENCH_TRIANGLES),
        ("--rays", args.rays, MAX_BENCH_RAYS),
    ] {
        if value > max {
            return Err(CliError::input(format!(
                "{flag} {value} is out of range (at most {max})"
            )));
        }
    }
    let pool = super::args::thread_pool(args.threads)?;
    let scenes = pool.install(|| {
        args.scenes
            .iter()
            .map(|s| scene::load(s).map_err(|e| CliError::input(e.to_string())))
            .collect::<Result<Vec<_>, _>>()
    })?;
    let mut table = format!(
        "lightlab {} bench, {} threads, median of {} runs\n\n{TABLE_HEADER}\n",
        env!("CARGO_PKG_VERSION"),
        pool.current_num_threads(),
        args.runs
    );
    print!("{table}");
    let mut emit = |figures: Vec<Figure>| {
        for f in figures {
            let row = f.row();
            println!("{row}");
            table.push_str(&row);
            table.push('\n');
        }
    };
    pool.install(|| {
        for s in &scenes {
            emit(scene_ray_figures(s, 4, args.runs));
            let mut base = RenderSettings::for_scene(s);
            base.spp = args.spp;
            let unbiased: Vec<_> = EstimatorKind::unbiased().collect();
            emit(estimator_figures(s, &base, &unbiased, args.runs));
        }
        if args.triangles > 0 {
            emit(mesh_figures(args.triangles, args.rays, args.runs));
        }
    });
    if let Some(path) = &args.output {
        std::fs::write(path, &table)
            .map_err(|e| CliError::failure(format!("writing {}: {e}", path.display())))?;
    }
    Ok(())
}
