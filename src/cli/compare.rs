//! `lightlab compare SCENE --strategies A,B,C (--spp N | --time SECS) [--reference REF]
//! -o DIR`.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::lab_args::LabRenderArgs;
use super::render::{STOP, install_stop_handler, step_bar};
use crate::lab::budget::{Budget, time_budget};
use crate::lab::compare::{CompareConfig, run_compare};
use crate::lab::experiment::ReferenceSource;
use crate::lab::insets::Inset;
use crate::lab::strategy::Strategy;

/// Arguments of `compare`.
#[derive(Args, Debug)]
pub struct CompareArgs {
    /// The scene: `builtin:NAME`.
    pub scene: String,
    /// Comma-separated strategies: presets (`light`, `bsdf`, `default`, ...) or
    /// `LABEL:FLAGS` (`"area:--estimator light --light-sampling area"`).
    #[arg(long, required = true)]
    pub strategies: String,
    /// Equal samples per pixel.
    #[arg(long, conflicts_with = "time", allow_negative_numbers = true)]
    pub spp: Option<u32>,
    /// Equal wall-clock time per strategy, in seconds.
    #[arg(long, allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Reference image (EXR from `lightlab reference`); default: render one with the
    /// renderer's default strategy (`lightlab render` without strategy flags) at
    /// --reference-spp.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Samples per pixel of a rendered reference.
    #[arg(long, default_value_t = 1024, allow_negative_numbers = true)]
    pub reference_spp: u32,
    /// Inset rectangle `x,y,w,h` (repeatable); default: two high-error regions.
    #[arg(long)]
    pub inset: Vec<Inset>,
    #[command(flatten)]
    pub render: LabRenderArgs,
    /// Output folder.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// The budget from `--spp` / `--time`.
pub fn budget(spp: Option<u32>, time: Option<f64>) -> Result<Budget, CliError> {
    match (spp, time) {
        (Some(0), _) => Err(CliError::input("--spp must be at least 1")),
        (Some(n), None) => Ok(Budget::Spp(n)),
        (None, Some(t)) => time_flag(t).map(Budget::Time),
        _ => Err(CliError::input("give --spp N or --time SECS")),
    }
}

/// The value of `--time SECS` as a duration, or an input error naming the flag.
pub fn time_flag(seconds: f64) -> Result<std::time::Duration, CliError> {
    time_budget(seconds).map_err(|e| CliError::input(format!("--time {e}")))
}

/// The reference source: the file, or the renderer's default strategy at `spp`.
pub fn reference_source(file: &Option<PathBuf>, spp: u32) -> Result<ReferenceSource, CliError> {
    if spp == 0 {
        return Err(CliError::input("--reference-spp must be at least 1"));
    }
    Ok(match file {
        Some(p) => ReferenceSource::File(p.clone()),
        None => ReferenceSource::Render {
            strategy: Strategy::new("default", Default::default()),
            spp,
        },
    })
}

/// Runs `compare`.
pub fn run(args: &CompareArgs) -> Result<(), CliError> {
    let strategies = Strategy::parse_list(&args.strategies).map_err(CliError::input)?;
    let config = CompareConfig {
        scene: args.scene.clone(),
        reference: reference_source(&args.reference, args.reference_spp)?,
        strategies,
        budget: budget(args.spp, args.time)?,
        base: args.render.base(),
        insets: args.inset.clone(),
        title: None,
        notes: vec![],
        links: vec![],
    };
    install_stop_handler();
    let (bar, log) = step_bar(1 + config.strategies.len() as u64);
    let results = args
        .render
        .install(|| run_compare(&config, &args.output, &STOP, &log))?;
    bar.finish_and_clear();
    let results = results.map_err(CliError::input)?;
    print!(
        "{}",
        crate::lab::compare::results_table(&results).markdown()
    );
    eprintln!("report: {}", args.output.join("index.html").display());
    Ok(())
}
