//! `lightlab merge PART... -o out.exr`: sample-weighted merge of `--pass` parts,
//! variance kept.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::image::io::write_film_with_metadata;
use crate::image::output::check_output;
use crate::lab::merge::merge_files;

/// Arguments of `merge`.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The EXR parts (from `render --pass I/N -o part.exr`).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output EXR.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// Runs `merge`.
pub fn run(args: &MergeArgs) -> Result<(), CliError> {
    // Checked before reading the parts: merge writes .exr (variance and spp are kept).
    check_output(&args.output, &["exr"]).map_err(|e| {
        CliError::input(format!(
            "-o {e}; merge writes .exr (variance and spp are kept)"
        ))
    })?;
    let merged = merge_files(&args.parts).map_err(CliError::input)?;
    let film = merged.film;
    let parts: Vec<String> = args.parts.iter().map(|p| p.display().to_string()).collect();
    let mut metadata = merged.metadata;
    metadata.push(("lightlab.merged_from".to_string(), parts.join(" ")));
    write_film_with_metadata(&film, &args.output, 0.0, &metadata).map_err(CliError::failure)?;
    let spp = film.spp();
    eprintln!(
        "merged {} parts: {spp} spp -> {}",
        args.parts.len(),
        args.output.display()
    );
    Ok(())
}
