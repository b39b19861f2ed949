//! Image files. Output goes to a temporary file in the same folder and is renamed into
//! place, so a file is written whole or not at all (`output.rs`).
//!
//! One file per format: `exr` and `exr_write` (float RGB, the variance of each pixel's mean
//! as channels `variance.R/G/B`, the samples per pixel as the header attribute `spp`, text
//! metadata; read with the `exr` crate, written by lightlab in parallel blocks),
//! `png` (sRGB 8-bit, with the sRGB transfer functions), `hdr` (Radiance RGBE, read only)
//! and `pfm`. This file holds the shared types and the dispatch by extension.

mod exr;
mod exr_write;
mod hdr;
mod pfm;
mod png;

use exr::read_exr;
use exr_write::write_exr;
use hdr::read_hdr;
use pfm::read_pfm;
pub use pfm::{pfm_bytes, write_pfm};
use png::read_png;
pub use png::{linear_to_srgb, srgb_to_linear, to_srgb8, write_png, write_rgb8_png};

use std::path::{Path, PathBuf};

use super::film::Film;
use crate::math::Spectrum;

/// An error reading or writing an image, naming the file.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct ImageError {
    /// The file.
    pub path: PathBuf,
    /// What went wrong.
    pub message: String,
}

pub(super) fn image_error(path: &Path, message: impl ToString) -> ImageError {
    ImageError {
        path: path.to_path_buf(),
        message: message.to_string(),
    }
}

/// An image read from a file: RGB means, and per-pixel variance of the mean and spp
/// when the file carries them.
#[derive(Clone, Debug)]
pub struct LoadedImage {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// RGB values, row-major.
    pub rgb: Vec<Spectrum>,
    /// Variance of each pixel's mean, if stored.
    pub variance: Option<Vec<Spectrum>>,
    /// Samples per pixel, if stored.
    pub spp: Option<u32>,
    /// Text attributes of an EXR header (name, value), e.g. `lightlab.settings`.
    pub metadata: Vec<(String, String)>,
}

impl LoadedImage {
    /// An image with RGB values only (no variance, spp or metadata).
    pub fn rgb_only(width: u32, height: u32, rgb: Vec<Spectrum>) -> LoadedImage {
        LoadedImage {
            width,
            height,
            rgb,
            variance: None,
            spp: None,
            metadata: Vec::new(),
        }
    }
}

/// Writes `film` to `path` by extension: `.exr` (float RGB + variance + spp) or `.png`
/// (sRGB, scaled by 2^exposure). Other extensions are an error.
pub fn write_film(film: &Film, path: &Path, exposure: f32) -> Result<(), ImageError> {
    write_film_with_metadata(film, path, exposure, &[])
}

/// [`write_film`] with text attributes (name, value) stored in an EXR header; other
/// formats have no place for them and drop them.
pub fn write_film_with_metadata(
    film: &Film,
    path: &Path,
    exposure: f32,
    metadata: &[(String, String)],
) -> Result<(), ImageError> {
    match extension(path).as_str() {
        "exr" => write_exr(film, path, metadata),
        "png" => write_png(film.width, film.height, &film.means(), path, exposure),
        "pfm" => write_pfm(film.width, film.height, &film.means(), path),
        other => Err(image_error(
            path,
            format!("unknown image format \".{other}\" (known: .exr, .png, .pfm)"),
        )),
    }
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Writes through a temporary sibling file renamed into place (see [`super::output`]).
pub(super) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), ImageError> {
    super::output::write_atomically(path, write).map_err(|e| image_error(path, e))
}

/// Reads an image: EXR (R, G, B, optional variance.R/G/B and spp), Radiance HDR, PFM, or PNG
/// (sRGB decoded to linear).
pub fn read_image(path: &Path) -> Result<LoadedImage, ImageError> {
    match extension(path).as_str() {
        "exr" => read_exr(path),
        "pfm" => read_pfm(path),
        "png" => read_png(path),
        "hdr" => read_hdr(path),
        other => Err(image_error(
            path,
            format!("unknown image format \".{other}\" (known: .exr, .hdr, .pfm, .png)"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn exr_round_trips_with_variance_and_spp() {
        let mut film = Film::new(3, 2);
        for (i, p) in film.pixels.iter_mut().enumerate() {
            for k in 0..4 {
                p.add(Spectrum::new(i as f32, k as f32, 0.5));
            }
        }
        let dir = std::env::temp_dir().join(format!("lightlab-io-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.exr");
        let meta = [("lightlab.note".to_string(), "a b".to_string())];
        write_film_with_metadata(&film, &path, 0.0, &meta).unwrap();
        let img = read_image(&path).unwrap();
        assert_eq!((img.width, img.height, img.spp), (3, 2, Some(4)));
        assert_eq!(img.metadata, meta);
        assert_eq!(img.rgb, film.means());
        let var = img.variance.unwrap();
        assert!((var[0].y - film.pixels[0].variance_of_mean().y).abs() < 1e-6);
        let pfm = dir.join("t.pfm");
        write_film(&film, &pfm, 0.0).unwrap();
        assert_eq!(read_image(&pfm).unwrap().rgb, film.means());
        assert!(write_film(&film, &dir.join("t.bmp"), 0.0).is_err());
        let _ = fs::remove_dir_all(dir);
    }
}
