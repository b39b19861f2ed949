//! A tile's samples, camera rays in packets. The pixels are taken in blocks of
//! [`BLOCK_WIDTH`] × [`BLOCK_HEIGHT`] aligned to the image, and a block's samples in chunks
//! of [`CHUNK`] sample indices: for each index of the chunk, the camera rays of the
//! block's pixels are traced together
//! ([`Geometry::intersect_packet`](crate::geometry::Geometry::intersect_packet)); then
//! each pixel's samples of the chunk are shaded one after another, each estimate going on
//! from its own hit with its own sampler. Neighbouring pixels look almost the same way,
//! so a packet shares most of its traversal.
//!
//! Which rays share a packet depends on the sample index and the pixel alone, never on
//! how the samples are split into rounds, passes (`--pass I/N`), tiles (the render's
//! tiles are whole blocks, see `tile_size`) or threads. That
//! matters because a packet may visit boxes in another order than a ray alone would, and
//! where two primitives are met at the same distance (or within the slab test's rounding
//! margin of a box's entry) the order decides which one is hit: a sample's radiance may
//! then differ from the one-ray path's, but it is the same in every render that draws
//! that sample. (An earlier version packed eight consecutive samples in film order, so the
//! packets changed with the rounds, and a 3-pass render of `mesh_obj` merged to one pixel
//! 16 % away from the single render: two coplanar faces of different materials, met at
//! the same distance.) Each sample draws the same numbers as when traced alone, and every
//! pixel receives its samples in increasing index.
//!
//! Where the estimator runs in stages ([`Estimator::stages`]: `mis` with the balance or
//! power heuristic and one light sample) and some light can be sampled at [`LANES`] shading
//! points at once ([`LightLanes`]: rectangles under `solid-angle`), a chunk is shaded in three
//! passes: every sample's hit and light choice ([`Estimator::begin`]), the light samples
//! (four by four), every sample's score and BSDF samples ([`Estimator::finish`]). The
//! estimates are the one-at-a-time ones bit for bit; only the light sampling's work is
//! shared. On a tree of one node the chunk's camera rays are then traced one at a time.

use std::cell::RefCell;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec2;

use super::{RenderSettings, Tile};
use crate::geometry::bvh::PACKET;
use crate::geometry::{Ray, SurfaceHit};
use crate::integrator::{Begun, Estimator, OptimalPixel};
use crate::light::{LaneJob, LightLanes, LightSample};
use crate::math::Spectrum;
use crate::sampling::warp::LANES;
use crate::sampling::{Sampler, Uniform};
use crate::scene::{Camera, Scene};

/// Samples of a tile, handed out in [`sample_order`].
pub(super) trait TileSamples: Sync {
    /// Samples `samples` of every pixel of `tile` (of an image `width` pixels wide,
    /// streams keyed by `seed`), in [`sample_order`]: `sink(x, y, film position,
    /// radiance)`.
    fn run(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    );
}

/// Width of the pixel blocks whose camera rays share a packet (with [`BLOCK_HEIGHT`], one
/// ray per lane of a [`PACKET`]).
pub(super) const BLOCK_WIDTH: u32 = 4;
/// Height of the pixel blocks whose camera rays share a packet.
pub(super) const BLOCK_HEIGHT: u32 = 2;
const _: () = assert!((BLOCK_WIDTH * BLOCK_HEIGHT) as usize == PACKET);

/// A pixel of a block: (x, y, the key of its sampler streams).
type BlockPixel = (u32, u32, u64);

/// Sample indices per chunk. A pixel's samples of a chunk are shaded one after another:
/// they share their surface, material and lights, which keeps the caches and branch
/// predictors warm (shading index by index across the block instead took 1.6 % more
/// instructions and ran at 0.91–0.95× on the README scene, `mesh_obj` and the
/// 10⁶-triangle mesh).
const CHUNK: u32 = 8;

