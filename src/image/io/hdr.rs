//! Radiance RGBE (`.hdr`), read through the `image` crate within its size limits.

use std::path::Path;

use super::{ImageError, LoadedImage, image_error};
use crate::image::limits::open_image;
use crate::math::Spectrum;

/// Radiance RGBE (`.hdr`), linear.
pub(super) fn read_hdr(path: &Path) -> Result<LoadedImage, ImageError> {
    let img = open_image(path)
        .map_err(|e| image_error(path, e))?
        .into_rgb32f();
    let (w, h) = img.dimensions();
    let rgb = img
        .pixels()
        .map(|p| Spectrum::new(p.0[0], p.0[1], p.0[2]))
        .collect();
    Ok(LoadedImage::rgb_only(w, h, rgb))
}
