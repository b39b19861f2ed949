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
//! the same distance.) Each sample draws the same numbers as when traced alone (but for
//! the culled samples below that draw none), and every pixel receives its samples in
//! increasing index.
//!
//! A block through whose pixels the camera sees none of the boxes at the top of the
//! scene's BVH ([`FrustumCull`]) traces none of its camera rays: their hits are `None`,
//! as the traversal would have found. In a scene without an environment such samples
//! bring no light at all: no camera ray is made, and the film position is drawn only
//! for a filter that uses it.
//!
//! Where the estimator runs in stages and the fast paths are on, a chunk is shaded in
//! stages instead (see [`super::staged`] and its `Staging::new`); on a tree
//! of one node, or in a scene tested without a tree
//! ([`Geometry::is_flat`](crate::geometry::Geometry::is_flat)), its camera rays are then
//! traced one at a time.

mod ahead;
mod order;

use std::cell::RefCell;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec2;

use super::frustum::FrustumCull;
use super::staged::{Stages, Staging};
use super::{RenderSettings, Tile};
use crate::geometry::bvh::PACKET;
use crate::geometry::{Ray, SurfaceHit};
use crate::integrator::{Estimator, OptimalPixel};
use crate::math::Spectrum;
use crate::sampling::sobol::CHUNK_LANES;
use crate::sampling::{Sampler, SamplerKind, Uniform};
use crate::scene::{Camera, Scene};
use ahead::{DrawsAhead, Nothing, SobolPoints, StrataCells, row_of};
pub(super) use order::{BLOCK_HEIGHT, BLOCK_WIDTH, CHUNK};
use order::{BlockPixel, each_sample, sample_order};

