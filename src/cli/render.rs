//! `lightlab render [SCENE] [flags] -o out.{png,exr,pfm}`.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use super::{CliError, StrategyArgs};
use crate::image::Film;
use crate::image::io::write_film;
use crate::image::tev::TevDisplay;
use crate::render::{Control, render};
use crate::scene::{self, builtin::DEFAULT_SCENE};

/// Arguments of `render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A scene: a Mitsuba XML file or `builtin:NAME` (see `lightlab scenes`). Default:
    /// builtin:assignment.
    pub scene: Option<String>,
    /// Set a scene file parameter: `-D spp=64` replaces `<default name="spp" .../>`.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = super::args::parse_define)]
    pub define: Vec<(String, String)>,
    #[command(flatten)]
    pub strategy: StrategyArgs,
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

/// Runs `render`.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let spec = args.scene.as_deref().unwrap_or(DEFAULT_SCENE);
    let scene = scene::load_with(spec, &args.define).map_err(CliError::input)?;
    let settings = args.strategy.settings(&scene)?;
    let pool = super::args::thread_pool(args.threads)?;
    install_stop_handler();
    let camera = settings.camera(&scene);
    let (first, last) = settings.pass.sample_range(settings.spp);
    let bar = progress_bar((last - first) as u64 * (camera.width * camera.height) as u64);
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
    let out = pool.install(|| {
        render(
            &scene,
            &settings,
            &Control {
                progress: &progress,
                stop: &STOP,
                frame: Some(&frame),
            },
        )
    });
    bar.finish_and_clear();
    if let Some(d) = display {
        d.finish(&scene.name, &out.film);
    }
    write_film(&out.film, &args.output, args.exposure).map_err(CliError::failure)?;
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
        settings.patch(),
        args.output.display()
    );
    if out.invalid_samples > 0 {
        eprintln!(
            "warning: {} samples were not finite and were scored as zero",
            out.invalid_samples
        );
    }
    if out.stopped {
        eprintln!(
            "stopped early: the image holds {} of {} spp",
            out.spp,
            last - first
        );
    }
    Ok(())
}
