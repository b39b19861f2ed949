//! `lightlab reference SCENE [strategy flags] [--rel-error E] [--spp N] [--time SECS]
//! -o ref.exr`: progressive passes until the error target or a budget; the EXR header
//! records spp, time, settings, the error estimate and the command.

use std::path::PathBuf;
use std::time::Duration;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use super::args::SceneFileArgs;
use super::render::{STOP, install_stop_handler};
use super::{CliError, StrategyArgs};
use crate::image::io::write_film_with_metadata;
use crate::image::output::check_output;
use crate::lab::merge::provenance;
use crate::lab::reference::{ReferenceTarget, render_reference};
use crate::lab::report::{VERSION, command_line};

/// Arguments of `reference`.
#[derive(Args, Debug)]
pub struct ReferenceArgs {
    /// The scene: `builtin:NAME`.
    pub scene: String,
    #[command(flatten)]
    pub file: SceneFileArgs,
    #[command(flatten)]
    pub strategy: StrategyArgs,
    /// Stop when the relative standard error of the image mean and of 90% of the pixels
    /// is below this (e.g. 0.01).
    #[arg(long, allow_negative_numbers = true)]
    pub rel_error: Option<f64>,
    /// Time budget in seconds.
    #[arg(long, allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Output EXR.
    #[arg(short, long, default_value = "reference.exr")]
    pub output: PathBuf,
}

/// Runs `reference`.
pub fn run(args: &ReferenceArgs) -> Result<(), CliError> {
    if args.strategy.0.pass.is_some() {
        return Err(CliError::input(
            "reference renders whole images; --pass does not apply",
        ));
    }
    check_output(&args.output, &["exr"]).map_err(|e| {
        CliError::input(format!(
            "-o {e}; the reference must be an .exr file (it keeps variance and metadata)"
        ))
    })?;
    let target = ReferenceTarget {
        rel_error: args.rel_error,
        max_spp: args.strategy.0.spp,
        max_time: match args.time {
            Some(t) => Some(super::compare::time_flag(t)?),
            None => None,
        },
    };
    match target.rel_error {
        Some(e) if !(e.is_finite() && e > 0.0) => {
            return Err(CliError::input(format!(
                "--rel-error must be positive, not {e}"
            )));
        }
        None if target.max_spp.is_none() && target.max_time.is_none() => {
            return Err(CliError::input("give --rel-error, --spp or --time"));
        }
        _ => {}
    }
    // `--threads` bounds the load too (BVH builds and material tables run in parallel).
    let pool = super::args::thread_pool(args.threads)?;
    let scene = pool.install(|| args.file.load(&args.scene))?;
    let settings = args.strategy.settings(&scene)?;
    install_stop_handler();
    let bar = ProgressBar::new_spinner();
    if let Ok(style) = ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}") {
        bar.set_style(style);
    }
    bar.enable_steady_tick(Duration::from_millis(200));
    let progress = |spp: u32, e: &crate::lab::reference::ErrorEstimate| {
        bar.set_message(format!(
            "{spp} spp, relative error {:.2e} (mean), {:.2e} (90% of pixels)",
            e.mean_rel_error, e.pixel_rel_error
        ))
    };
    let r = pool.install(|| render_reference(&scene, &settings, &target, &STOP, &progress));
    bar.finish_and_clear();
    let out = &r.output;
    let final_settings = crate::render::RenderSettings {
        spp: out.spp,
        ..settings.clone()
    };
    let partial = format!("stopped by Ctrl-C at {} spp", out.spp);
    // Scene, content hash, settings and sample blocks (so references merge like
    // passes), then how the reference was made.
    let mut metadata = provenance(&scene, &final_settings, out);
    metadata.extend(
        [
            ("lightlab.version", VERSION.to_string()),
            ("lightlab.command", command_line()),
            ("lightlab.flags", final_settings.patch().to_string()),
            ("lightlab.time_s", format!("{:.3}", out.time.as_secs_f64())),
            ("lightlab.passes", r.passes.to_string()),
            (
                "lightlab.rel_error_mean",
                format!("{:.4e}", r.error.mean_rel_error),
            ),
            (
                "lightlab.rel_error_pixel_q90",
                format!("{:.4e}", r.error.pixel_rel_error),
            ),
            ("lightlab.converged", r.converged.to_string()),
            ("lightlab.invalid_samples", out.invalid_samples.to_string()),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v)),
    );
    if out.stopped {
        metadata.push(("lightlab.partial".into(), partial.clone()));
    }
    pool.install(|| write_film_with_metadata(&out.film, &args.output, 0.0, &metadata))
        .map_err(CliError::failure)?;
    eprintln!(
        "{}: {} spp in {} passes, {:.2} s; relative error {:.2e} (image mean), {:.2e} (90% of pixels){} -> {}",
        scene.name,
        out.spp,
        r.passes,
        out.time.as_secs_f64(),
        r.error.mean_rel_error,
        r.error.pixel_rel_error,
        match (args.rel_error, r.converged) {
            (Some(_), true) => ", target met",
            (Some(_), false) if out.stopped => ", target NOT met (stopped by Ctrl-C)",
            (Some(_), false) => ", target NOT met (budget ran out)",
            _ => "",
        },
        args.output.display()
    );
    if out.stopped {
        return Err(CliError::interrupted(format!(
            "{partial}: {} holds the partial reference",
            args.output.display()
        )));
    }
    Ok(())
}