/// Samples of a tile, handed out in [`sample_order`].
pub(super) trait TileSamples: Sync {
    /// Samples `samples` of every pixel of `tile` (of an image `width` pixels wide,
    /// streams keyed by `seed`), in [`sample_order`]: `sink(x, y, film position,
    /// radiance)`. (Where [`CameraPackets::positions`] is false, a sample that surely
    /// sees nothing may come with its pixel's centre instead of its own position.)
    fn run(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    );
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
        // Only the pixel's key is handed on: streams without hashed seeds.
        let keys_only = (SamplerKind::Independent, 0);
        each_sample(tile, samples, seed_width, keys_only, |x, y, streams, s| {
            let (p, l) = (self.0)(x, y, streams.key(), s);
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
    /// What the estimates are shaded in stages with ([`Staging`]), when the estimator
    /// [`stages`](Estimator::stages) and the fast paths are on; else every estimate runs
    /// whole, one at a time.
    pub staging: Option<&'a Staging>,
    /// Where on the film the camera may see the scene (its top BVH boxes): the camera
    /// rays of a block of pixels that sees none of it are not traced (`None`: every ray
    /// is traced).
    pub cull: Option<&'a FrustumCull>,
    /// Whether the sink uses film positions (every filter but the one-pixel box, whose
    /// samples go to their own pixel whatever their position). Where it does not, the
    /// samples of a block that sees nothing in a scene without an environment are
    /// handed on with their pixel's centre instead of a drawn position.
    pub positions: bool,
}

/// Least depth of the scene's BVH (in wide nodes) for which camera rays are traced in
/// packets.
const MIN_PACKET_DEPTH: usize = 2;

/// One sample waiting for its packet: pixel, stream, film position, camera ray.
pub(super) struct Pending {
    pub x: u32,
    pub y: u32,
    pub sampler: Sampler,
    pub film: Vec2,
    pub ray: Ray,
}

impl TileSamples for CameraPackets<'_> {
    fn run(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        // Compiled once per sampler, each computing only its own numbers ahead (the
        // independent sampler's draws still test its `pointed`, which is 0).
        match self.settings.sampler {
            SamplerKind::Sobol => self.run_sampled::<SobolPoints>(tile, samples, seed_width, sink),
            SamplerKind::Stratified => {
                self.run_sampled::<StrataCells>(tile, samples, seed_width, sink)
            }
            SamplerKind::Independent => {
                self.run_sampled::<Nothing>(tile, samples, seed_width, sink)
            }
        }
    }
}

impl CameraPackets<'_> {
    /// [`TileSamples::run`], with what every chunk's first dimensions draw computed
    /// together as `A` does.
    #[inline(always)]
    fn run_sampled<A: DrawsAhead>(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        // A tree of one node: a packet would save no node tests, only add its set-up;
        // nor in a scene tested without a tree, where a ray is one pass over the blocks.
        let geometry = &self.scene.geometry;
        let single_rays = geometry.bvh().depth() < MIN_PACKET_DEPTH || geometry.is_flat();
        // Staging comes only with an estimate in stages (see `Staging::new`).
        assert!(
            self.staging.is_none() || self.estimator.stages(),
            "staging needs an estimate in stages"
        );
        let kind = (self.settings.sampler, self.settings.spp);
        if single_rays && self.staging.is_none() {
            // `each_sample`'s order, with the block's culling decided once per chunk.
            sample_order(tile, samples, seed_width, kind, |chunk, block| {
                let misses = self.misses(block);
                if misses && self.scene.environment.is_none() {
                    return self.dark::<A>(chunk, block, sink);
                }
                for pixel @ (x, y, streams) in block {
                    let rows = A::chunk(streams, chunk.start, chunk.len());
                    for s in chunk.clone() {
                        let row = row_of(&rows, chunk.start, s);
                        let mut p = self.start::<A>(pixel, s, row);
                        let hit = if misses {
                            None
                        } else {
                            self.scene.geometry.intersect(&p.ray, f32::INFINITY)
                        };
                        let l = self.radiance(*x, *y, &p.ray, hit.as_ref(), &mut p.sampler);
                        sink(*x, *y, p.film, l);
                    }
                }
            });
            return;
        }
        // A chunk's samples with their camera hits, sample index by sample index (one
        // packet each, or one ray at a time where `single_rays`, where only the staged
        // shading comes here; none for a culled block, which comes here only in a scene
        // with an environment), the block's pixels within each.
        let mut traced: Vec<(Pending, Option<SurfaceHit>)> =
            Vec::with_capacity(CHUNK as usize * PACKET);
        let mut stages = Stages::default();
        let mut rows: [Option<[A::Row; CHUNK_LANES]>; PACKET] = [None; PACKET];
        sample_order(tile, samples, seed_width, kind, |chunk, block| {
            let misses = self.misses(block);
            if misses && self.scene.environment.is_none() {
                return self.dark::<A>(chunk, block, sink);
            }
            // What the chunk's first dimensions draw, pixel by pixel.
            for (r, (_, _, streams)) in rows.iter_mut().zip(block) {
                *r = A::chunk(streams, chunk.start, chunk.len());
            }
            for s in chunk.clone() {
                let start = traced.len();
                traced.extend(block.iter().zip(&rows).map(|(pixel, r)| {
                    (self.start::<A>(pixel, s, row_of(r, chunk.start, s)), None)
                }));
                // A block that surely misses leaves every hit `None` (the environment's
                // light comes from `radiance`).
                if misses {
                    continue;
                }
                if single_rays {
                    for (p, hit) in &mut traced[start..] {
                        *hit = self.scene.geometry.intersect(&p.ray, f32::INFINITY);
                    }
                } else {
                    self.trace(&mut traced[start..]);
                }
            }
            let n = block.len();
            if let Some(staging) = self.staging {
                stages.shade(self, staging, &mut traced, n, sink);
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

    /// Sample `s` of `pixel` (its row `ahead` of its chunk's numbers drawn ahead, if
    /// any): its stream, after the film position it draws first, and its camera ray.
    #[inline(always)]
    fn start<A: DrawsAhead>(&self, pixel: &BlockPixel, s: u32, ahead: Option<&A::Row>) -> Pending {
        let (x, y, _) = *pixel;
        let (sampler, film) = self.film_position::<A>(pixel, s, ahead);
        Pending {
            x,
            y,
            sampler,
            film,
            ray: self.camera.ray(film),
        }
    }

    /// Sample `s` of pixel `(x, y, streams)` (its row `ahead` of its chunk's numbers
    /// drawn ahead, if any): its stream and the film position it draws first.
    #[inline(always)]
    fn film_position<A: DrawsAhead>(
        &self,
        (x, y, streams): &BlockPixel,
        s: u32,
        ahead: Option<&A::Row>,
    ) -> (Sampler, Vec2) {
        let kind = (self.settings.sampler, self.settings.spp);
        let mut sampler = A::sampler(streams, s, kind, ahead);
        let film = Vec2::new(*x as f32, *y as f32) + sampler.next_2d();
        (sampler, film)
    }

    /// Hands on samples `chunk` of a block that sees nothing, in a scene without an
    /// environment, in [`each_sample`]'s order: every radiance is zero (what an escaped
    /// ray brings), and no camera ray is made. The film positions are drawn only where
    /// the sink uses them ([`CameraPackets::positions`]); otherwise each sample goes
    /// with its pixel's centre.
    fn dark<A: DrawsAhead>(
        &self,
        chunk: Range<u32>,
        block: &[BlockPixel],
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        for pixel @ (x, y, streams) in block {
            let rows = match self.positions {
                true => A::chunk(streams, chunk.start, chunk.len()),
                false => None,
            };
            for s in chunk.clone() {
                let film = if self.positions {
                    self.film_position::<A>(pixel, s, row_of(&rows, chunk.start, s))
                        .1
                } else {
                    Vec2::new(*x as f32 + 0.5, *y as f32 + 0.5)
                };
                sink(*x, *y, film, Spectrum::ZERO);
            }
        }
    }

    /// Whether every camera ray of `block`'s pixels surely misses the scene (film
    /// positions of pixel (x, y) lie in [x, x + 1] × [y, y + 1]).
    #[inline]
    fn misses(&self, block: &[BlockPixel]) -> bool {
        let (Some(cull), Some(first)) = (self.cull, block.first()) else {
            return false;
        };
        let (mut x0, mut y0, mut x1, mut y1) = (first.0, first.1, first.0, first.1);
        for (x, y, _) in block {
            (x0, y0) = (x0.min(*x), y0.min(*y));
            (x1, y1) = (x1.max(*x), y1.max(*y));
        }
        cull.misses((x0 as f64, y0 as f64), (x1 as f64 + 1.0, y1 as f64 + 1.0))
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
    pub(super) fn counted(&self, l: Spectrum) -> Spectrum {
        if l.is_finite() {
            l
        } else {
            self.invalid.fetch_add(1, Ordering::Relaxed);
            Spectrum::ZERO
        }
    }
}

#[cfg(test)]
mod tests;