/// Calls `f(sample indices, block)` for samples `samples` of every pixel of `tile` (of an
/// image `width` pixels wide, streams keyed by `seed`): for each [`BLOCK_WIDTH`] ×
/// [`BLOCK_HEIGHT`] block of the image that the tile covers (blocks aligned to the image,
/// row by row; the tile's part of it, pixels row by row), the samples in chunks of
/// [`CHUNK`] consecutive indices.
#[inline(always)]
fn sample_order(
    (x0, y0, x1, y1): Tile,
    samples: Range<u32>,
    (seed, width): (u64, u32),
    mut f: impl FnMut(Range<u32>, &[BlockPixel]),
) {
    for by in (y0 - y0 % BLOCK_HEIGHT..y1).step_by(BLOCK_HEIGHT as usize) {
        for bx in (x0 - x0 % BLOCK_WIDTH..x1).step_by(BLOCK_WIDTH as usize) {
            let mut block = [(0, 0, 0); PACKET];
            let mut n = 0;
            for y in by.max(y0)..(by + BLOCK_HEIGHT).min(y1) {
                for x in bx.max(x0)..(bx + BLOCK_WIDTH).min(x1) {
                    block[n] = (x, y, Sampler::pixel_key(seed, (y * width + x) as u64));
                    n += 1;
                }
            }
            for start in samples.clone().step_by(CHUNK as usize) {
                f(start..(start + CHUNK).min(samples.end), &block[..n]);
            }
        }
    }
}

/// Calls `f(x, y, pixel key, sample index)` for every sample of [`sample_order`], one at
/// a time: block by block, chunk by chunk, within a chunk pixel by pixel (the order the
/// packet path shades them in).
#[inline(always)]
fn each_sample(
    tile: Tile,
    samples: Range<u32>,
    seed_width: (u64, u32),
    mut f: impl FnMut(u32, u32, u64, u32),
) {
    sample_order(tile, samples, seed_width, |chunk, block| {
        for &(x, y, key) in block {
            for s in chunk.clone() {
                f(x, y, key, s);
            }
        }
    });
}

/// A sample at a time: `f(x, y, pixel key, sample index)` gives the film position and
/// radiance (as the spatial-reuse rounds hand over their finished samples).
pub(super) struct OneByOne<F>(pub F);

impl<F: Fn(u32, u32, u64, u32) -> (Vec2, Spectrum) + Sync> TileSamples for OneByOne<F> {
    fn run(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        each_sample(tile, samples, seed_width, |x, y, key, s| {
            let (p, l) = (self.0)(x, y, key, s);
            sink(x, y, p, l);
        });
    }
}

/// What the camera packets need: the scene, how to sample and estimate, and the counts
/// they keep.
pub(super) struct CameraPackets<'a> {
    pub scene: &'a Scene,
    pub settings: &'a RenderSettings,
    pub camera: &'a Camera,
    pub estimator: &'a Estimator,
    /// Per-pixel optimal-MIS state (`--mis optimal`), else empty.
    pub optimal: &'a [Mutex<OptimalPixel>],
    /// Samples whose radiance was not finite.
    pub invalid: &'a AtomicU64,
    /// The lights sampled [`LANES`] shading points at a time, when the estimator
    /// [`stages`](Estimator::stages) and some light has lanes; else every estimate runs
    /// whole, one at a time.
    pub lanes: Option<&'a LightLanes>,
}

/// Least depth of the scene's BVH (in wide nodes) for which camera rays are traced in
/// packets.
const MIN_PACKET_DEPTH: usize = 2;

/// One sample waiting for its packet: pixel, stream, film position, camera ray.
struct Pending {
    x: u32,
    y: u32,
    sampler: Sampler,
    film: Vec2,
    ray: Ray,
}

