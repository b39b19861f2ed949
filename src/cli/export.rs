//! `lightlab export SCENE -o scene.xml [--width W] [--height H] [--spp N] [--sampler S]
//! [--seed N]`: the scene as a Mitsuba 3 XML file, with its meshes and environment map
//! beside it (see [`crate::scene::export`]); the flags change the file's film size,
//! sample count and sampler as they change a render.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::args::SceneFileArgs;
use crate::render::RenderSettings;
use crate::sampling::SamplerKind;
use crate::scene::export::{check_output, export};
use crate::settings::RenderPatch;

/// Arguments of `export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// The scene: `builtin:NAME` (or a Mitsuba XML file, written back out).
    pub scene: String,
    #[command(flatten)]
    pub file: SceneFileArgs,
    /// The XML file to write; meshes (`NAME_meshK.ply`) and an environment map
    /// (`NAME_envmap.pfm`) go beside it.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Film width in the file (height follows the scene's aspect unless given).
    #[arg(long)]
    pub width: Option<u32>,
    /// Film height in the file (width follows the scene's aspect unless given).
    #[arg(long)]
    pub height: Option<u32>,
    /// Samples per pixel in the file.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Sampler the file asks for: independent, stratified, sobol (written as Mitsuba's
    /// `ldsampler`).
    #[arg(long)]
    pub sampler: Option<SamplerKind>,
    /// Seed the file's sampler asks for.
    #[arg(long)]
    pub seed: Option<u64>,
}

/// Runs `export`: writes the files, lists them, and prints what Mitsuba 3 would read
/// differently.
pub fn run(args: &ExportArgs) -> Result<(), CliError> {
    check_output(&args.output).map_err(|e| CliError::input(format!("-o {e}")))?;
    let mut scene = args.file.load(&args.scene)?;
    // The flags go through the render settings, so they are checked and the size keeps
    // the aspect as in a render; only what they set changes.
    let patch = RenderPatch {
        width: args.width,
        height: args.height,
        spp: args.spp,
        sampler: args.sampler,
        seed: args.seed,
        ..RenderPatch::default()
    };
    let settings = RenderSettings::build(&scene, &[&patch]).map_err(CliError::input)?;
    scene.camera = settings.camera(&scene);
    scene.spp = settings.spp;
    scene.requested = scene.requested.then(&RenderPatch {
        sampler: args.sampler,
        seed: args.seed,
        ..RenderPatch::default()
    });
    let exported = export(&scene, &args.output)
        .map_err(|e| CliError::input(format!("{}: cannot export: {e}", scene.name)))?;
    for path in &exported.files {
        println!("{}", path.display());
    }
    for note in &exported.notes {
        eprintln!("note: {note}");
    }
    Ok(())
}
