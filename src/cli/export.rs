//! `lightlab export SCENE -o scene.xml`: the scene as a Mitsuba 3 XML file, with its
//! meshes and environment map beside it (see [`crate::scene::export`]).

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::args::SceneFileArgs;
use crate::scene::export::{check_output, export};

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
}

/// Runs `export`: writes the files, lists them, and prints what Mitsuba 3 would read
/// differently.
pub fn run(args: &ExportArgs) -> Result<(), CliError> {
    check_output(&args.output).map_err(|e| CliError::input(format!("-o {e}")))?;
    let scene = args.file.load(&args.scene)?;
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