impl TileSamples for CameraPackets<'_> {
    fn run(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        // A tree of one node: a packet would save no node tests, only add its set-up.
        let single_rays = self.scene.geometry.bvh().depth() < MIN_PACKET_DEPTH;
        // The stages hold only for what `render` checks before it hands over lanes.
        assert!(
            self.lanes.is_none() || (self.estimator.stages() && self.optimal.is_empty()),
            "light lanes need an estimate in stages without optimal-MIS state"
        );
        if single_rays && self.lanes.is_none() {
            each_sample(tile, samples, seed_width, |x, y, key, s| {
                let mut p = self.start(x, y, key, s);
                let hit = self.scene.geometry.intersect(&p.ray, f32::INFINITY);
                let l = self.radiance(x, y, &p.ray, hit.as_ref(), &mut p.sampler);
                sink(x, y, p.film, l);
            });
            return;
        }
        // A chunk's samples with their camera hits, sample index by sample index (one
        // packet each, or one ray at a time on a tree of one node, where only the staged
        // shading comes here), the block's pixels within each.
        let mut traced: Vec<(Pending, Option<SurfaceHit>)> =
            Vec::with_capacity(CHUNK as usize * PACKET);
        let mut stages = Stages::default();
        sample_order(tile, samples, seed_width, |chunk, block| {
            for s in chunk.clone() {
                let start = traced.len();
                traced.extend(
                    block
                        .iter()
                        .map(|&(x, y, key)| (self.start(x, y, key, s), None)),
                );
                if single_rays {
                    for (p, hit) in &mut traced[start..] {
                        *hit = self.scene.geometry.intersect(&p.ray, f32::INFINITY);
                    }
                } else {
                    self.trace(&mut traced[start..]);
                }
            }
            let n = block.len();
            if let Some(lanes) = self.lanes {
                self.shade_in_stages(lanes, &mut traced, n, &mut stages, sink);
            } else {
                for lane in 0..n {
                    for (p, hit) in traced[lane..].iter_mut().step_by(n) {
                        let l = self.radiance(p.x, p.y, &p.ray, hit.as_ref(), &mut p.sampler);
                        sink(p.x, p.y, p.film, l);
                    }
                }
            }
            traced.clear();
        });
    }
}

