//! `merge`: combines the EXR parts of a render split with `--pass I/N` into the image a
//! single run would have made. Each part stores per pixel the mean, the variance of the
//! mean and (in its header) the sample count, which recover Welford's statistics
//! (count n, mean, M2 = Var(mean)·n·(n − 1)); parts combine by Chan et al.'s pairwise
//! update (1979), so the merge is sample-weighted and keeps the variance.

use std::path::{Path, PathBuf};

use crate::image::io::{LoadedImage, read_image};
use crate::image::{Film, PixelStats};

/// Why parts cannot be merged, naming the file.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// A part could not be read.
    #[error(transparent)]
    Read(#[from] crate::image::io::ImageError),
    /// A part lacks what a merge needs, or does not match the first part.
    #[error("{0}: {1}")]
    Part(PathBuf, String),
    /// Nothing to merge.
    #[error("no parts to merge")]
    Empty,
}

/// The film a loaded EXR part describes: every pixel with the header's `spp` samples.
pub fn film_from_image(image: &LoadedImage, path: &Path) -> Result<Film, MergeError> {
    let bad = |m: &str| MergeError::Part(path.to_path_buf(), m.to_string());
    let spp = image
        .spp
        .ok_or_else(|| bad("no `spp` header attribute (only lightlab EXR files merge)"))?;
    let variance = image
        .variance
        .as_ref()
        .ok_or_else(|| bad("no variance.R/G/B channels (only lightlab EXR files merge)"))?;
    let n = spp as f32;
    let pixels = image
        .rgb
        .iter()
        .zip(variance)
        .map(|(&mean, &var)| PixelStats {
            count: spp,
            mean,
            // Var(mean) = M2 / ((n − 1) n)
            m2: if spp > 1 {
                var * (n * (n - 1.0))
            } else {
                var * 0.0
            },
            // Unit sample weights: exact for the one-pixel box filter; for wider filters
            // (weighted pixels) the parts are combined by sample count, an approximation.
            weight: n,
            weight2: n,
        })
        .collect();
    Ok(Film {
        width: image.width,
        height: image.height,
        pixels,
    })
}

/// Reads and merges the parts; all must have the same size.
pub fn merge_files(parts: &[PathBuf]) -> Result<Film, MergeError> {
    let mut merged: Option<Film> = None;
    for path in parts {
        let image = read_image(path)?;
        let film = film_from_image(&image, path)?;
        merged = Some(match merged {
            None => film,
            Some(m) => m.merge(&film).ok_or_else(|| {
                MergeError::Part(
                    path.clone(),
                    format!(
                        "is {}x{} but the first part is {}x{}",
                        film.width, film.height, m.width, m.height
                    ),
                )
            })?,
        });
    }
    merged.ok_or(MergeError::Empty)
}
