//! `merge`: combines the EXR parts of a render split with `--pass I/N` into the image a
//! single run would have made. Each part stores per pixel the mean, the variance of the
//! mean and (in its header) the sample count, which recover Welford's statistics
//! (count n, mean, M2 = Var(mean)·n·(n − 1)); parts combine by Chan et al.'s pairwise
//! update (1979), so the merge is sample-weighted and keeps the variance.
//!
//! Every EXR `render` writes records where its samples come from (the header attributes
//! of [`header`]): the scene's content hash, the settings other than seed, spp and pass,
//! and the blocks of sample indices it rendered under each seed. `merge` combines only
//! parts of one scene under one set of settings whose sample blocks are disjoint (the
//! same pass twice, or `--pass 1/2` with `--pass 1/3` of one seed, would count samples
//! twice), and names the file and the attribute when they are not.

use std::path::{Path, PathBuf};

use crate::image::io::{LoadedImage, read_image};
use crate::image::{Film, PixelStats};
use crate::render::{RenderOutput, RenderSettings, SampleBlock};
use crate::scene::Scene;

/// Names of the header attributes that say where a render's samples come from.
pub mod header {
    /// The scene's name (`builtin:NAME` or the file), for messages.
    pub const SCENE: &str = "lightlab.scene";
    /// [`Scene::content_hash`](crate::scene::Scene::content_hash), 16 hex digits.
    pub const SCENE_HASH: &str = "lightlab.scene_hash";
    /// The canonical render flags without `--seed`, `--spp` and `--pass`.
    pub const SETTINGS: &str = "lightlab.settings";
    /// The sample blocks, `SEED:FIRST..LAST` separated by spaces.
    pub const SAMPLES: &str = "lightlab.samples";
}

/// The settings of a render as recorded in [`header::SETTINGS`]: what must agree between
/// parts (seed, spp and pass may differ; the sample blocks say what they cover).
pub fn recorded_settings(settings: &RenderSettings) -> String {
    let mut patch = settings.patch();
    (patch.seed, patch.spp, patch.pass) = (None, None, None);
    patch.to_string()
}

/// The header attributes recording where `out`'s samples come from.
pub fn provenance(
    scene: &Scene,
    settings: &RenderSettings,
    out: &RenderOutput,
) -> Vec<(String, String)> {
    vec![
        (header::SCENE.into(), scene.name.clone()),
        (
            header::SCENE_HASH.into(),
            format!("{:016x}", scene.content_hash),
        ),
        (header::SETTINGS.into(), recorded_settings(settings)),
        (header::SAMPLES.into(), blocks_text(&out.samples)),
    ]
}

/// Sample blocks as [`header::SAMPLES`] writes them.
pub fn blocks_text(blocks: &[SampleBlock]) -> String {
    let text: Vec<String> = blocks.iter().map(|b| b.to_string()).collect();
    text.join(" ")
}

/// The first pair (one of `have`, one of `new`) that holds the same samples, if any.
pub fn overlapping(
    have: &[SampleBlock],
    new: &[SampleBlock],
) -> Option<(SampleBlock, SampleBlock)> {
    new.iter()
        .find_map(|n| have.iter().find(|h| h.overlaps(n)).map(|h| (*h, *n)))
}

/// What a part's header says about its samples.
struct Provenance {
    scene: String,
    scene_hash: String,
    settings: String,
    samples: Vec<SampleBlock>,
}

fn provenance_of(image: &LoadedImage, path: &Path) -> Result<Provenance, MergeError> {
    let get = |name: &str| {
        image
            .metadata
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.clone())
            .ok_or_else(|| {
                MergeError::Part(
                    path.to_path_buf(),
                    format!(
                        "no `{name}` header attribute: only EXR files that this version of \
                         lightlab renders say which samples they hold, and merge needs that"
                    ),
                )
            })
    };
    let samples_text = get(header::SAMPLES)?;
    let samples = samples_text
        .split_whitespace()
        .map(|b| b.parse::<SampleBlock>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| MergeError::Part(path.to_path_buf(), format!("`{}`: {e}", header::SAMPLES)))?;
    for (i, a) in samples.iter().enumerate() {
        if let Some(b) = samples[i + 1..].iter().find(|b| a.overlaps(b)) {
            return Err(MergeError::Part(
                path.to_path_buf(),
                format!("`{}`: blocks {a} and {b} overlap", header::SAMPLES),
            ));
        }
    }
    Ok(Provenance {
        scene: get(header::SCENE)?,
        scene_hash: get(header::SCENE_HASH)?,
        settings: get(header::SETTINGS)?,
        samples,
    })
}

