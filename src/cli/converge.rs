//! `lightlab converge SCENE --strategies A,B,C --max-spp N [--reference REF] -o DIR`.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::compare::reference_source;
use super::lab_args::LabRenderArgs;
use super::render::{STOP, install_stop_handler, step_bar};
use crate::lab::converge::{ConvergeConfig, run_converge};
use crate::lab::strategy::Strategy;

/// Arguments of `converge`.
#[derive(Args, Debug)]
pub struct ConvergeArgs {
    /// The scene: `builtin:NAME`.
    pub scene: String,
    /// Comma-separated strategies (as for `compare`).
    #[arg(long, required = true)]
    pub strategies: String,
    /// Largest samples per pixel (points at 1, 2, 4, ... up to it).
    #[arg(long, allow_negative_numbers = true)]
    pub max_spp: u32,
    /// Seeds per point (each point averages them; bars show their spread).
    #[arg(long, default_value_t = 4)]
    pub seeds: u32,
    /// Reference image; default: render one with the renderer's default strategy at
    /// --reference-spp.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Samples per pixel of a rendered reference (default: 16 × --max-spp).
    #[arg(long)]
    pub reference_spp: Option<u32>,
    #[command(flatten)]
    pub render: LabRenderArgs,
    /// Output folder.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// Runs `converge`.
pub fn run(args: &ConvergeArgs) -> Result<(), CliError> {
    let strategies = Strategy::parse_list(&args.strategies).map_err(CliError::input)?;
    // Checked here: the default --reference-spp derives from it and would take the blame.
    if args.max_spp == 0 || args.seeds == 0 {
        return Err(CliError::input(format!(
            "--max-spp {} --seeds {}: both must be at least 1",
            args.max_spp, args.seeds
        )));
    }
    let ref_spp = args
        .reference_spp
        .unwrap_or(args.max_spp.saturating_mul(16));
    let config = ConvergeConfig {
        scene: args.scene.clone(),
        reference: reference_source(&args.reference, ref_spp)?,
        strategies,
        max_spp: args.max_spp,
        seeds: args.seeds,
        base: args.render.base(),
        title: None,
    };
    install_stop_handler();
    let (bar, log) = step_bar(1 + config.strategies.len() as u64);
    let done = args
        .render
        .install(|| run_converge(&config, &args.output, &STOP, &log))?;
    bar.finish_and_clear();
    done.map_err(CliError::input)?;
    eprintln!("report: {}", args.output.join("index.html").display());
    Ok(())
}
