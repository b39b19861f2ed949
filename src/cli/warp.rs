//! `lightlab warp NAME`: draws a warp's samples beside its observed and expected
//! histograms and prints its chi-square result; `lightlab warp --list` names them all.

use std::path::PathBuf;

use crate::lab::warp_plot::warp_plot;
use crate::sampling::chi2::{Chi2Config, chi2_test};
use crate::sampling::registry;

/// Arguments of `lightlab warp`.
#[derive(clap::Args, Debug)]
pub struct WarpArgs {
    /// The warp or distribution to show (see --list).
    pub name: Option<String>,
    /// Number of samples in the chi-square test.
    #[arg(long, default_value_t = 1_000_000)]
    pub n: usize,
    /// Seed of the sample stream.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output PNG.
    #[arg(short = 'o', long = "output", default_value = "warp.png")]
    pub output: PathBuf,
    /// Print every warp and distribution, one per line: name, then a description.
    #[arg(long)]
    pub list: bool,
}

/// Runs the subcommand: lists the registry, or tests and plots one entry.
pub fn run(args: &WarpArgs) -> Result<(), String> {
    if args.list {
        for entry in registry::all() {
            println!("{:32} {}", entry.name, entry.description);
        }
        return Ok(());
    }
    let name = args
        .name
        .as_deref()
        .ok_or("give a warp name, or --list to see them")?;
    if args.n == 0 {
        return Err("--n must be at least 1".into());
    }
    let entry = registry::find(name)?;
    let mut config = Chi2Config::new(&entry.domain, args.n, args.seed);
    if let Some(resolution) = entry.resolution {
        config.resolution = resolution;
    }
    let report = chi2_test(
        &entry.domain,
        &mut |rng| entry.sample(rng),
        &*entry.pdf,
        &config,
    );
    println!("{}: {}", entry.name, entry.description);
    println!(
        "samples: {}, cells: {} x {}",
        args.n, config.resolution[0], config.resolution[1]
    );
    println!("chi2: {:.2}, dof: {}", report.statistic, report.dof);
    if let Some(failure) = &report.failure {
        println!("failure: {failure}");
    }
    println!("p-value: {}", report.p_value);
    let image = warp_plot(&entry, &report, args.seed);
    image
        .save(&args.output)
        .map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    println!("wrote {}", args.output.display());
    Ok(())
}
