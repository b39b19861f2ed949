//! Environment maps from image files: the loader reads the file, the light holds only
//! texels (lights read no files).

use std::path::Path;

use glam::Mat3;

use crate::image::io::read_image;
use crate::light::environment::{Environment, LatLongImage};

/// An environment map from a lat-long image file (`.exr`, `.hdr`, `.pfm`, `.png`) in
/// Mitsuba 3's `envmap` convention, scaled by `scale` and rotated by `to_world`.
pub fn environment_from_file(
    path: &Path,
    scale: f32,
    to_world: Mat3,
) -> Result<Environment, String> {
    let img = read_image(path).map_err(|e| e.to_string())?;
    let image = LatLongImage::new(img.width as usize, img.height as usize, img.rgb)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Environment::from_image(image, scale, to_world).map_err(|e| format!("{}: {e}", path.display()))
}
