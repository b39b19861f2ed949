//! Rendering: tiles in parallel (rayon), one sampler stream per (seed, pixel, sample),
//! rounds of samples so a stop request still leaves a whole image, and a progress bar.

mod frustum;
mod packets;
mod settings;
mod spatial;
mod splat;
mod staged;

pub use crate::settings::{Pass, SampleBlock};
pub use settings::RenderSettings;

use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::image::{Film, PixelStats};
use crate::integrator::{Estimator, EstimatorKind, MisHeuristic, OptimalPixel};
use crate::scene::Scene;
use packets::TileSamples;

/// Side of a square tile in pixels, on images large enough to give `MIN_TILES` (64) of them.
pub const TILE: u32 = 16;

/// The fewest tiles a round should have: each round ends at a barrier, so with a few
/// large tiles one thread waits for the other's last tile (2-thread CPU use of
/// `constant_env`, 9 tiles of 16², and `path_include`, 12: 183 and 189 %; with 4² tiles,
/// 196 and 197 %).
const MIN_TILES: u32 = 64;

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
    /// Shadow rays traced (light and MIS estimators).
    pub shadow_rays: u64,
    /// The samples rendered, as blocks of sample indices under a seed (one block per
    /// render; merged outputs list all of theirs).
    pub samples: Vec<SampleBlock>,
}

impl RenderOutput {
    /// `next` (a render of further samples of the same image, with its own streams)
    /// added to `total`: films merged by Chan's rule, spp, invalid samples and sample
    /// blocks summed, the stop flag of the later render. The time is left to the caller
    /// (zero here).
    pub fn merge(total: Option<RenderOutput>, next: RenderOutput) -> RenderOutput {
        match total {
            None => next,
            Some(t) if next.spp == 0 => RenderOutput {
                stopped: next.stopped,
                ..t
            },
            Some(mut t) => RenderOutput {
                samples: {
                    t.samples.extend(next.samples);
                    t.samples
                },
                film: t.film.merge(&next.film).unwrap_or(t.film),
                time: Duration::ZERO,
                spp: t.spp + next.spp,
                invalid_samples: t.invalid_samples + next.invalid_samples,
                stopped: next.stopped,
                shadow_rays: t.shadow_rays + next.shadow_rays,
            },
        }
    }
}

/// Hooks a render reports to and listens to.
pub struct Control<'a> {
    /// Called with (samples done, samples total) after each round.
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    /// Set to stop after the current round.
    pub stop: &'a AtomicBool,
    /// Called with the film after each round (a live view), when given. A render given
    /// one keeps eight rounds where it has the samples, so that the view refines; without
    /// one, a short render takes fewer, longer rounds (a splatted image may then differ
    /// in its last bits, see `round_boundaries`).
    pub frame: Option<&'a (dyn Fn(&Film) + Sync)>,
}

