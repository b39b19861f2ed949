//! Rendering: tiles in parallel (rayon), one sampler stream per (seed, pixel, sample),
//! rounds of samples so a stop request still leaves a whole image, and a progress bar.

pub mod camera;
mod settings;

pub use settings::{Pass, RenderSettings};

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::Vec2;
use rayon::prelude::*;

use crate::image::{Film, PixelStats};
use crate::integrator::Estimator;
use crate::math::Spectrum;
use crate::sampling::{Sampler, Uniform};
use crate::scene::Scene;

/// Side of a square tile in pixels.
pub const TILE: u32 = 16;

/// What a render produced.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// The film.
    pub film: Film,
    /// Wall-clock time spent rendering (excludes scene loading).
    pub time: Duration,
    /// Samples per pixel rendered (fewer than asked if stopped early).
    pub spp: u32,
    /// Samples whose radiance was not finite; they were scored as zero.
    pub invalid_samples: u64,
    /// True when a stop request ended the render early.
    pub stopped: bool,
}

/// Hooks a render reports to and listens to.
pub struct Control<'a> {
    /// Called with (samples done, samples total) after each round.
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    /// Set to stop after the current round.
    pub stop: &'a AtomicBool,
}

/// Renders `scene` with `settings`.
pub fn render(scene: &Scene, settings: &RenderSettings, control: &Control<'_>) -> RenderOutput {
    // The light-sampling strategy lives in the lights, where every estimator asks for it.
    let scene = &*scene.with_light_sampling(settings.light_sampling);
    let camera = settings.camera(scene);
    let (w, h) = (camera.width, camera.height);
    let estimator =
        Estimator::new(scene, settings.estimator, settings.light_select).with_mis(settings.mis);
    let (first, last) = settings.pass.sample_range(settings.spp);
    let mut film = Film::new(w, h);
    let tiles = tiles(w, h);
    let invalid = AtomicU64::new(0);
    let start = Instant::now();
    let rounds = round_boundaries(first, last);
    let total = (last - first) as u64 * (w * h) as u64;
    let mut done = first;
    let mut stopped = false;
    for window in rounds.windows(2) {
        let (s0, s1) = (window[0], window[1]);
        let results: Vec<Vec<PixelStats>> = tiles
            .par_iter()
            .map(|&(x0, y0, x1, y1)| {
                let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
                for y in y0..y1 {
                    for x in x0..x1 {
                        let mut stats = *film.pixel(x, y);
                        let pixel = (y * w + x) as u64;
                        for s in s0..s1 {
                            let mut sampler = Sampler::new(
                                settings.sampler,
                                settings.seed,
                                pixel,
                                s,
                                settings.spp,
                            );
                            let p = Vec2::new(x as f32, y as f32) + sampler.next_2d();
                            let l = estimator.radiance(scene, &camera.ray(p), &mut sampler);
                            stats.add(if l.is_finite() {
                                l
                            } else {
                                invalid.fetch_add(1, Ordering::Relaxed);
                                Spectrum::ZERO
                            });
                        }
                        out.push(stats);
                    }
                }
                out
            })
            .collect();
        for (&(x0, y0, x1, _), tile) in tiles.iter().zip(results) {
            for (i, stats) in tile.into_iter().enumerate() {
                let (x, y) = (x0 + i as u32 % (x1 - x0), y0 + i as u32 / (x1 - x0));
                film.pixels[(y * w + x) as usize] = stats;
            }
        }
        done = s1;
        (control.progress)((s1 - first) as u64 * (w * h) as u64, total);
        if control.stop.load(Ordering::Relaxed) && s1 < last {
            stopped = true;
            break;
        }
    }
    RenderOutput {
        film,
        time: start.elapsed(),
        spp: done - first,
        invalid_samples: invalid.into_inner(),
        stopped,
    }
}

/// Tiles (x0, y0, x1, y1) covering the image, row by row.
fn tiles(w: u32, h: u32) -> Vec<(u32, u32, u32, u32)> {
    let mut t = Vec::new();
    for y in (0..h).step_by(TILE as usize) {
        for x in (0..w).step_by(TILE as usize) {
            t.push((x, y, (x + TILE).min(w), (y + TILE).min(h)));
        }
    }
    t
}

/// Sample indices at which rounds start: about eight rounds, at least one sample each.
fn round_boundaries(first: u32, last: u32) -> Vec<u32> {
    let n = last - first;
    let step = n.div_ceil(8).max(1);
    let mut b: Vec<u32> = (first..last).step_by(step as usize).collect();
    b.push(last);
    b
}

/// A render with no progress output and no stop request.
pub fn render_quiet(scene: &Scene, settings: &RenderSettings) -> RenderOutput {
    let stop = AtomicBool::new(false);
    render(
        scene,
        settings,
        &Control {
            progress: &|_, _| {},
            stop: &stop,
        },
    )
}
