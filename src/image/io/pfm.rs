//! Portable float map (`.pfm`): little-endian float RGB, rows bottom to top.

use std::fs;
use std::path::Path;

use super::{ImageError, LoadedImage, image_error, write_atomically};
use crate::image::limits::MAX_IMAGE_PIXELS;
use crate::math::Spectrum;

/// A little-endian PFM file, whole (bottom row first, as the format requires), of the
/// row-major, top-first `rgb`.
pub fn pfm_bytes(width: u32, height: u32, rgb: &[Spectrum]) -> Vec<u8> {
    let mut out = format!("PF\n{width} {height}\n-1.0\n").into_bytes();
    out.reserve(12 * rgb.len());
    for y in (0..height).rev() {
        for c in &rgb[(y * width) as usize..((y + 1) * width) as usize] {
            for v in c.to_array() {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    out
}

/// Writes a little-endian PFM (see [`pfm_bytes`]).
pub fn write_pfm(width: u32, height: u32, rgb: &[Spectrum], path: &Path) -> Result<(), ImageError> {
    let out = pfm_bytes(width, height, rgb);
    write_atomically(path, |tmp| fs::write(tmp, &out).map_err(|e| e.to_string()))
}

pub(super) fn read_pfm(path: &Path) -> Result<LoadedImage, ImageError> {
    let bytes = fs::read(path).map_err(|e| image_error(path, e))?;
    // Header: three whitespace-separated tokens after the magic, then one whitespace byte.
    let mut tokens = Vec::new();
    let mut pos = 0;
    while tokens.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos {
            return Err(image_error(path, "truncated PFM header"));
        }
        tokens.push(String::from_utf8_lossy(&bytes[start..pos]).into_owned());
    }
    pos += 1;
    let bad = |m: &str| image_error(path, m);
    let channels = match tokens[0].as_str() {
        "PF" => 3,
        "Pf" => 1,
        _ => return Err(bad("not a PFM file (magic is not PF or Pf)")),
    };
    let w: u32 = tokens[1].parse().map_err(|_| bad("bad PFM width"))?;
    let h: u32 = tokens[2].parse().map_err(|_| bad("bad PFM height"))?;
    let scale: f32 = tokens[3].parse().map_err(|_| bad("bad PFM scale"))?;
    // Checked against the file's bytes before anything is allocated.
    let pixels = w as u64 * h as u64;
    let n = (pixels * channels as u64) as usize;
    let data = (pixels > 0 && pixels <= MAX_IMAGE_PIXELS)
        .then(|| bytes.get(pos..pos + 4 * n))
        .flatten()
        .ok_or_else(|| {
            bad("PFM size is out of range or its data is shorter than its header says")
        })?;
    let value = |i: usize| {
        let b = [
            data[4 * i],
            data[4 * i + 1],
            data[4 * i + 2],
            data[4 * i + 3],
        ];
        if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let mut rgb = vec![Spectrum::ZERO; pixels as usize];
    for y in 0..h as usize {
        for x in 0..w as usize {
            let i = ((h as usize - 1 - y) * w as usize + x) * channels;
            rgb[y * w as usize + x] = if channels == 3 {
                Spectrum::new(value(i), value(i + 1), value(i + 2))
            } else {
                Spectrum::splat(value(i))
            };
        }
    }
    Ok(LoadedImage::rgb_only(w, h, rgb))
}
