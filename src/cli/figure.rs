//! `lightlab figure NAME -o DIR`: one of the lecture's comparisons; `--list` names them.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::lab_args::LabRenderArgs;
use super::render::{STOP, install_stop_handler, step_bar};
use crate::lab::compare::CompareConfig;
use crate::lab::figure::{FIGURES, FigureOptions, find, plan, run_figure};

/// Arguments of `figure`.
#[derive(Args, Debug)]
pub struct FigureArgs {
    /// The figure (see --list).
    pub name: Option<String>,
    /// List the figures, saying which this build can make.
    #[arg(long)]
    pub list: bool,
    /// Override the figure's equal spp.
    #[arg(long, conflicts_with = "time")]
    pub spp: Option<u32>,
    /// Equal wall-clock time per strategy, in seconds, instead of the figure's equal spp
    /// (the references keep their spp).
    #[arg(long, allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Override the reference spp.
    #[arg(long)]
    pub reference_spp: Option<u32>,
    /// Also plot relMSE against spp and time up to this spp (4 seeds per point).
    #[arg(long)]
    pub converge: Option<u32>,
    #[command(flatten)]
    pub render: LabRenderArgs,
    /// Output folder.
    #[arg(short, long, default_value = "figure")]
    pub output: PathBuf,
}

/// Runs `figure`.
pub fn run(args: &FigureArgs) -> Result<(), CliError> {
    let options = FigureOptions {
        base: args.render.base(),
        spp: args.spp,
        time: args.time.map(super::compare::time_flag).transpose()?,
        reference_spp: args.reference_spp,
        converge: args.converge,
    };
    if [args.spp, args.reference_spp, args.converge].contains(&Some(0)) {
        return Err(CliError::input(
            "--spp, --reference-spp and --converge must be at least 1",
        ));
    }
    if args.list {
        let width = FIGURES.iter().map(|f| f.name.len()).max().unwrap_or(0);
        for f in FIGURES {
            println!("{:width$} {}", f.name, f.description);
        }
        return Ok(());
    }
    let name = args
        .name
        .as_deref()
        .ok_or_else(|| CliError::input("give a figure name, or --list to see them"))?;
    let figure = find(name).map_err(CliError::input)?;
    install_stop_handler();
    // One step per reference and per strategy of every panel (twice with --converge).
    let per_panel = |c: &CompareConfig| 1 + c.strategies.len() as u64;
    let steps: u64 = plan(figure, &options)
        .map_err(CliError::input)?
        .iter()
        .map(per_panel)
        .sum();
    let (bar, log) = step_bar(steps * if args.converge.is_some() { 2 } else { 1 });
    let panels = args
        .render
        .install(|| run_figure(figure, &options, &args.output, &STOP, &log))?;
    bar.finish_and_clear();
    let panels = panels.map_err(CliError::input)?;
    for (panel, results) in &panels {
        println!("## {panel}");
        print!("{}", crate::lab::compare::results_table(results).markdown());
    }
    eprintln!("report: {}", args.output.join("index.html").display());
    Ok(())
}
