//! Portable float map (`.pfm`): float RGB (`PF`) or grey (`Pf`), rows bottom to top; the
//! header's scale gives the byte order by its sign (negative: little-endian) and
//! multiplies every value by its magnitude. Written little-endian with scale −1.

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
    // The scale's sign gives the byte order; its magnitude multiplies every value (as
    // Mitsuba 3 and tev read it), so a map stored as v/s with scale ±s reads back as v.
    let scale: f32 = tokens[3]
        .parse()
        .ok()
        .filter(|s: &f32| s.is_finite() && *s != 0.0)
        .ok_or_else(|| {
            bad(&format!(
                "bad PFM scale \"{}\" (a finite, non-zero number is needed)",
                tokens[3]
            ))
        })?;
    let magnitude = scale.abs();
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
        magnitude
            * if scale < 0.0 {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn read_bytes(name: &str, bytes: &[u8]) -> Result<LoadedImage, ImageError> {
        let dir = std::env::temp_dir().join(format!("lightlab-pfm-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        fs::write(&path, bytes).unwrap();
        let read = read_pfm(&path);
        let _ = fs::remove_file(path);
        let _ = fs::remove_dir(dir);
        read
    }

    /// The scale's magnitude multiplies the values, its sign picks the byte order: one
    /// pixel (1, 2, 3) stored under scales ±2.5 reads (2.5, 5, 7.5), as Mitsuba 3 reads it.
    #[test]
    fn scale_multiplies_and_sign_gives_byte_order() {
        let values = [1.0f32, 2.0, 3.0];
        let mut little = b"PF\n1 1\n-2.5\n".to_vec();
        let mut big = b"PF\n1 1\n2.5\n".to_vec();
        for v in values {
            little.extend_from_slice(&v.to_le_bytes());
            big.extend_from_slice(&v.to_be_bytes());
        }
        let want = Spectrum::new(2.5, 5.0, 7.5);
        assert_eq!(read_bytes("le.pfm", &little).unwrap().rgb, vec![want]);
        assert_eq!(read_bytes("be.pfm", &big).unwrap().rgb, vec![want]);
        let mut grey = b"Pf\n1 1\n-4\n".to_vec();
        grey.extend_from_slice(&0.5f32.to_le_bytes());
        assert_eq!(
            read_bytes("g.pfm", &grey).unwrap().rgb,
            vec![Spectrum::splat(2.0)]
        );
        for scale in ["0", "-0.0", "nan", "inf"] {
            let mut bad = format!("Pf\n1 1\n{scale}\n").into_bytes();
            bad.extend_from_slice(&0.5f32.to_le_bytes());
            let err = read_bytes("bad.pfm", &bad).unwrap_err().to_string();
            assert!(err.contains("bad PFM scale"), "{scale}: {err}");
        }
    }
}
