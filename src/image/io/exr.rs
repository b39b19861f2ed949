//! OpenEXR: float RGB, the variance of each pixel's mean (`variance.R/G/B`), `spp` and
//! text metadata in the header; reading checks the declared sizes against the file first.

use exr::prelude::Layer;
use exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, LayerAttributes,
    ReadChannels, ReadLayers, SmallVec, Text, WritableImage, read,
};
use std::path::Path;

use super::{ImageError, LoadedImage, image_error, write_atomically};
use crate::image::film::{Film, PixelStats};
use crate::image::limits::check_exr;
use crate::math::Spectrum;

/// Images of at most this many pixels (64 × 64) are compressed on the calling thread.
const SERIAL_PIXELS: usize = 64 * 64;

pub(super) fn write_exr(
    film: &Film,
    path: &Path,
    metadata: &[(String, String)],
) -> Result<(), ImageError> {
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
    // The exr crate compresses blocks (16 rows under ZIP16) on a thread pool that it
    // builds for each write. On a small image the pool costs more than it saves
    // (`render --spp 1` at 64 × 64: 3.7 ms with the pool, 3.4 ms without; at 128 × 128
    // 5.8 and 6.3 ms, at 1920² 480 and 630 ms).
    let serial = film.width as usize * film.height as usize <= SERIAL_PIXELS;
    write_atomically(path, |tmp| {
        let writer = image.write();
        let writer = if serial {
            writer.non_parallel()
        } else {
            writer
        };
        writer.to_file(tmp).map_err(|e| e.to_string())
    })
}

pub(super) fn read_exr(path: &Path) -> Result<LoadedImage, ImageError> {
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
