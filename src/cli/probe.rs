//! `lightlab probe [SCENE] --pixel X,Y [strategy flags] [--spp N] -o DIR`: where one
//! pixel's samples go (`probe.json`, `probe.png`).

use std::path::PathBuf;

use clap::Args;

use super::args::SceneFileArgs;
use super::{CliError, StrategyArgs};
use crate::lab::probe::{probe, write_probe};
use crate::math::spectrum::luminance;
use crate::scene::builtin::DEFAULT_SCENE;

/// Arguments of `probe`.
#[derive(Args, Debug)]
pub struct ProbeArgs {
    /// A scene: a Mitsuba XML file or `builtin:NAME`. Default: builtin:assignment.
    pub scene: Option<String>,
    #[command(flatten)]
    pub file: SceneFileArgs,
    /// The pixel whose shading point is probed, `X,Y` (x right, y down, from 0).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pub pixel: (u32, u32),
    #[command(flatten)]
    pub strategy: StrategyArgs,
    /// Output folder (created if missing): probe.json and probe.png.
    #[arg(short, long, default_value = "probe")]
    pub output: PathBuf,
}

/// Parses `X,Y`.
fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let err = || format!("expected X,Y (two whole numbers), not \"{s}\"");
    let (x, y) = s.split_once(',').ok_or_else(err)?;
    Ok((
        x.trim().parse().map_err(|_| err())?,
        y.trim().parse().map_err(|_| err())?,
    ))
}

/// Runs `probe`.
pub fn run(args: &ProbeArgs) -> Result<(), CliError> {
    let spec = args.scene.as_deref().unwrap_or(DEFAULT_SCENE);
    let scene = args.file.load(spec)?;
    let settings = args.strategy.settings(&scene)?;
    let report = probe(&scene, &settings, args.pixel).map_err(CliError::input)?;
    std::fs::create_dir_all(&args.output).map_err(|e| {
        CliError::input(format!("-o {}: cannot create: {e}", args.output.display()))
    })?;
    let flags = settings.patch().to_string();
    write_probe(&report, &scene.name, &flags, &args.output).map_err(CliError::failure)?;
    let drawn = report.samples.iter().filter(|s| s.w_in.is_some()).count();
    eprintln!(
        "{} pixel ({}, {}): estimate {:.5} ± {:.5} (luminance) from {} samples, {} directions drawn, {} -> {}",
        scene.name,
        args.pixel.0,
        args.pixel.1,
        luminance(report.estimate),
        luminance(report.std_error),
        report.spp,
        drawn,
        flags,
        args.output.display()
    );
    Ok(())
}
