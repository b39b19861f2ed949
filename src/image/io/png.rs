//! 8-bit sRGB PNG (and the sRGB transfer functions that PNG, JPEG and textures share).

use std::path::Path;

use super::{ImageError, LoadedImage, image_error, write_atomically};
use crate::image::limits::open_image;
use crate::math::Spectrum;

/// sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
#[inline]
pub fn linear_to_srgb(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// Inverse sRGB transfer function.
#[inline]
pub fn srgb_to_linear(x: f32) -> f32 {
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// 8-bit sRGB of a linear RGB value (non-finite values become black).
pub fn to_srgb8(c: Spectrum, scale: f32) -> [u8; 3] {
    let q = |v: f32| {
        let v = if v.is_finite() {
            (v * scale).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (linear_to_srgb(v) * 255.0 + 0.5) as u8
    };
    [q(c.x), q(c.y), q(c.z)]
}

/// Writes an sRGB PNG of linear RGB values scaled by 2^exposure.
pub fn write_png(
    width: u32,
    height: u32,
    rgb: &[Spectrum],
    path: &Path,
    exposure: f32,
) -> Result<(), ImageError> {
    let scale = exposure.exp2();
    let bytes: Vec<u8> = rgb.iter().flat_map(|&c| to_srgb8(c, scale)).collect();
    write_rgb8_png(width, height, bytes, path)
}

/// Writes 8-bit RGB bytes as a PNG.
pub fn write_rgb8_png(
    width: u32,
    height: u32,
    bytes: Vec<u8>,
    path: &Path,
) -> Result<(), ImageError> {
    let img = image::RgbImage::from_raw(width, height, bytes)
        .ok_or_else(|| image_error(path, "pixel count does not match the size"))?;
    write_atomically(path, |tmp| {
        img.save_with_format(tmp, image::ImageFormat::Png)
            .map_err(|e| e.to_string())
    })
}

pub(super) fn read_png(path: &Path) -> Result<LoadedImage, ImageError> {
    let img = open_image(path)
        .map_err(|e| image_error(path, e))?
        .to_rgb8();
    let rgb = img
        .pixels()
        .map(|p| Spectrum::from_array(p.0.map(|v| srgb_to_linear(v as f32 / 255.0))))
        .collect();
    Ok(LoadedImage {
        width: img.width(),
        height: img.height(),
        rgb,
        variance: None,
        spp: None,
        metadata: Vec::new(),
    })
}
