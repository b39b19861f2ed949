//! A tile's samples, camera rays in packets: the samples are taken in the order the film
//! accumulates them (row by row, pixel by pixel, sample by sample), and every
//! [`PACKET`] consecutive ones have their camera rays traced together
//! ([`Geometry::intersect_packet`](crate::geometry::Geometry::intersect_packet)); each
//! estimate then goes on from its own hit with its own sampler, in the same order. A
//! pixel's samples, and neighbouring pixels, look almost the same way, so the packet
//! shares most of its traversal. Each sample draws the same numbers as when traced alone,
//! so the image is the same, up to which of two primitives a camera ray meets at exactly
//! the same distance.

use std::cell::RefCell;
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec2;

use super::{RenderSettings, Tile};
use crate::geometry::bvh::PACKET;
use crate::geometry::{Ray, SurfaceHit};
use crate::integrator::{Estimator, OptimalPixel};
use crate::math::Spectrum;
use crate::sampling::{Sampler, Uniform};
use crate::scene::{Camera, Scene};

/// Samples of a tile, handed out in film order.
pub(super) trait TileSamples: Sync {
    /// Samples `samples` of every pixel of `tile` (of an image `width` pixels wide,
    /// streams keyed by `seed`), in film order: `sink(x, y, film position, radiance)`.
    fn run(
        &self,
        tile: Tile,
        samples: Range<u32>,
        seed_width: (u64, u32),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    );
}

/// Calls `f(x, y, pixel key, sample index)` for samples `samples` of every pixel of
/// `tile` (of an image `width` pixels wide, streams keyed by `seed`) in film order.
#[inline(always)]
fn film_order(
    (x0, y0, x1, y1): Tile,
    samples: Range<u32>,
    (seed, width): (u64, u32),
    mut f: impl FnMut(u32, u32, u64, u32),
) {
    for y in y0..y1 {
        for x in x0..x1 {
            let key = Sampler::pixel_key(seed, (y * width + x) as u64);
            for s in samples.clone() {
                f(x, y, key, s);
            }
        }
    }
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
        film_order(tile, samples, seed_width, |x, y, key, s| {
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
        if self.scene.geometry.bvh().depth() < MIN_PACKET_DEPTH {
            // A tree of one node: a packet would save no node tests, only add its set-up.
            film_order(tile, samples, seed_width, |x, y, key, s| {
                let mut p = self.start(x, y, key, s);
                let hit = self.scene.geometry.intersect(&p.ray, f32::INFINITY);
                let l = self.radiance(x, y, &p.ray, hit.as_ref(), &mut p.sampler);
                sink(x, y, p.film, l);
            });
            return;
        }
        let mut pending: Vec<Pending> = Vec::with_capacity(PACKET);
        film_order(tile, samples, seed_width, |x, y, key, s| {
            pending.push(self.start(x, y, key, s));
            if pending.len() == PACKET {
                self.shade(&mut pending, sink);
            }
        });
        self.shade(&mut pending, sink);
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

    /// Traces the pending samples' camera rays (together when there are several) and
    /// hands their estimates to `sink` in order; `pending` is left empty.
    fn shade(&self, pending: &mut Vec<Pending>, sink: &mut impl FnMut(u32, u32, Vec2, Spectrum)) {
        let geometry = &self.scene.geometry;
        let hits = match pending.len() {
            0 => return,
            1 => {
                let mut hits = [None; PACKET];
                hits[0] = geometry.intersect(&pending[0].ray, f32::INFINITY);
                hits
            }
            n => {
                let rays = std::array::from_fn(|l| pending[l.min(n - 1)].ray);
                let t_max = std::array::from_fn(|l| {
                    if l < n {
                        f32::INFINITY
                    } else {
                        f32::NEG_INFINITY
                    }
                });
                geometry.intersect_packet(&rays, &t_max)
            }
        };
        for (mut p, hit) in pending.drain(..).zip(hits) {
            let l = self.radiance(p.x, p.y, &p.ray, hit.as_ref(), &mut p.sampler);
            sink(p.x, p.y, p.film, l);
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
        if l.is_finite() {
            l
        } else {
            self.invalid.fetch_add(1, Ordering::Relaxed);
            Spectrum::ZERO
        }
    }
}

#[cfg(test)]
mod tests {
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
    /// multiple of the packet and with optimal MIS's per-pixel state; and on a scene whose
    /// BVH is one node, through the single-ray path.
    #[test]
    fn packets_give_the_samples_of_single_rays() {
        // (scene, optimal MIS, height of the tile's centre as a share of the image's)
        for (spec, optimal_mis, at) in [
            ("builtin:assignment", false, 0.5),
            ("builtin:materials", false, 0.5),
            ("tests/scenes/mesh_obj.xml", false, 0.5),
            ("builtin:veach-mis", true, 0.8),
            ("tests/scenes/tent_point.xml", false, 0.85),
        ] {
            let scene = load(spec).expect("scene");
            // Every scene but the last goes through packets; the last keeps single rays.
            let one_node = spec.ends_with("tent_point.xml");
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
            let packets = CameraPackets {
                scene: &scene,
                settings: &settings,
                camera: &camera,
                estimator: &estimator,
                optimal: &optimal_a,
                invalid: &invalid,
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
            // 5 samples per pixel: packets straddle pixels and the last one is partial.
            let a = trace(&packets, tile, 3..8, key);
            let b = trace(&single, tile, 3..8, key);
            assert_eq!(a.len(), 24 * 5);
            assert!(a.iter().any(|s| s.3 != [0; 3]), "{spec}: all black");
            assert_eq!(a, b, "{spec}");
        }
    }
}