impl CameraPackets<'_> {
    /// Sample `s` of pixel (x, y) (pixel key `key`): its stream, after the film position
    /// it draws first, and its camera ray.
    #[inline(always)]
    fn start(&self, x: u32, y: u32, key: u64, s: u32) -> Pending {
        let mut sampler = Sampler::for_pixel(self.settings.sampler, key, s, self.settings.spp);
        let film = Vec2::new(x as f32, y as f32) + sampler.next_2d();
        Pending {
            x,
            y,
            sampler,
            film,
            ray: self.camera.ray(film),
        }
    }

    /// Traces the camera rays of one packet's samples (together when there are several)
    /// and stores each one's closest hit beside it.
    fn trace(&self, packet: &mut [(Pending, Option<SurfaceHit>)]) {
        let geometry = &self.scene.geometry;
        match packet.len() {
            0 => {}
            1 => packet[0].1 = geometry.intersect(&packet[0].0.ray, f32::INFINITY),
            n => {
                let rays = std::array::from_fn(|l| packet[l.min(n - 1)].0.ray);
                let t_max = std::array::from_fn(|l| {
                    if l < n {
                        f32::INFINITY
                    } else {
                        f32::NEG_INFINITY
                    }
                });
                let hits = geometry.intersect_packet(&rays, &t_max);
                for ((_, hit), found) in packet.iter_mut().zip(hits) {
                    *hit = found;
                }
            }
        }
    }

    /// Shades a chunk's traced samples (`n` pixels, in the order of the one-at-a-time
    /// loop: pixel by pixel, each pixel's samples in increasing index) with the estimate
    /// in stages: every sample's first stage, then the light samples, those of lights
    /// with lanes [`LANES`] at a time, then every sample's last stage and its sink. The
    /// estimates are the one-at-a-time ones bit for bit (see [`Estimator::begin`]).
    fn shade_in_stages(
        &self,
        lanes: &LightLanes,
        traced: &mut [(Pending, Option<SurfaceHit>)],
        n: usize,
        stages: &mut Stages,
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        let (scene, estimator) = (self.scene, self.estimator);
        let len = traced.len();
        let order = (0..n).flat_map(move |lane| (lane..len).step_by(n));
        stages.begun.clear();
        for i in order.clone() {
            let (p, hit) = &mut traced[i];
            let begun = estimator.begin(scene, &p.ray, hit.as_ref(), &mut p.sampler);
            stages.begun.push(begun);
        }
        // The light samples: a light with lanes waits in `batch` for three others.
        stages.samples.clear();
        stages.samples.resize(stages.begun.len(), None);
        let mut batch = [0usize; LANES];
        let mut waiting = 0;
        for (k, begun) in stages.begun.iter().enumerate() {
            let Begun::Light(staged) = begun else {
                continue;
            };
            let Some(sel) = staged.light() else { continue };
            if lanes.has(sel.index) {
                batch[waiting] = k;
                waiting += 1;
                if waiting == LANES {
                    let begun = &stages.begun;
                    sample_batch(
                        scene,
                        estimator,
                        lanes,
                        begun,
                        &batch,
                        LANES,
                        &mut stages.samples,
                    );
                    waiting = 0;
                }
            } else {
                let light = &scene.lights[sel.index];
                stages.samples[k] = light.sample(staged.at(), staged.u_point(), estimator.lights);
            }
        }
        if waiting > 0 {
            // The lanes past the last waiting job repeat it, and their samples are dropped.
            let filled: [usize; LANES] = std::array::from_fn(|l| batch[l.min(waiting - 1)]);
            let begun = &stages.begun;
            sample_batch(
                scene,
                estimator,
                lanes,
                begun,
                &filled,
                waiting,
                &mut stages.samples,
            );
        }
        for (k, i) in order.enumerate() {
            let (p, hit) = &mut traced[i];
            let l = match (&stages.begun[k], hit) {
                (Begun::Light(staged), Some(hit)) => {
                    let ls = stages.samples[k];
                    estimator.finish(scene, &p.ray, hit, staged, ls, &mut p.sampler)
                }
                (Begun::Done(l), _) => *l,
                (Begun::Light(_), None) => unreachable!("a staged estimate has a hit"),
            };
            sink(p.x, p.y, p.film, self.counted(l));
        }
    }

    /// The estimate of pixel (x, y)'s sample along camera ray `ray` given its closest hit
    /// (with the pixel's optimal-MIS state under `--mis optimal`); a non-finite estimate
    /// is counted and scored as zero.
    #[inline(always)]
    fn radiance(
        &self,
        x: u32,
        y: u32,
        ray: &Ray,
        hit: Option<&SurfaceHit>,
        sampler: &mut Sampler,
    ) -> Spectrum {
        let (scene, estimator) = (self.scene, self.estimator);
        let l = match self.optimal.get((y * self.camera.width + x) as usize) {
            Some(cell) => {
                let mut guard = cell.lock().unwrap_or_else(|e| e.into_inner());
                let state = RefCell::new(*guard);
                let l = estimator.radiance_from(scene, ray, hit, sampler, Some(&state));
                *guard = state.into_inner();
                l
            }
            None => estimator.radiance_from(scene, ray, hit, sampler, None),
        };
        self.counted(l)
    }

    /// `l`, or zero (counted) when it is not finite.
    #[inline(always)]
    fn counted(&self, l: Spectrum) -> Spectrum {
        if l.is_finite() {
            l
        } else {
            self.invalid.fetch_add(1, Ordering::Relaxed);
            Spectrum::ZERO
        }
    }
}

/// A chunk's estimates between their stages, kept from chunk to chunk so that no chunk
/// allocates.
#[derive(Default)]
struct Stages {
    begun: Vec<Begun>,
    samples: Vec<Option<LightSample>>,
}

