//! Rounds of a render with spatial reuse of RIS reservoirs (`--ris-spatial K`): every
//! sample index is shaded in two passes over the whole image, the first filling each
//! pixel's reservoirs at its primary hit, the second combining them with those of K
//! neighbouring pixels ([`crate::integrator::Reuse`] has the estimator).

use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec2;
use rayon::prelude::*;

use super::packets::OneByOne;
use super::splat::round_splatted;
use super::{RenderSettings, Tile, round_pixel_box};
use crate::image::Film;
use crate::integrator::{Estimator, Reuse, SpatialReservoir, SpatialSurface};
use crate::math::Spectrum;
use crate::sampling::warp::square_to_uniform_disk_concentric;
use crate::sampling::{Sampler, Uniform};
use crate::scene::{Camera, Scene};
use crate::settings::MAX_RIS_SPATIAL;

/// Neighbours whose shading normals differ by more than this angle's cosine (25°) or
/// whose depth differs by more than [`MAX_DEPTH_RATIO`] are not reused: their samples
/// rarely suit the pixel (the thresholds of Bitterli et al. 2020). Choosing neighbours by
/// their primary hits never biases the estimate, which is unbiased given every pixel's hit.
const MIN_NORMAL_COS: f32 = 0.906;
/// Largest relative depth difference of a reused neighbour.
const MAX_DEPTH_RATIO: f32 = 0.1;

/// One pixel's first pass.
struct Primary {
    /// Film position of the camera sample.
    film: Vec2,
    /// Radiance seen directly (emission or background).
    emitted: Spectrum,
    /// The sample's stream, continued by the second pass.
    sampler: Sampler,
    /// The surface to shade, if the ray met one that reflects towards the camera.
    surface: Option<SpatialSurface>,
}

/// What a spatial round needs besides the film.
pub(super) struct Job<'a> {
    pub scene: &'a Scene,
    pub settings: &'a RenderSettings,
    pub camera: &'a Camera,
    pub estimator: &'a Estimator,
    pub invalid: &'a AtomicU64,
}

/// Renders samples `samples` of every pixel into `film`, one sample index at a time.
pub(super) fn round(film: &mut Film, tiles: &[Tile], samples: Range<u32>, job: &Job<'_>) {
    let (w, h) = (film.width as usize, film.height as usize);
    let per_pixel = job.estimator.spatial_reservoirs();
    let mut reservoirs = vec![SpatialReservoir::default(); w * h * per_pixel];
    let mut results = vec![(Vec2::ZERO, Spectrum::ZERO); w * h];
    // Every pixel's first pass, overwritten in place at each sample index.
    let mut primaries: Vec<Option<Primary>> = (0..w * h).map(|_| None).collect();
    for s in samples {
        first_pass(job, s, w, &mut primaries, &mut reservoirs, per_pixel);
        results.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                *out = second_pass(job, &primaries, &reservoirs, per_pixel, (x, y), (w, h));
            }
        });
        let result =
            OneByOne(|x: u32, y: u32, _: u64, _: u32| results[y as usize * w + x as usize]);
        let settings = job.settings;
        if settings.filter.is_pixel_box() {
            round_pixel_box(film, tiles, s..s + 1, settings.seed, &result);
        } else {
            round_splatted(
                film,
                tiles,
                s..s + 1,
                settings.seed,
                settings.filter,
                &result,
            );
        }
    }
}

/// Primary hits and reservoirs of sample `s` of every pixel, row by row in parallel.
fn first_pass(
    job: &Job<'_>,
    s: u32,
    w: usize,
    primaries: &mut [Option<Primary>],
    reservoirs: &mut [SpatialReservoir],
    per_pixel: usize,
) {
    let settings = job.settings;
    primaries
        .par_chunks_mut(w)
        .zip(reservoirs.par_chunks_mut(w * per_pixel))
        .enumerate()
        .for_each(|(y, (row, row_reservoirs))| {
            for (x, (out, r)) in row
                .iter_mut()
                .zip(row_reservoirs.chunks_mut(per_pixel))
                .enumerate()
            {
                let key = Sampler::pixel_key(settings.seed, (y * w + x) as u64);
                let mut sampler = Sampler::for_pixel(settings.sampler, key, s, settings.spp);
                let film = Vec2::new(x as f32, y as f32) + sampler.next_2d();
                let ray = job.camera.ray(film);
                let (emitted, surface) =
                    job.estimator
                        .spatial_primary(job.scene, &ray, &mut sampler, r);
                *out = Some(Primary {
                    film,
                    emitted,
                    sampler,
                    surface,
                });
            }
        });
}

/// The sample of pixel `(x, y)`: its film position and radiance, its direct light
/// combined from its reservoirs and those of up to K neighbours in a disk around it.
fn second_pass(
    job: &Job<'_>,
    primaries: &[Option<Primary>],
    reservoirs: &[SpatialReservoir],
    per_pixel: usize,
    (x, y): (usize, usize),
    (w, h): (usize, usize),
) -> (Vec2, Spectrum) {
    let primary = |j: usize| {
        primaries[j]
            .as_ref()
            .expect("the first pass fills every pixel")
    };
    let i = y * w + x;
    let primary_i = primary(i);
    let Some(surface) = &primary_i.surface else {
        return finite(job, primary_i.film, primary_i.emitted);
    };
    let mut sampler = primary_i.sampler.clone();
    let reuse = |j: usize| Reuse {
        surface: primary(j).surface.as_ref().expect("a surface"),
        reservoirs: &reservoirs[j * per_pixel..(j + 1) * per_pixel],
    };
    let own = reuse(i);
    let mut neighbours = [own; MAX_RIS_SPATIAL as usize];
    let mut count = 0;
    let radius = job.settings.ris_radius as f32;
    for _ in 0..job.settings.ris_spatial.min(MAX_RIS_SPATIAL) {
        let d = square_to_uniform_disk_concentric(sampler.next_2d()) * radius;
        let nx = (x as f32 + 0.5 + d.x).floor();
        let ny = (y as f32 + 0.5 + d.y).floor();
        if !(nx >= 0.0 && ny >= 0.0 && nx < w as f32 && ny < h as f32) {
            continue;
        }
        let j = ny as usize * w + nx as usize;
        let Some(other) = &primary(j).surface else {
            continue;
        };
        let similar = other.normal().dot(surface.normal()) >= MIN_NORMAL_COS
            && (other.depth() - surface.depth()).abs() <= MAX_DEPTH_RATIO * surface.depth();
        if j != i && similar {
            neighbours[count] = reuse(j);
            count += 1;
        }
    }
    let direct = job
        .estimator
        .spatial_direct(job.scene, own, &neighbours[..count], &mut sampler);
    finite(job, primary_i.film, primary_i.emitted + direct)
}

/// The sample as the film takes it: non-finite radiance is counted and scored as zero.
fn finite(job: &Job<'_>, film: Vec2, l: Spectrum) -> (Vec2, Spectrum) {
    if l.is_finite() {
        (film, l)
    } else {
        job.invalid.fetch_add(1, Ordering::Relaxed);
        (film, Spectrum::ZERO)
    }
}
