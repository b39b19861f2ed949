//! Size limits of images read from files: a declared size is checked against a cap and
//! against the bytes the file can hold before any decoder allocates pixels for it, so a
//! header that claims 10⁹×10⁹ pixels is an error instead of an aborted allocation.

use std::path::Path;

use exr::meta::MetaData;
use exr::prelude::Compression;

/// Most pixels an input image may have: 2²⁷ (a 16384×8192 environment map); the reader
/// keeps 12 to 24 bytes per pixel.
pub const MAX_IMAGE_PIXELS: u64 = 1 << 27;

/// Longest side of an input image.
pub const MAX_IMAGE_SIDE: u32 = 1 << 16;

/// Most bytes a compressed EXR block may inflate to per byte in the file. Deflate
/// peaks near 1032:1 (RFC 1951: a 258-byte match in one to two bits); the rest of
/// OpenEXR's lossless codecs stay below it.
const MAX_INFLATION: u64 = 2048;

/// Checks every layer an EXR header declares: a non-empty size of at most
/// [`MAX_IMAGE_PIXELS`], an offset table (8 bytes per chunk, OpenEXR file layout) that
/// fits in the file, and pixel bytes the file's size can hold. Returns the message of
/// the first violation.
pub fn check_exr(path: &Path) -> Result<(), String> {
    let file_bytes = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    let meta = MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    for header in meta.headers.iter() {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        let pixels = (w as u64).saturating_mul(h as u64);
        if pixels == 0 || pixels > MAX_IMAGE_PIXELS {
            return Err(format!(
                "EXR header declares {w}x{h} pixels (1 to {MAX_IMAGE_PIXELS} accepted)"
            ));
        }
        let table = (header.chunk_count as u64).saturating_mul(8);
        let pixel_bytes = pixels.saturating_mul(header.channels.bytes_per_pixel as u64);
        let holds = if header.compression == Compression::Uncompressed {
            file_bytes
        } else {
            file_bytes.saturating_mul(MAX_INFLATION)
        };
        if table > file_bytes || pixel_bytes > holds {
            return Err(format!(
                "EXR header declares {w}x{h} pixels in {} chunks, more than the file's {file_bytes} bytes can hold (truncated or corrupt)",
                header.chunk_count
            ));
        }
    }
    Ok(())
}

/// Limits for the `image` crate's decoders (PNG, JPEG, Radiance HDR): sides of at most
/// [`MAX_IMAGE_SIDE`] and allocations of at most 24 bytes per allowed pixel.
pub fn decoder_limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(24 * MAX_IMAGE_PIXELS);
    limits
}

/// Decodes a PNG, JPEG or Radiance HDR file (format from its bytes) within
/// [`decoder_limits`], and refuses more than [`MAX_IMAGE_PIXELS`].
pub fn open_image(path: &Path) -> Result<image::DynamicImage, String> {
    // Reading the size consumes the reader, so the file is opened twice.
    let reader = || -> Result<_, String> {
        let mut reader = image::ImageReader::open(path)
            .map_err(|e| e.to_string())?
            .with_guessed_format()
            .map_err(|e| e.to_string())?;
        reader.limits(decoder_limits());
        Ok(reader)
    };
    let (w, h) = reader()?.into_dimensions().map_err(|e| e.to_string())?;
    if w as u64 * h as u64 > MAX_IMAGE_PIXELS || w == 0 || h == 0 {
        return Err(format!(
            "image is {w}x{h} pixels (1 to {MAX_IMAGE_PIXELS} accepted)"
        ));
    }
    reader()?.decode().map_err(|e| e.to_string())
}