impl<'a> Control<'a> {
    /// No progress report and no live view; stops when `stop` is set.
    pub fn quiet(stop: &'a AtomicBool) -> Control<'a> {
        Control {
            progress: &|_, _| {},
            stop,
            frame: None,
        }
    }
}

/// What one render of an image hands on to the next render of the same image (the
/// rounds of a timed render, a reference's passes): under optimal MIS, every pixel's α
/// and technique moments, so that the next call starts from all the samples so far
/// rather than again from the balance heuristic. α only ever comes from samples of
/// earlier rounds, as within one render, so carrying it keeps each round unbiased.
#[derive(Debug, Default)]
pub struct Carry {
    /// The image size the state is for.
    size: (u32, u32),
    /// Per pixel, row by row (empty until an optimal-MIS render fills it).
    optimal: Vec<Mutex<OptimalPixel>>,
}

impl Carry {
    /// True until a render that has something to hand on (optimal MIS) has run with it.
    pub fn is_empty(&self) -> bool {
        self.optimal.is_empty()
    }
}

/// `veach-mis` at `w` × `h` under optimal MIS: the scene of the tests of [`Carry`].
#[cfg(test)]
pub(crate) fn optimal_mis_veach(w: u32, h: u32) -> (Scene, RenderSettings) {
    let scene = crate::scene::load("builtin:veach-mis").expect("scene");
    let mut settings = RenderSettings::for_scene(&scene);
    settings.resolution = Some((w, h));
    settings.estimator = EstimatorKind::Mis;
    settings.mis.heuristic = MisHeuristic::Optimal;
    (scene, settings)
}

/// Renders `scene` with `settings`.
pub fn render(scene: &Scene, settings: &RenderSettings, control: &Control<'_>) -> RenderOutput {
    render_carrying(scene, settings, control, &mut Carry::default())
}

/// [`render`], starting from and leaving in `carry` what the next render of the same
/// image may continue from. A `carry` filled for another image size starts afresh.
pub fn render_carrying(
    scene: &Scene,
    settings: &RenderSettings,
    control: &Control<'_>,
    carry: &mut Carry,
) -> RenderOutput {
    let camera = settings.camera(scene);
    let (w, h) = (camera.width, camera.height);
    // The light strategy travels with the estimator to every light it asks.
    let estimator = Estimator::new(scene, settings.estimator, settings.light_select)
        .with_mis(settings.mis)
        .with_light_strategy(scene, settings.light_strategy())
        .with_ris_candidates(settings.ris_candidates);
    let (first, last) = settings.pass.sample_range(settings.spp);
    let (first, last) = (first + settings.first_sample, last + settings.first_sample);
    let mut film = Film::new(w, h);
    // Splatted tiles merge in tile order, so their size is part of the image's rounding:
    // it depends on the image's size alone, never on the thread count.
    let tiles = tiles(w, h, tile_size(w, h));
    let invalid = AtomicU64::new(0);
    let start = Instant::now();
    // Optimal MIS learns its weights round by round (the first is the balance heuristic,
    // unless `carry` holds earlier rounds), and a live view shows a render refine round
    // by round: both keep eight rounds.
    let optimal_mis =
        settings.estimator == EstimatorKind::Mis && settings.mis.heuristic == MisHeuristic::Optimal;
    let eighths = optimal_mis || control.frame.is_some();
    let rounds = round_boundaries(first, last, w as u64 * h as u64, eighths);
    let total = (last - first) as u64 * (w * h) as u64;
    let mut done = first;
    let mut stopped = false;
    // Optimal MIS keeps per pixel the α of earlier rounds and the moments of all samples
    // (each pixel's samples run on one thread at a time: the locks are uncontended).
    if optimal_mis && (carry.size != (w, h) || carry.optimal.is_empty()) {
        carry.size = (w, h);
        carry.optimal = (0..w as usize * h as usize)
            .map(|_| Mutex::new(OptimalPixel::default()))
            .collect();
    }
    let optimal: &[Mutex<OptimalPixel>] = if optimal_mis { &carry.optimal } else { &[] };
    // The estimates in stages, lights chosen and sampled `LANES` shading points at a
    // time where they can be.
    let staging = staged::Staging::new(scene, &estimator);
    // Blocks of pixels whose camera rays all miss the scene skip the traversal, and
    // without an environment the whole sample but its film position (not under
    // `--ris-spatial`, whose rounds trace their own camera rays).
    let cull = frustum::FrustumCull::new(&camera, &scene.geometry.bvh().cut(frustum::TOP_BOXES));
    for window in rounds.windows(2) {
        let (s0, s1) = (window[0], window[1]);
        let job = packets::CameraPackets {
            scene,
            settings,
            camera: &camera,
            estimator: &estimator,
            optimal,
            invalid: &invalid,
            staging: staging.as_ref(),
            cull: cull.as_ref(),
            positions: !settings.filter.is_pixel_box(),
        };
        if settings.ris_spatial > 0 {
            let job = spatial::Job {
                scene,
                settings,
                camera: &camera,
                estimator: &estimator,
                invalid: &invalid,
            };
            spatial::round(&mut film, &tiles, s0..s1, &job);
        } else if settings.filter.is_pixel_box() {
            round_pixel_box(&mut film, &tiles, s0..s1, settings.seed, &job);
        } else {
            splat::round_splatted(
                &mut film,
                &tiles,
                s0..s1,
                settings.seed,
                settings.filter,
                &job,
            );
        }
        for cell in optimal {
            cell.lock().unwrap_or_else(|e| e.into_inner()).next_round();
        }
        done = s1;
        (control.progress)((s1 - first) as u64 * (w * h) as u64, total);
        if let Some(frame) = control.frame {
            frame(&film);
        }
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
        shadow_rays: estimator.shadow_rays.get(),
        samples: vec![SampleBlock {
            seed: settings.seed,
            first,
            last: done,
        }],
    }
}

/// One round with the one-pixel box filter: each pixel continues its own Welford
/// statistics with its samples `samples`.
fn round_pixel_box(
    film: &mut Film,
    tiles: &[Tile],
    samples: Range<u32>,
    seed: u64,
    job: &impl TileSamples,
) {
    let w = film.width;
    let results: Vec<Vec<PixelStats>> = tiles
        .par_iter()
        .map(|&(x0, y0, x1, y1)| {
            let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
            for y in y0..y1 {
                for x in x0..x1 {
                    out.push(*film.pixel(x, y));
                }
            }
            let tile = (x0, y0, x1, y1);
            job.run(tile, samples.clone(), (seed, w), &mut |x, y, _, l| {
                out[((y - y0) * (x1 - x0) + x - x0) as usize].add(l);
            });
            out
        })
        .collect();
    for (&(x0, y0, x1, _), tile) in tiles.iter().zip(results) {
        for (i, stats) in tile.into_iter().enumerate() {
            let (x, y) = (x0 + i as u32 % (x1 - x0), y0 + i as u32 / (x1 - x0));
            film.pixels[(y * w + x) as usize] = stats;
        }
    }
}

/// A rectangle of pixels (x0, y0, x1, y1), half-open.
type Tile = (u32, u32, u32, u32);

/// The smallest tile side: one camera-ray packet's block wide.
const MIN_TILE: u32 = packets::BLOCK_WIDTH;

// Every tile side the halving gives (TILE, TILE/2, …, MIN_TILE) is a whole number of
// packet blocks in both directions, so tiles never split a block: which rays share a
// packet stays independent of the tiling.
const _: () = assert!(
    TILE.is_power_of_two()
        && MIN_TILE.is_power_of_two()
        && TILE >= MIN_TILE
        && MIN_TILE.is_multiple_of(packets::BLOCK_WIDTH)
        && MIN_TILE.is_multiple_of(packets::BLOCK_HEIGHT)
);

/// The side of the tiles of a `w`×`h` image: [`TILE`], halved (down to one packet block,
/// 4) while the image would have fewer than `MIN_TILES` tiles, so that small images keep
/// both threads busy up to each round's barrier.
fn tile_size(w: u32, h: u32) -> u32 {
    let mut size = TILE;
    while size > MIN_TILE && w.div_ceil(size) * h.div_ceil(size) < MIN_TILES {
        size /= 2;
    }
    size
}

/// Tiles (x0, y0, x1, y1) of `size` pixels covering the image, row by row.
fn tiles(w: u32, h: u32, size: u32) -> Vec<Tile> {
    let mut t = Vec::new();
    for y in (0..h).step_by(size as usize) {
        for x in (0..w).step_by(size as usize) {
            t.push((x, y, (x + size).min(w), (y + size).min(h)));
        }
    }
    t
}

/// Samples (pixels × samples per pixel) a round aims at where the render has them:
/// about 0.1 s of the README scene's work on 2 cores (heavier scenes take a few times
/// longer), so a stop request and the progress bar still answer within a fraction of a
/// second.
const MIN_ROUND_SAMPLES: u64 = 1 << 20;

/// Sample indices at which the rounds of samples `first..last` of an image of `pixels`
/// pixels start: at most eight rounds, of ⌈n/8⌉ samples per pixel each (n = last −
/// first). With `eighths`, exactly that. Otherwise each round is also of at least
/// [`MIN_ROUND_SAMPLES`] samples where the render has them, rounded down to whole
/// chunks of [`packets::CHUNK`] samples per pixel (so between half of it and all of
/// it), and a round of more than one chunk is rounded up to whole chunks: a round
/// shades each pixel's samples in chunks of consecutive ones, which share caches and
/// branch predictors, and each round ends at a barrier. At 16 spp, eight rounds of
/// 2 spp ran the README's render 1.12× slower than two of 8 (BENCHMARKS.md, session
/// 22). Pixel-box images do not depend on the rounds (except under optimal MIS, which
/// asks for `eighths`); splatted ones do, in their last bits, through the order of
/// their sums (so a splatted render with a live view, which asks for `eighths`, may
/// differ in its last bits from one without). The rounds depend on the image, the
/// sample range and `eighths` alone, never on the threads or the clock.
fn round_boundaries(first: u32, last: u32, pixels: u64, eighths: bool) -> Vec<u32> {
    let n = last - first;
    let eighth = n.div_ceil(8).max(1);
    let step = if eighths {
        eighth
    } else {
        let chunk = packets::CHUNK;
        // At most 2²⁰ (pixels ≥ 1): no overflow below.
        let floor = (MIN_ROUND_SAMPLES / pixels.max(1)) as u32;
        let floor = if floor > chunk {
            floor - floor % chunk
        } else {
            floor.max(1)
        };
        let step = eighth.max(floor);
        if step > chunk {
            step.next_multiple_of(chunk)
        } else {
            step
        }
    };
    let mut b: Vec<u32> = (first..last).step_by(step as usize).collect();
    b.push(last);
    b
}

/// A render with no progress output and no stop request.
pub fn render_quiet(scene: &Scene, settings: &RenderSettings) -> RenderOutput {
    let stop = AtomicBool::new(false);
    render(scene, settings, &Control::quiet(&stop))
}

/// The bits of every pixel mean of `film` (tests compare images bit for bit).
#[cfg(test)]
pub(crate) fn mean_bits(film: &Film) -> Vec<[u32; 3]> {
    film.pixels
        .iter()
        .map(|p| p.mean.to_array().map(f32::to_bits))
        .collect()
}

#[cfg(test)]
mod tests;
