//! `lightlab export SCENE -o scene.xml`: the scene as a Mitsuba 3 XML file, with its
//! meshes and environment map beside it (see [`crate::scene::export`]).

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use super::args::SceneFileArgs;
use crate::scene::export::export;

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
    let ext = args.output.extension().and_then(|e| e.to_str());
    if !ext.is_some_and(|e| e.eq_ignore_ascii_case("xml")) {
        return Err(CliError::input(format!(
            "-o {}: the export is a Mitsuba XML file: give a .xml path",
            args.output.display()
        )));
    }
    let folder = args.output.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(folder) = folder
        && !folder.is_dir()
    {
        return Err(CliError::input(format!(
            "-o {}: folder {} does not exist",
            args.output.display(),
            folder.display()
        )));
    }
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
