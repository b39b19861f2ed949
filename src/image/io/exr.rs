//! Reading OpenEXR (with the `exr` crate): float RGB, the variance of each pixel's mean
//! (`variance.R/G/B`) where present, `spp` and text metadata in the header; the declared
//! sizes are checked against the file first. Writing is `exr_write.rs`.

use exr::prelude::{AttributeValue, ReadChannels, ReadLayers, Text, read};
use std::path::Path;

use super::{ImageError, LoadedImage, image_error};
use crate::image::limits::check_exr;
use crate::math::Spectrum;

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
            AttributeValue::Text(t) => Some((text(k), text(t))),
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

/// A header text as a string: UTF-8 (as lightlab writes it, and OpenEXR by convention)
/// where its bytes are, else one character per byte (Latin-1, as the `exr` crate wrote
/// it before).
fn text(t: &Text) -> String {
    match std::str::from_utf8(t.bytes()) {
        Ok(s) => s.to_owned(),
        Err(_) => t.to_string(),
    }
}
