//! Image files. Output goes to a temporary file in the same folder and is renamed into
//! place, so a file is written whole or not at all (`output.rs`).
//!
//! EXR files hold float RGB, the variance of each pixel's mean as channels
//! `variance.R/G/B`, and the samples per pixel as the header attribute `spp`.

use std::fs;
use std::path::{Path, PathBuf};

use exr::prelude::Layer;
use exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, LayerAttributes,
    ReadChannels, ReadLayers, SmallVec, Text, WritableImage, read,
};

use super::film::{Film, PixelStats};
use super::limits::{MAX_IMAGE_PIXELS, check_exr, open_image};
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

fn image_error(path: &Path, message: impl ToString) -> ImageError {
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
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), ImageError> {
    super::output::write_atomically(path, write).map_err(|e| image_error(path, e))
}

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

/// Writes a little-endian PFM (bottom row first, as the format requires).
pub fn write_pfm(width: u32, height: u32, rgb: &[Spectrum], path: &Path) -> Result<(), ImageError> {
    let mut out = format!("PF\n{width} {height}\n-1.0\n").into_bytes();
    for y in (0..height).rev() {
        for c in &rgb[(y * width) as usize..((y + 1) * width) as usize] {
            for v in c.to_array() {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    write_atomically(path, |tmp| fs::write(tmp, &out).map_err(|e| e.to_string()))
}

fn write_exr(film: &Film, path: &Path, metadata: &[(String, String)]) -> Result<(), ImageError> {
    let size = (film.width as usize, film.height as usize);
    let channel = |name: &str, f: &dyn Fn(&PixelStats) -> f32| {
        AnyChannel::new(name, FlatSamples::F32(film.pixels.iter().map(f).collect()))
    };
    let channels = vec![
        channel("R", &|p| p.mean.x),
        channel("G", &|p| p.mean.y),
        channel("B", &|p| p.mean.z),
        channel("variance.R", &|p| p.variance_of_mean().x),
        channel("variance.G", &|p| p.variance_of_mean().y),
        channel("variance.B", &|p| p.variance_of_mean().z),
    ];
    let mut attributes = LayerAttributes::named("");
    attributes.software_name = Some(Text::from("lightlab"));
    let spp = film.pixels.iter().map(|p| p.count).min().unwrap_or(0);
    attributes
        .other
        .insert(Text::from("spp"), AttributeValue::I32(spp as i32));
    for (name, value) in metadata {
        if name == "spp" || name.is_empty() {
            return Err(image_error(
                path,
                format!("bad EXR attribute name \"{name}\""),
            ));
        }
        attributes.other.insert(
            Text::from(name.as_str()),
            AttributeValue::Text(Text::from(value.as_str())),
        );
    }
    let layer = Layer::new(
        size,
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(channels)),
    );
    let image = Image::from_layer(layer);
    write_atomically(path, |tmp| {
        image.write().to_file(tmp).map_err(|e| e.to_string())
    })
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

/// Radiance RGBE (`.hdr`), linear.
fn read_hdr(path: &Path) -> Result<LoadedImage, ImageError> {
    let img = open_image(path)
        .map_err(|e| image_error(path, e))?
        .into_rgb32f();
    let (w, h) = img.dimensions();
    let rgb = img
        .pixels()
        .map(|p| Spectrum::new(p.0[0], p.0[1], p.0[2]))
        .collect();
    Ok(LoadedImage {
        width: w,
        height: h,
        rgb,
        variance: None,
        spp: None,
        metadata: Vec::new(),
    })
}

fn read_exr(path: &Path) -> Result<LoadedImage, ImageError> {
    check_exr(path).map_err(|e| image_error(path, e))?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| image_error(path, e))?;
    let layer = &image.layer_data;
    let (w, h) = (layer.size.width(), layer.size.height());
    let find = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| c.sample_data.values_as_f32().collect::<Vec<f32>>())
    };
    let zip3 = |r: Vec<f32>, g: Vec<f32>, b: Vec<f32>| -> Vec<Spectrum> {
        r.into_iter()
            .zip(g)
            .zip(b)
            .map(|((r, g), b)| Spectrum::new(r, g, b))
            .collect()
    };
    let (Some(r), Some(g), Some(b)) = (find("R"), find("G"), find("B")) else {
        return Err(image_error(path, "EXR has no R, G and B channels"));
    };
    // Subsampled channels (x/y sampling > 1) hold fewer values than pixels.
    if layer
        .channel_data
        .list
        .iter()
        .any(|c| c.sample_data.len() != w * h)
    {
        return Err(image_error(
            path,
            "EXR has subsampled channels (not supported)",
        ));
    }
    let variance = match (find("variance.R"), find("variance.G"), find("variance.B")) {
        (Some(r), Some(g), Some(b)) => Some(zip3(r, g, b)),
        _ => None,
    };
    let spp = [&layer.attributes.other, &image.attributes.other]
        .iter()
        .find_map(|m| match m.get(&Text::from("spp")) {
            Some(AttributeValue::I32(v)) if *v >= 0 => Some(*v as u32),
            _ => None,
        });
    let mut metadata: Vec<(String, String)> = [&image.attributes.other, &layer.attributes.other]
        .iter()
        .flat_map(|m| m.iter())
        .filter_map(|(k, v)| match v {
            AttributeValue::Text(t) => Some((k.to_string(), t.to_string())),
            _ => None,
        })
        .collect();
    metadata.sort();
    Ok(LoadedImage {
        width: w as u32,
        height: h as u32,
        rgb: zip3(r, g, b),
        variance,
        spp,
        metadata,
    })
}

fn read_png(path: &Path) -> Result<LoadedImage, ImageError> {
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

fn read_pfm(path: &Path) -> Result<LoadedImage, ImageError> {
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
    Ok(LoadedImage {
        width: w,
        height: h,
        rgb,
        variance: None,
        spp: None,
        metadata: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
