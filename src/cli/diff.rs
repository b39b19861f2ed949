//! `lightlab diff IMAGE REFERENCE [--false-color out.png]`. The relative bias against an
//! all-zero reference is printed as `undefined`.

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::image::io::{read_image, write_rgb8_png};
use crate::image::metrics::{compare, false_color};
use crate::image::output::check_output;

/// Arguments of `diff`.
#[derive(Args, Debug)]
pub struct DiffArgs {
    /// The image to judge (.exr, .pfm or .png).
    pub image: PathBuf,
    /// The reference.
    pub reference: PathBuf,
    /// Write a false-colour map of per-pixel relMSE (log scale 1e-4 … 10) to this PNG
    /// (a `.png` path: the map is 8-bit colour, not data).
    #[arg(long)]
    pub false_color: Option<PathBuf>,
}

/// Runs `diff`: prints one `name: value` line per metric.
pub fn run(args: &DiffArgs) -> Result<(), CliError> {
    // Refused before any work: write_rgb8_png would put PNG bytes under any name.
    if let Some(path) = &args.false_color {
        check_output(path, &["png"]).map_err(|e| {
            CliError::input(format!(
                "--false-color {e}; the false-colour map is written as PNG: give a .png path"
            ))
        })?;
    }
    let img = read_image(&args.image).map_err(CliError::input)?;
    let reference = read_image(&args.reference).map_err(CliError::input)?;
    if (img.width, img.height) != (reference.width, reference.height) {
        return Err(CliError::input(format!(
            "{} is {}x{} but {} is {}x{}",
            args.image.display(),
            img.width,
            img.height,
            args.reference.display(),
            reference.width,
            reference.height
        )));
    }
    let e = compare(
        &img.rgb,
        img.variance.as_deref(),
        &reference.rgb,
        reference.variance.as_deref(),
    );
    println!("mse: {:.6e}", e.mse);
    println!("relmse: {:.6e}", e.rel_mse);
    match (e.relative_bias, e.bias_std_error) {
        (None, _) => println!("relative-bias: undefined (the reference sums to zero)"),
        (Some(bias), Some(se)) => println!(
            "relative-bias: {bias:+.4e} ± {se:.4e} (z = {:+.2})",
            e.bias_z().unwrap_or(0.0)
        ),
        (Some(bias), None) => {
            println!("relative-bias: {bias:+.4e} (no variance in either file: no standard error)")
        }
    }
    println!("nan-pixels: {}", e.nan_pixels);
    println!("inf-pixels: {}", e.inf_pixels);
    if let Some(path) = &args.false_color {
        write_rgb8_png(
            img.width,
            img.height,
            false_color(&img.rgb, &reference.rgb),
            path,
        )
        .map_err(CliError::failure)?;
    }
    Ok(())
}
