//! `lightlab export SCENE -o scene.xml [--width W] [--height H] [--spp N] [--sampler S]
//! [--seed N]`: the scene as a Mitsuba 3 XML file, with its meshes and environment map
//! beside it (see [`crate::scene::export`]); the flags change the file's film size,
//! sample count and sampler as they change a render.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::args::{ExportPatchArgs, SceneFileArgs};
use crate::render::RenderSettings;
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
    /// The film size, samples, sampler (`sobol` is written as Mitsuba's `ldsampler`)
    /// and seed the file asks for, as the render flags of the same names.
    #[command(flatten)]
    pub settings: ExportPatchArgs,
}

/// Runs `export`: writes the files, lists them, and prints what Mitsuba 3 would read
/// differently.
pub fn run(args: &ExportArgs) -> Result<(), CliError> {
    check_output(&args.output).map_err(|e| CliError::input(format!("-o {e}")))?;
    let mut scene = args.file.load(&args.scene)?;
    // The flags go through the render settings, so they are checked and the size keeps
    // the aspect as in a render; only what they set changes.
    let patch = &args.settings.0;
    let settings = RenderSettings::build(&scene, &[patch]).map_err(CliError::input)?;
    scene.camera = settings.camera(&scene);
    scene.spp = settings.spp;
    scene.requested = scene.requested.then(&RenderPatch {
        sampler: patch.sampler,
        seed: patch.seed,
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
