//! What every experiment starts with: the scene, each strategy's settings, and a
//! reference image (read from a file, or rendered and described in the report).

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use crate::image::io::read_image;
use crate::lab::LabError;
use crate::lab::reference::{ReferenceTarget, render_reference};
use crate::lab::strategy::Strategy;
use crate::math::Spectrum;
use crate::render::RenderSettings;
use crate::scene::{self, Scene};
use crate::settings::RenderPatch;

/// Loads a scene, naming it in the error.
pub fn load_scene(spec: &str) -> Result<Scene, LabError> {
    scene::load(spec).map_err(|error| LabError::Scene {
        spec: spec.to_string(),
        error,
    })
}

/// Settings of every strategy on `scene`: the scene's defaults, then `base` (the
/// experiment's flags for every strategy), then the strategy's own patch, then `budget`
/// (an equal-spp budget); later layers win. Fails on the first strategy that does not fit.
pub fn resolve(
    scene: &Scene,
    strategies: &[Strategy],
    base: &RenderPatch,
    budget: &RenderPatch,
) -> Result<Vec<RenderSettings>, LabError> {
    strategies
        .iter()
        .map(|s| {
            RenderSettings::build(scene, &[base, &s.patch, budget]).map_err(|error| {
                LabError::Strategy {
                    label: s.label.clone(),
                    flags: s.patch.to_string(),
                    error,
                }
            })
        })
        .collect()
}

/// Mixed into the seed of a rendered reference so its streams differ from every
/// strategy's.
pub const REFERENCE_SEED_SALT: u64 = 0x05ee_d0f4_efe4_e4c3;

/// Where the reference comes from.
#[derive(Clone, Debug)]
pub enum ReferenceSource {
    /// An image file (EXR with variance is best).
    File(PathBuf),
    /// Render `strategy` at `spp` (with the experiment's base flags).
    Render {
        /// The strategy.
        strategy: Strategy,
        /// Samples per pixel.
        spp: u32,
    },
}

/// A reference image and how it was made.
#[derive(Clone, Debug)]
pub struct ReferenceImage {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Linear RGB.
    pub rgb: Vec<Spectrum>,
    /// Variance of each pixel's mean, if known.
    pub variance: Option<Vec<Spectrum>>,
    /// One line for the report: file, or strategy, spp and time.
    pub description: String,
}

/// Reads or renders the reference; a file must be `width`×`height`.
pub fn obtain_reference(
    scene: &Scene,
    source: &ReferenceSource,
    base: &RenderPatch,
    size: (u32, u32),
    stop: &AtomicBool,
) -> Result<ReferenceImage, LabError> {
    match source {
        ReferenceSource::File(path) => {
            let img = read_image(path)?;
            if (img.width, img.height) != size {
                return Err(LabError::Input(format!(
                    "reference {} is {}x{} but the renders are {}x{} (give the same --width/--height)",
                    path.display(),
                    img.width,
                    img.height,
                    size.0,
                    size.1
                )));
            }
            Ok(ReferenceImage {
                width: img.width,
                height: img.height,
                rgb: img.rgb,
                variance: img.variance,
                description: format!(
                    "reference: {}{}",
                    path.display(),
                    img.spp.map(|s| format!(" ({s} spp)")).unwrap_or_default()
                ),
            })
        }
        ReferenceSource::Render { strategy, spp } => {
            let mut settings = resolve(
                scene,
                std::slice::from_ref(strategy),
                base,
                &RenderPatch::default(),
            )?
            .remove(0);
            // Streams of their own: a reference sharing samples with a strategy it judges
            // would favour that strategy.
            settings.seed ^= REFERENCE_SEED_SALT;
            let target = ReferenceTarget {
                max_spp: Some(*spp),
                ..Default::default()
            };
            let r = render_reference(scene, &settings, &target, stop, &|_, _| {});
            let film = &r.output.film;
            Ok(ReferenceImage {
                width: film.width,
                height: film.height,
                rgb: film.means(),
                variance: Some(film.pixels.iter().map(|p| p.variance_of_mean()).collect()),
                description: format!(
                    "reference: rendered with \"{}\" (`{}`), {} spp in {:.1} s, estimated relative error {:.2e} (image mean), {:.2e} (90% of pixels)",
                    strategy.label,
                    RenderSettings {
                        spp: r.output.spp,
                        ..settings.clone()
                    }
                    .patch(),
                    r.output.spp,
                    r.output.time.as_secs_f64(),
                    r.error.mean_rel_error,
                    r.error.pixel_rel_error
                ),
            })
        }
    }
}
