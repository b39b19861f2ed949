//! The command line: parses arguments and calls the library, one file per subcommand.

mod args;
mod bench;
mod compare;
mod converge;
mod diff;
mod export;
mod figure;
mod lab_args;
mod merge;
mod probe;
mod reference;
mod render;
mod scenes;
pub mod warp;

use clap::{Parser, Subcommand};

pub use args::StrategyArgs;

/// An error the CLI prints before exiting with `code`.
#[derive(Debug)]
pub struct CliError {
    /// What went wrong (already located: file, line, element).
    pub message: String,
    /// Exit code: 2 for bad input, 1 for failures while working.
    pub code: i32,
}

impl CliError {
    /// Bad input (exit code 2).
    pub fn input(message: impl ToString) -> CliError {
        CliError {
            message: message.to_string(),
            code: 2,
        }
    }
    /// A failure while working (exit code 1).
    pub fn failure(message: impl ToString) -> CliError {
        CliError {
            message: message.to_string(),
            code: 1,
        }
    }
    /// Stopped by Ctrl-C after writing what was done (exit code 130 = 128 + SIGINT, as
    /// shells report a process that SIGINT ended).
    pub fn interrupted(message: impl ToString) -> CliError {
        CliError {
            message: message.to_string(),
            code: 130,
        }
    }
}

#[derive(Parser, Debug)]
#[command(
    name = "lightlab",
    version,
    about = "A renderer and laboratory for Monte Carlo direct illumination and importance sampling"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a scene (default: the built-in `assignment` scene) to .png, .exr or .pfm.
    Render(render::RenderArgs),
    /// Compare an image with a reference: MSE, relMSE, bias, NaN/Inf counts.
    Diff(diff::DiffArgs),
    /// List the built-in scenes.
    Scenes,
    /// Write a scene (a built-in one) as a Mitsuba 3 XML file, meshes and map beside it.
    Export(export::ExportArgs),
    /// Draw a named warp's samples beside its histograms and run its chi-square test.
    Warp(warp::WarpArgs),
    /// Render a reference progressively until an error target or a budget (EXR).
    Reference(reference::ReferenceArgs),
    /// Compare strategies at equal spp or equal time; writes an HTML report.
    Compare(compare::CompareArgs),
    /// Error against spp and time on log-log axes, with fitted slopes.
    Converge(converge::ConvergeArgs),
    /// Merge the EXR parts of a `--pass I/N` render (sample-weighted, variance kept).
    Merge(merge::MergeArgs),
    /// Where one pixel's samples go: every direction the estimator draws at the surface
    /// seen through a pixel, with density, MIS weight and contribution (JSON and PNG).
    Probe(probe::ProbeArgs),
    /// Reproduce one of the lecture's comparisons (`--list` names them).
    Figure(figure::FigureArgs),
    /// Throughput figures: rays/s, BVH build time, samples/s per estimator (medians).
    Bench(bench::BenchArgs),
}

/// Runs the CLI on the process arguments and returns the exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    let result = match cli.command {
        Command::Render(a) => render::run(&a),
        Command::Diff(a) => diff::run(&a),
        Command::Scenes => scenes::run(),
        Command::Export(a) => export::run(&a),
        Command::Warp(a) => warp::run(&a).map_err(CliError::input),
        Command::Reference(a) => reference::run(&a),
        Command::Compare(a) => compare::run(&a),
        Command::Converge(a) => converge::run(&a),
        Command::Merge(a) => merge::run(&a),
        Command::Probe(a) => probe::run(&a),
        Command::Figure(a) => figure::run(&a),
        Command::Bench(a) => bench::run(&a),
    };
    match result {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {}", e.message);
            e.code
        }
    }
}