/// The light samples of the staged estimates `begun[batch[l]]`, whose lights all have
/// lanes, into `samples[batch[l]]`, for the first `used` lanes (the others are padding).
#[inline]
fn sample_batch(
    scene: &Scene,
    estimator: &Estimator,
    lanes: &LightLanes,
    begun: &[Begun],
    batch: &[usize; LANES],
    used: usize,
    samples: &mut [Option<LightSample>],
) {
    let jobs: [LaneJob; LANES] = std::array::from_fn(|l| match &begun[batch[l]] {
        Begun::Light(staged) => {
            let sel = staged.light().expect("a staged light sample has a light");
            (sel.index, staged.at(), staged.u_point())
        }
        Begun::Done(_) => unreachable!("only staged light samples are batched"),
    });
    let drawn = lanes.sample(&scene.lights, estimator.lights, &jobs, used);
    for (l, ls) in drawn.into_iter().enumerate().take(used) {
        samples[batch[l]] = ls;
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::integrator::{EstimatorKind, MisHeuristic};
    use crate::scene::load;

    /// Every sample of a tile as (x, y, film position bits, radiance bits).
    type Trace = Vec<(u32, u32, [u32; 2], [u32; 3])>;

    fn trace(
        job: &impl TileSamples,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
    ) -> Trace {
        let mut out = Vec::new();
        job.run(tile, samples, seed_width, &mut |x, y, p, l| {
            out.push((
                x,
                y,
                p.to_array().map(f32::to_bits),
                l.to_array().map(f32::to_bits),
            ));
        });
        out
    }

    /// Camera packets give every sample the radiance the one-ray-at-a-time path gives it
    /// (the pre-packet renderer's sample, written out here), in the same order, on
    /// scenes of rectangles, spheres and meshes, with a count of samples that is not a
    /// multiple of the packet and with optimal MIS's per-pixel state; and on two scenes
    /// whose BVH is one node, whose rays are traced one at a time. Where the estimate runs
    /// in stages with light lanes, with them and without.
    #[test]
    fn packets_give_the_samples_of_single_rays() {
        // (scene, optimal MIS, height of the tile's centre as a share of the image's)
        for (spec, optimal_mis, at) in [
            ("builtin:assignment", false, 0.5),
            ("builtin:materials", false, 0.5),
            ("tests/scenes/mesh_obj.xml", false, 0.5),
            ("builtin:veach-mis", true, 0.8),
            ("tests/scenes/tent_point.xml", false, 0.85),
            ("tests/scenes/microfacet_conductor.xml", false, 0.75),
        ] {
            let scene = load(spec).expect("scene");
            // Every scene but the last two traces packets; they trace one ray at a time.
            let one_node = spec.ends_with("tent_point.xml") || spec.contains("microfacet_c");
            let depth = scene.geometry.bvh().depth();
            assert_eq!(depth < MIN_PACKET_DEPTH, one_node, "{spec}: depth {depth}");
            let mut settings = RenderSettings::for_scene(&scene);
            if optimal_mis {
                settings.estimator = EstimatorKind::Mis;
                settings.mis.heuristic = MisHeuristic::Optimal;
            }
            let camera = settings.camera(&scene);
            let estimator = Estimator::new(&scene, settings.estimator, settings.light_select)
                .with_mis(settings.mis)
                .with_light_strategy(settings.light_strategy());
            let pixels = (camera.width * camera.height) as usize;
            let states = |n: usize| -> Vec<Mutex<OptimalPixel>> {
                (0..n)
                    .map(|_| Mutex::new(OptimalPixel::default()))
                    .collect()
            };
            let (optimal_a, optimal_b) = if optimal_mis {
                (states(pixels), states(pixels))
            } else {
                (Vec::new(), Vec::new())
            };
            let invalid = AtomicU64::new(0);
            // The estimates in stages with light samples in lanes where they apply (all
            // but optimal MIS and the point lights), and whole.
            let lanes = if estimator.stages() && !optimal_mis {
                LightLanes::new(&scene.lights, estimator.lights)
            } else {
                None
            };
            assert_eq!(
                lanes.is_some(),
                !optimal_mis && !spec.contains("tent"),
                "{spec}"
            );
            let packets = CameraPackets {
                scene: &scene,
                settings: &settings,
                camera: &camera,
                estimator: &estimator,
                optimal: &optimal_a,
                invalid: &invalid,
                lanes: lanes.as_ref(),
            };
            let single = OneByOne(|x: u32, y: u32, key: u64, s: u32| {
                let mut sampler = Sampler::for_pixel(settings.sampler, key, s, settings.spp);
                let p = Vec2::new(x as f32, y as f32) + sampler.next_2d();
                let ray = camera.ray(p);
                let l = match optimal_b.get((y * camera.width + x) as usize) {
                    Some(cell) => {
                        let mut guard = cell.lock().expect("unpoisoned");
                        let state = RefCell::new(*guard);
                        let l = estimator.radiance_in(&scene, &ray, &mut sampler, Some(&state));
                        *guard = state.into_inner();
                        l
                    }
                    None => estimator.radiance(&scene, &ray, &mut sampler),
                };
                (p, if l.is_finite() { l } else { Spectrum::ZERO })
            });
            let (w, h) = (camera.width, camera.height);
            let yc = (h as f32 * at) as u32;
            let tile = (w / 2 - 3, yc - 2, w / 2 + 3, yc + 2);
            let key = (settings.seed, w);
            // 5 samples per pixel; the tile cuts the image's blocks, so packets are partial.
            let a = trace(&packets, tile, 3..8, key);
            let b = trace(&single, tile, 3..8, key);
            assert_eq!(a.len(), 24 * 5);
            assert!(a.iter().any(|s| s.3 != [0; 3]), "{spec}: all black");
            assert_eq!(a, b, "{spec}");
            if lanes.is_some() {
                let whole = CameraPackets {
                    lanes: None,
                    ..packets
                };
                assert_eq!(trace(&whole, tile, 3..8, key), b, "{spec} without lanes");
            }
        }
    }

    /// Each pixel's samples (film position and radiance bits), in the order it got them.
    type PerPixel = BTreeMap<(u32, u32), Vec<([u32; 2], [u32; 3])>>;

    /// A trace's samples, pixel by pixel.
    fn per_pixel(trace: Trace) -> PerPixel {
        let mut out = BTreeMap::new();
        for (x, y, p, l) in trace {
            out.entry((x, y)).or_insert_with(Vec::new).push((p, l));
        }
        out
    }

    /// A sample's radiance does not depend on how the samples are split into rounds or
    /// passes, or the image into tiles: its packet holds the same rays every time. The
    /// case is the one where packets of eight consecutive samples in film order made a
    /// 3-pass render merge 16 % away from the single render at one pixel (`mesh_obj` at
    /// 32 × 24, 12 spp, seed 5).
    #[test]
    fn samples_do_not_depend_on_rounds_passes_or_tiles() {
        let scene = load("tests/scenes/mesh_obj.xml").expect("scene");
        let mut settings = RenderSettings::for_scene(&scene);
        settings.resolution = Some((32, 24));
        settings.seed = 5;
        settings.spp = 12;
        let camera = settings.camera(&scene);
        let estimator = Estimator::new(&scene, settings.estimator, settings.light_select)
            .with_mis(settings.mis)
            .with_light_strategy(settings.light_strategy());
        let invalid = AtomicU64::new(0);
        let lanes = LightLanes::new(&scene.lights, estimator.lights);
        assert!(lanes.is_some());
        // With the light lanes (the estimate in stages) and without.
        for lanes in [lanes.as_ref(), None] {
            let packets = CameraPackets {
                scene: &scene,
                settings: &settings,
                camera: &camera,
                estimator: &estimator,
                optimal: &[],
                invalid: &invalid,
                lanes,
            };
            let (w, h) = (camera.width, camera.height);
            let key = (settings.seed, w);
            // The samples in rounds as the single render takes them (two samples per
            // round) and as the 3-pass render does (one per round), over the render's
            // 4 × 4 tiles; and all in one piece over the whole image.
            let in_rounds = |rounds: &[Range<u32>], tiles: &[Tile]| {
                let mut out = BTreeMap::new();
                for samples in rounds {
                    for &tile in tiles {
                        let trace = trace(&packets, tile, samples.clone(), key);
                        for (pixel, list) in per_pixel(trace) {
                            out.entry(pixel).or_insert_with(Vec::new).extend(list);
                        }
                    }
                }
                out
            };
            let tiles = super::super::tiles(w, h, 4);
            let single: Vec<Range<u32>> = (0..6).map(|r| 2 * r..2 * r + 2).collect();
            let passes: Vec<Range<u32>> = (0..12).map(|s| s..s + 1).collect();
            let all_at_once = std::slice::from_ref(&(0..12));
            let whole = in_rounds(all_at_once, &[(0, 0, w, h)]);
            assert_eq!(whole, in_rounds(&single, &tiles));
            assert_eq!(whole, in_rounds(&passes, &tiles));
            assert_eq!(whole.len(), (w * h) as usize);
            assert!(whole.values().all(|list| list.len() == 12));
        }
    }
}
