//! `lightlab render [SCENE] [flags] -o out.{png,exr,pfm}`.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use super::args::SceneFileArgs;
use super::{CliError, StrategyArgs};
use crate::image::Film;
use crate::image::io::write_film_with_metadata;
use crate::image::output::check_output;
use crate::image::tev::TevDisplay;
use crate::lab::budget::{Budget, render_budget};
use crate::lab::merge::provenance;
use crate::render::{Control, RenderSettings};
use crate::scene::builtin::DEFAULT_SCENE;

/// Arguments of `render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A scene: a Mitsuba XML file or `builtin:NAME` (see `lightlab scenes`). Default:
    /// builtin:assignment.
    pub scene: Option<String>,
    #[command(flatten)]
    pub file: SceneFileArgs,
    #[command(flatten)]
    pub strategy: StrategyArgs,
    /// Render for SECS seconds of wall-clock time instead of a number of samples: rounds
    /// of whole images until the budget (within about 10 %), merged.
    #[arg(long, value_name = "SECS", allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Worker threads (default: all cores). The image is the same for any count.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Show the image in a running tev viewer (`HOST:PORT`, tev's default is
    /// 127.0.0.1:14158) after every round.
    #[arg(long, value_name = "HOST:PORT")]
    pub display_server: Option<String>,
    /// PNG exposure in stops (the image is scaled by 2^exposure).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Output file: .png (sRGB), .exr (float RGB + variance), .pfm.
    #[arg(short, long, default_value = "render.png")]
    pub output: PathBuf,
}

/// Set by Ctrl-C: renders stop after their current round and write what they have.
pub static STOP: AtomicBool = AtomicBool::new(false);

/// Installs the Ctrl-C handler once (later calls are harmless).
pub fn install_stop_handler() {
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::Relaxed) {
            std::process::exit(130); // a second Ctrl-C stops at once
        }
        eprintln!("\nstopping after the current round (Ctrl-C again to quit now)");
    });
}

/// A progress bar on stderr with an ETA; draws nothing when stderr is not a terminal.
pub fn progress_bar(total: u64) -> ProgressBar {
    let bar = ProgressBar::new(total);
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}",
    ) {
        bar.set_style(style);
    }
    bar
}

/// The flags that describe the render: the settings' own, with `--time SECS` in place
/// of the nominal `--spp` when time was the budget.
fn summary_flags(settings: &RenderSettings, time: Option<f64>) -> String {
    let mut patch = settings.patch();
    match time {
        Some(t) => {
            patch.spp = None;
            format!("{patch} --time {t}")
        }
        None => patch.to_string(),
    }
}

/// A bar over the `steps` renders of a lab experiment (a reference, each strategy), with
/// an ETA, and the experiment's log: each line prints above the bar and counts one step.
pub fn step_bar(steps: u64) -> (ProgressBar, impl Fn(&str)) {
    let bar = ProgressBar::new(steps.max(1));
    if let Ok(style) = ProgressStyle::with_template(
        "{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} renders, ETA {eta}",
    ) {
        bar.set_style(style);
    }
    bar.enable_steady_tick(std::time::Duration::from_millis(250));
    let shown = bar.clone();
    let log = move |line: &str| {
        shown.suspend(|| eprintln!("{line}"));
        shown.inc(1);
    };
    (bar, log)
}

/// Runs `render`.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    // Refused before the render, not after it.
    check_output(&args.output, &["exr", "png", "pfm"])
        .map_err(|e| CliError::input(format!("-o {}", e)))?;
    if !args.exposure.is_finite() {
        return Err(CliError::input(format!(
            "--exposure {}: must be a finite number of stops",
            args.exposure
        )));
    }
    let spec = args.scene.as_deref().unwrap_or(DEFAULT_SCENE);
    // `--threads` bounds the load too (BVH builds and material tables run in parallel).
    let pool = super::args::thread_pool(args.threads)?;
    let scene = pool.install(|| args.file.load(spec))?;
    let settings = args.strategy.settings(&scene)?;
    let budget = match args.time {
        None => Budget::Spp(settings.spp),
        Some(_) if args.strategy.0.spp.is_some() => {
            return Err(CliError::input("give --spp N or --time SECS, not both"));
        }
        Some(_) if settings.pass.count > 1 => {
            return Err(CliError::input(
                "--pass splits a number of samples; it cannot split --time",
            ));
        }
        Some(t) => super::compare::budget(None, Some(t))?,
    };
    install_stop_handler();
    let camera = settings.camera(&scene);
    let (first, last) = settings.pass.sample_range(settings.spp);
    let bar = progress_bar(match budget {
        Budget::Spp(_) => (last - first) as u64 * (camera.width * camera.height) as u64,
        Budget::Time(t) => u64::try_from(t.as_millis()).unwrap_or(u64::MAX),
    });
    let progress = |done: u64, _total: u64| bar.set_position(done);
    let display = args
        .display_server
        .as_deref()
        .and_then(|a| TevDisplay::connect(a, &scene.name, camera.width, camera.height));
    let frame = |film: &Film| {
        if let Some(d) = &display {
            d.send(&scene.name, film);
        }
    };
    // Frames only for a live view: a render without one may take fewer, longer rounds.
    let control = Control {
        progress: &progress,
        stop: &STOP,
        frame: display
            .is_some()
            .then_some(&frame as &(dyn Fn(&Film) + Sync)),
    };
    let out = pool.install(|| render_budget(&scene, &settings, budget, &control));
    bar.finish_and_clear();
    if let Some(d) = display {
        d.finish(&scene.name, &out.film);
    }
    // An interrupted render still writes its whole rounds, and says so in an EXR header.
    let partial = format!("stopped by Ctrl-C at {} of {} spp", out.spp, last - first);
    let mut metadata = provenance(&scene, &settings, &out);
    if out.stopped {
        metadata.push(("lightlab.partial".to_string(), partial.clone()));
    }
    // On the render's pool: the EXR writer compresses its blocks in parallel.
    pool.install(|| write_film_with_metadata(&out.film, &args.output, args.exposure, &metadata))
        .map_err(CliError::failure)?;
    let samples = out.spp as f64 * (camera.width * camera.height) as f64;
    eprintln!(
        "{}: {}x{} at {} spp{} in {:.2} s ({:.2} Msamples/s), {} -> {}",
        scene.name,
        camera.width,
        camera.height,
        out.spp,
        if settings.pass.count > 1 {
            format!(" (pass {})", settings.pass)
        } else {
            String::new()
        },
        out.time.as_secs_f64(),
        samples / out.time.as_secs_f64().max(1e-9) / 1e6,
        summary_flags(&settings, args.time),
        args.output.display()
    );
    eprintln!("{}", settings.lights_summary(&scene));
    if out.invalid_samples > 0 {
        eprintln!(
            "warning: {} samples were not finite and were scored as zero",
            out.invalid_samples
        );
    }
    if out.stopped {
        return Err(CliError::interrupted(format!(
            "{partial}: {} holds the partial image",
            args.output.display()
        )));
    }
    Ok(())
}
