//! Writing OpenEXR: one scanline part of six float channels (R, G, B and `variance.R/G/B`,
//! the variance of each pixel's mean), the header attributes `software`, `spp` and text
//! metadata, ZIP-compressed in blocks of 16 rows (OpenEXR's `ZIP_COMPRESSION`; the layout
//! of the OpenEXR specification's "OpenEXR File Layout": magic and version, header
//! attributes, a table of chunk offsets, then the chunks).
//!
//! The blocks are compressed in parallel on the calling rayon pool, with deflate at level
//! 1 (a greedy match search) rather than the level 4 of OpenEXR's library and of the
//! `exr` crate, which wrote lightlab's files before: on a 1920×1080 render at 16 spp the
//! blocks took 0.75 s of one core at level 4 and 0.16 s at level 1, for a file 4 % larger
//! (float mantissas hardly compress either way; BENCHMARKS.md, session 35).
//! Text is written as UTF-8 bytes, which OpenEXR's strings are by convention.

use rayon::prelude::*;
use std::io::Write;
use std::path::Path;

use super::{ImageError, image_error, write_atomically};
use crate::image::film::{Film, PixelStats};

/// Rows per block under ZIP compression (fixed by the format).
const ROWS: usize = 16;

/// The channels in the order the file lists them (sorted by name, as OpenEXR requires),
/// with their `pLinear` flag: set for the variances, which are not perceptual values (it
/// matters only to lossy codecs; the `exr` crate set it the same way).
const CHANNELS: [(&str, u8); 6] = [
    ("B", 0),
    ("G", 0),
    ("R", 0),
    ("variance.B", 1),
    ("variance.G", 1),
    ("variance.R", 1),
];

/// A pixel's values in the order of [`CHANNELS`].
fn values(p: &PixelStats) -> [f32; 6] {
    let v = p.variance_of_mean();
    [p.mean.z, p.mean.y, p.mean.x, v.z, v.y, v.x]
}

/// Whether a text attribute may not take `name`: one that lightlab writes itself
/// (`spp`), or one of the standard attributes the `exr` crate knows (its list), which
/// readers interpret rather than hand over as text: a text `owner` or `comments` would
/// come back as a typed field, a `chunkCount` or `type` would change how the file reads.
/// (Names OpenEXR added later, such as `cameraMake`, are not in that list.)
fn reserved(name: &str) -> bool {
    name == "spp" || exr::meta::header::standard_names::ALL.contains(&name.as_bytes())
}

/// Longest attribute name OpenEXR reads (with the long-names flag; 31 without).
const MAX_NAME: usize = 255;

pub(super) fn write_exr(
    film: &Film,
    path: &Path,
    metadata: &[(String, String)],
) -> Result<(), ImageError> {
    let header = header(film, metadata).map_err(|e| image_error(path, e))?;
    let (width, height) = (film.width as usize, film.height as usize);
    let chunks: Vec<Vec<u8>> = (0..height.div_ceil(ROWS))
        .into_par_iter()
        .map(|c| {
            let rows = c * ROWS..((c + 1) * ROWS).min(height);
            chunk(
                &film.pixels[rows.start * width..rows.end * width],
                width,
                rows.start,
            )
        })
        .collect::<std::io::Result<_>>()
        .map_err(|e| image_error(path, e))?;
    write_atomically(path, |tmp| {
        let file = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
        let mut out = std::io::BufWriter::new(file);
        out.write_all(&header).map_err(|e| e.to_string())?;
        // The offset table: where each chunk starts, counted from the file's start.
        let mut at = (header.len() + 8 * chunks.len()) as u64;
        for c in &chunks {
            out.write_all(&at.to_le_bytes())
                .map_err(|e| e.to_string())?;
            at += c.len() as u64;
        }
        for c in &chunks {
            out.write_all(c).map_err(|e| e.to_string())?;
        }
        out.flush().map_err(|e| e.to_string())
    })
}