/// Why parts cannot be merged, naming the file.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// A part could not be read.
    #[error(transparent)]
    Read(#[from] crate::image::io::ImageError),
    /// A part lacks what a merge needs, or does not match the first part.
    #[error("{0}: {1}")]
    Part(PathBuf, String),
    /// Nothing to merge.
    #[error("no parts to merge")]
    Empty,
}

/// The film a loaded EXR part describes: every pixel with the header's `spp` samples.
pub fn film_from_image(image: &LoadedImage, path: &Path) -> Result<Film, MergeError> {
    let bad = |m: &str| MergeError::Part(path.to_path_buf(), m.to_string());
    let spp = image
        .spp
        .ok_or_else(|| bad("no `spp` header attribute (only lightlab EXR files merge)"))?;
    let variance = image
        .variance
        .as_ref()
        .ok_or_else(|| bad("no variance.R/G/B channels (only lightlab EXR files merge)"))?;
    let n = spp as f32;
    let pixels = image
        .rgb
        .iter()
        .zip(variance)
        .map(|(&mean, &var)| PixelStats {
            count: spp,
            mean,
            // Var(mean) = M2 / ((n − 1) n)
            m2: if spp > 1 {
                var * (n * (n - 1.0))
            } else {
                var * 0.0
            },
            // Unit sample weights: exact for the one-pixel box filter; for wider filters
            // (weighted pixels) the parts are combined by sample count, an approximation.
            weight: n,
            weight2: n,
        })
        .collect();
    Ok(Film {
        width: image.width,
        height: image.height,
        pixels,
    })
}

/// A merge of parts: the film and where its samples come from.
pub struct Merged {
    /// The merged film.
    pub film: Film,
    /// Header attributes for the merged file ([`header`]: scene, hash, settings, and
    /// every part's sample blocks).
    pub metadata: Vec<(String, String)>,
}

/// Reads and merges the parts. All must have the same size, scene hash and settings,
/// and no two may hold the same samples.
pub fn merge_files(parts: &[PathBuf]) -> Result<Merged, MergeError> {
    // (film so far, first part's provenance and path, sample blocks with their files)
    let mut merged: Option<(Film, Provenance, &Path)> = None;
    let mut owners: Vec<(SampleBlock, &Path)> = Vec::new();
    for path in parts {
        let image = read_image(path)?;
        let film = film_from_image(&image, path)?;
        let prov = provenance_of(&image, path)?;
        let part = |m: String| MergeError::Part(path.clone(), m);
        if let Some((m, first, first_path)) = &merged {
            if (m.width, m.height) != (film.width, film.height) {
                return Err(part(format!(
                    "is {}x{} but the first part is {}x{}",
                    film.width, film.height, m.width, m.height
                )));
            }
            let differs = |name: &str, a: &str, b: &str| {
                part(format!(
                    "`{name}` is \"{b}\" but {} has \"{a}\" ({})",
                    first_path.display(),
                    if name == header::SCENE_HASH {
                        format!(
                            "a different scene or scene content: {} vs {}",
                            first.scene, prov.scene
                        )
                    } else {
                        "parts of one render share their settings".to_string()
                    }
                ))
            };
            if prov.scene_hash != first.scene_hash {
                return Err(differs(
                    header::SCENE_HASH,
                    &first.scene_hash,
                    &prov.scene_hash,
                ));
            }
            if prov.settings != first.settings {
                return Err(differs(header::SETTINGS, &first.settings, &prov.settings));
            }
        }
        let have: Vec<SampleBlock> = owners.iter().map(|(b, _)| *b).collect();
        if let Some((old, new)) = overlapping(&have, &prov.samples) {
            let owner = owners.iter().find(|(b, _)| *b == old).map(|(_, p)| *p);
            return Err(part(format!(
                "`{}`: samples {new} overlap samples {old} of {} (the same pass twice, or \
                 passes of different splits of one seed)",
                header::SAMPLES,
                owner.map_or(String::new(), |p| p.display().to_string())
            )));
        }
        owners.extend(prov.samples.iter().map(|b| (*b, path.as_path())));
        merged = Some(match merged {
            None => (film, prov, path.as_path()),
            Some((m, first, first_path)) => {
                // Sizes were compared above.
                let film = m.merge(&film).ok_or_else(|| part("size mismatch".into()))?;
                (film, first, first_path)
            }
        });
    }
    let (film, first, _) = merged.ok_or(MergeError::Empty)?;
    let blocks: Vec<SampleBlock> = owners.iter().map(|(b, _)| *b).collect();
    Ok(Merged {
        film,
        metadata: vec![
            (header::SCENE.into(), first.scene),
            (header::SCENE_HASH.into(), first.scene_hash),
            (header::SETTINGS.into(), first.settings),
            (header::SAMPLES.into(), blocks_text(&blocks)),
        ],
    })
}