/// Magic number, version field and header attributes, up to the header's closing zero.
fn header(film: &Film, metadata: &[(String, String)]) -> Result<Vec<u8>, String> {
    // Sizes and rows are i32 in the file: a block (16 rows of six floats) and the last
    // row must fit in one.
    let (w, h) = (film.width, film.height);
    let block_bytes = w as u64 * (4 * CHANNELS.len() * ROWS) as u64;
    if w == 0 || h == 0 || block_bytes > i32::MAX as u64 || h > i32::MAX as u32 {
        return Err(format!("cannot write a {w}x{h} EXR image"));
    }
    if film.pixels.len() as u64 != w as u64 * h as u64 {
        let n = film.pixels.len();
        return Err(format!("cannot write a {w}x{h} EXR image from {n} pixels"));
    }
    for (name, value) in metadata {
        if name.is_empty() || name.contains('\0') || reserved(name) {
            return Err(format!("bad EXR attribute name \"{name}\""));
        }
        if name.len() > MAX_NAME {
            return Err(format!(
                "EXR attribute name longer than {MAX_NAME} bytes: \"{name}\""
            ));
        }
        if i32::try_from(value.len()).is_err() {
            return Err(format!("EXR attribute \"{name}\" is too long to store"));
        }
    }
    // Version 2, single-part scanline; bit 10 where a name is longer than 31 bytes.
    let long = metadata.iter().any(|(n, _)| n.len() > 31);
    let version: u32 = 2 | if long { 1 << 10 } else { 0 };
    let mut h = Vec::with_capacity(1024);
    h.extend_from_slice(&20000630u32.to_le_bytes());
    h.extend_from_slice(&version.to_le_bytes());
    let mut channels = Vec::new();
    for (name, linear) in CHANNELS {
        channels.extend_from_slice(name.as_bytes());
        channels.push(0);
        channels.extend_from_slice(&2i32.to_le_bytes()); // FLOAT
        channels.extend_from_slice(&[linear, 0, 0, 0]);
        channels.extend_from_slice(&1i32.to_le_bytes()); // x sampling
        channels.extend_from_slice(&1i32.to_le_bytes()); // y sampling
    }
    channels.push(0);
    attribute(&mut h, "channels", "chlist", &channels);
    attribute(&mut h, "compression", "compression", &[3]); // ZIP_COMPRESSION
    let window = [0, 0, film.width as i32 - 1, film.height as i32 - 1];
    let window: Vec<u8> = window.iter().flat_map(|v| v.to_le_bytes()).collect();
    attribute(&mut h, "dataWindow", "box2i", &window);
    attribute(&mut h, "displayWindow", "box2i", &window);
    attribute(&mut h, "lineOrder", "lineOrder", &[0]); // INCREASING_Y
    attribute(&mut h, "pixelAspectRatio", "float", &1f32.to_le_bytes());
    attribute(&mut h, "screenWindowCenter", "v2f", &[0; 8]);
    attribute(&mut h, "screenWindowWidth", "float", &1f32.to_le_bytes());
    attribute(&mut h, "software", "string", b"lightlab");
    let spp = i32::try_from(film.spp()).unwrap_or(i32::MAX);
    attribute(&mut h, "spp", "int", &spp.to_le_bytes());
    for (name, value) in metadata {
        attribute(&mut h, name, "string", value.as_bytes());
    }
    h.push(0);
    Ok(h)
}

/// Appends one attribute: name, type name, size in bytes, value.
fn attribute(h: &mut Vec<u8>, name: &str, kind: &str, value: &[u8]) {
    h.extend_from_slice(name.as_bytes());
    h.push(0);
    h.extend_from_slice(kind.as_bytes());
    h.push(0);
    h.extend_from_slice(&(value.len() as i32).to_le_bytes());
    h.extend_from_slice(value);
}

/// One chunk: the first row's y, the data's size, then the rows of `pixels` (rows of
/// `width` pixels starting at row `y`), each row every channel in turn, ZIP-compressed,
/// or as they are where compression would not make them smaller (the format's rule).
fn chunk(pixels: &[PixelStats], width: usize, y: usize) -> std::io::Result<Vec<u8>> {
    // Each row holds its channels one after the other: pixel i's channel c at c·width + i.
    let row_bytes = width * 4 * CHANNELS.len();
    let mut raw = vec![0u8; pixels.len() * 4 * CHANNELS.len()];
    for (row, bytes) in pixels
        .chunks_exact(width)
        .zip(raw.chunks_exact_mut(row_bytes))
    {
        for (i, p) in row.iter().enumerate() {
            for (c, v) in values(p).into_iter().enumerate() {
                let at = 4 * (c * width + i);
                bytes[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
        }
    }
    let zipped = zip(&raw)?;
    let data = if zipped.len() < raw.len() {
        &zipped
    } else {
        &raw
    };
    let mut out = Vec::with_capacity(8 + data.len());
    out.extend_from_slice(&(y as i32).to_le_bytes());
    out.extend_from_slice(&(data.len() as i32).to_le_bytes());
    out.extend_from_slice(data);
    Ok(out)
}

/// OpenEXR's ZIP coding of a block's bytes (OpenEXR's `ImfZip.cpp`): the bytes at even
/// positions, then those at odd positions (so the high bytes of floats sit together),
/// each stored as its difference from the one before plus 128, then zlib (RFC 1950) at
/// level 1.
fn zip(raw: &[u8]) -> std::io::Result<Vec<u8>> {
    let half = raw.len().div_ceil(2);
    let mut split = vec![0u8; raw.len()];
    for (i, pair) in raw.chunks(2).enumerate() {
        split[i] = pair[0];
        if let Some(&odd) = pair.get(1) {
            split[half + i] = odd;
        }
    }
    let mut before = split.first().copied().unwrap_or(0);
    for b in split.iter_mut().skip(1) {
        let now = *b;
        *b = now.wrapping_sub(before).wrapping_add(128);
        before = now;
    }
    let mut z = flate2::write::ZlibEncoder::new(
        Vec::with_capacity(raw.len() / 2),
        flate2::Compression::new(1),
    );
    z.write_all(&split)?;
    z.finish()
}

#[cfg(test)]
mod tests;
