//! A chunk of camera samples shaded in stages, so that their lights can be chosen and
//! sampled [`LANES`] shading points at a time: the light tree's walks interleaved
//! ([`Selector::select_lanes`]), the light samples of rectangles and spheres under
//! `solid-angle` in SIMD lanes ([`LightLanes`]). Without either (an environment map,
//! one triangle), the stages alone still pay: see [`Staging::new`].
//!
//! Where the estimator runs in stages ([`Estimator::stages`]: `mis` with the balance or
//! power heuristic and any number of light samples, and `light`), the camera packets
//! shade a chunk in up to four passes: every sample's hit and numbers
//! ([`Estimator::begin`], one [`LightJob`] per light sample), the light choices
//! ([`LANES`] jobs at a time where the light tree's walks go together, else made in the
//! first pass), the light samples (those of lights with lanes [`LANES`] at a time),
//! every sample's score and BSDF samples ([`Estimator::finish`]).
//! The estimates are the one-at-a-time ones bit for bit; only the choosing and the light
//! sampling's work is shared.

use glam::Vec2;

use super::packets::{CameraPackets, Pending};
use crate::geometry::SurfaceHit;
use crate::integrator::{Begun, Estimator, LightJob};
use crate::light::select::{LightSelector, Selector};
use crate::light::{KERNELS, LaneJob, LightLanes, LightSample, ShadingPoint};
use crate::math::Spectrum;
use crate::sampling::warp::LANES;
use crate::scene::Scene;

/// What a render shades in stages with: the light lanes, light choices that go
/// together ([`Selector::walks_together`]), both or neither.
pub(super) struct Staging {
    /// The lights sampled [`LANES`] shading points at a time (`None`: every light sample
    /// one at a time).
    lanes: Option<LightLanes>,
    /// Whether the lights are chosen [`LANES`] shading points at a time (else each as
    /// its estimate begins).
    walks: bool,
}

impl Staging {
    /// The staging of a render with `estimator` on `scene`: `None` unless the estimate
    /// runs in stages and the fast paths are on (`--fast-paths off` keeps the
    /// one-at-a-time estimate). Where no light has lanes and the light tree's walks do
    /// not go together (an environment map, one triangle, rectangles under `area`), the
    /// stages still pay: each pass is one short loop over the chunk, whose independent
    /// samples overlap in the processor, though it runs about 5 % more instructions
    /// (1.18× on `envmap_rotated`, 1.03–1.10× on most scenes under `area`, 0.95× on
    /// `legacy_v06` under `area`: BENCHMARKS.md, session 39).
    pub(super) fn new(scene: &Scene, estimator: &Estimator) -> Option<Staging> {
        if !estimator.stages() || !estimator.lights.fast_paths {
            return None;
        }
        let lanes = LightLanes::new(&scene.lights, estimator.lights);
        let walks = estimator.selector.walks_together();
        Some(Staging { lanes, walks })
    }

    /// Whether some light's samples are drawn in lanes.
    #[cfg(test)]
    pub(super) fn has_lanes(&self) -> bool {
        self.lanes.is_some()
    }
}

/// A chunk's estimates between their stages, kept from chunk to chunk so that no chunk
/// allocates.
#[derive(Default)]
pub(super) struct Stages {
    begun: Vec<Begun>,
    /// The light samples of the staged estimates, each with the index in `begun` of its
    /// estimate: each estimate's in the order it drew them
    /// ([`Estimator::staged_light_samples`] each, in the order of `begun`).
    jobs: Vec<(u32, LightJob)>,
    /// For each job, its light sample.
    samples: Vec<Option<LightSample>>,
}

impl Stages {
    /// Shades a chunk's traced samples (`n` pixels, in the order of the one-at-a-time
    /// loop: pixel by pixel, each pixel's samples in increasing index) in stages, and
    /// hands each to `sink`.
    pub(super) fn shade(
        &mut self,
        job: &CameraPackets<'_>,
        staging: &Staging,
        traced: &mut [(Pending, Option<SurfaceHit>)],
        n: usize,
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        // One light sample per estimate, the common case, as a constant: with the count
        // read at run time every estimate ran about 2 % more instructions (callgrind).
        let chunk = (traced, n);
        if job.estimator.staged_light_samples() == 1 {
            self.shade_with::<true>(job, staging, chunk, sink);
        } else {
            self.shade_with::<false>(job, staging, chunk, sink);
        }
    }

    /// [`Stages::shade`] of the chunk `(traced, n)` with one light sample per estimate
    /// (`ONE`) or the estimator's count.
    #[inline(always)]
    fn shade_with<const ONE: bool>(
        &mut self,
        job: &CameraPackets<'_>,
        staging: &Staging,
        (traced, n): (&mut [(Pending, Option<SurfaceHit>)], usize),
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        let (scene, estimator) = (job.scene, job.estimator);
        let per = if ONE {
            1
        } else {
            estimator.staged_light_samples()
        };
        let len = traced.len();
        let order = (0..n).flat_map(move |lane| (lane..len).step_by(n));
        self.begun.clear();
        self.jobs.clear();
        let selector = &estimator.selector;
        for i in order.clone() {
            let (p, hit) = &mut traced[i];
            let k = self.begun.len() as u32;
            let put = |at: &ShadingPoint, mut light: LightJob| {
                if !staging.walks {
                    light.choose(selector.select(at, light.u_select()));
                }
                self.jobs.push((k, light));
            };
            let src = &mut p.sampler;
            let begun = estimator.begin(scene, &p.ray, hit.as_ref(), src, per, put);
            self.begun.push(begun);
        }
        if staging.walks {
            self.choose_lights(selector);
        }
        self.sample_lights(scene, estimator, staging.lanes.as_ref());
        let mut first = 0;
        for (k, i) in order.enumerate() {
            let (p, hit) = &mut traced[i];
            // Each arm hands its estimate on itself: merged into one value first, the
            // estimate went through the stack, whose wide reload stalled on the narrow
            // stores that had just written it.
            match (&self.begun[k], hit) {
                (Begun::Light(staged), Some(hit)) => {
                    let lights = first..first + per;
                    first += per;
                    debug_assert!(
                        self.jobs[lights.clone()]
                            .iter()
                            .all(|&(o, _)| o as usize == k),
                        "the estimate's own light samples"
                    );
                    let jobs = self.jobs[lights.clone()].iter().map(|(_, light)| light);
                    let jobs = jobs.zip(self.samples[lights].iter().copied());
                    let src = &mut p.sampler;
                    let l = estimator.finish(scene, (&p.ray, hit), staged, jobs, src);
                    sink(p.x, p.y, p.film, job.counted(l));
                }
                (Begun::Done(l), _) => sink(p.x, p.y, p.film, job.counted(*l)),
                (Begun::Light(_), None) => unreachable!("a staged estimate has a hit"),
            }
        }
        debug_assert_eq!(first, self.jobs.len(), "every light sample scored");
    }

    /// The light of every job, chosen [`LANES`] at a time.
    fn choose_lights(&mut self, selector: &Selector) {
        let Stages { begun, jobs, .. } = self;
        for jobs in jobs.chunks_mut(LANES) {
            let mut chosen = [None; LANES];
            let chosen = &mut chosen[..jobs.len()];
            let last = jobs.len() - 1;
            // A short batch fills its other lanes with its last job.
            let lanes: [(&ShadingPoint, f32); LANES] = std::array::from_fn(|l| {
                let (owner, light) = &jobs[l.min(last)];
                (staged_at(begun, *owner), light.u_select())
            });
            selector.select_lanes(&lanes[..jobs.len()], chosen);
            for ((_, light), &selection) in jobs.iter_mut().zip(chosen.iter()) {
                light.choose(selection);
            }
        }
    }

    /// The light sample of every job: those of lights with `lanes` [`LANES`] at a time
    /// (batched by kernel), the others one at a time.
    fn sample_lights(&mut self, scene: &Scene, estimator: &Estimator, lanes: Option<&LightLanes>) {
        let Stages {
            begun,
            jobs,
            samples,
        } = self;
        samples.clear();
        samples.resize(jobs.len(), None);
        let mut batch = [[0usize; LANES]; KERNELS];
        let mut waiting = [0; KERNELS];
        for (j, (owner, light)) in jobs.iter().enumerate() {
            let Some(sel) = light.light() else { continue };
            let kernel = lanes.and_then(|l| l.kernel(sel.index));
            if let (Some(lanes), Some(kernel)) = (lanes, kernel) {
                batch[kernel][waiting[kernel]] = j;
                waiting[kernel] += 1;
                if waiting[kernel] == LANES {
                    let stage = (begun.as_slice(), jobs.as_slice());
                    sample_batch(scene, estimator, lanes, stage, &batch[kernel], samples);
                    waiting[kernel] = 0;
                }
            } else {
                let at = staged_at(begun, *owner);
                samples[j] = scene.lights[sel.index].sample(at, light.u_point(), estimator.lights);
            }
        }
        // The short batches left (there are none without lanes).
        let Some(lanes) = lanes else { return };
        for (batch, &waiting) in batch.iter().zip(&waiting) {
            if waiting > 0 {
                let stage = (begun.as_slice(), jobs.as_slice());
                sample_batch(scene, estimator, lanes, stage, &batch[..waiting], samples);
            }
        }
    }
}

/// The shading point of the staged estimate `begun[owner]`.
#[inline(always)]
fn staged_at(begun: &[Begun], owner: u32) -> &ShadingPoint {
    match &begun[owner as usize] {
        Begun::Light(staged) => staged.at(),
        Begun::Done(_) => unreachable!("only staged estimates have light samples"),
    }
}

/// The light samples of the jobs `j` in `batch` (1 to [`LANES`] of them, all of lights
/// with lanes of one kernel) of a chunk's `(begun, jobs)`, into `samples[j]`; a
/// short batch fills its other lanes (with its last job here, with the kernel's first
/// job in [`LightLanes::sample`]) and drops their samples.
fn sample_batch(
    scene: &Scene,
    estimator: &Estimator,
    lanes: &LightLanes,
    (begun, jobs): (&[Begun], &[(u32, LightJob)]),
    batch: &[usize],
    samples: &mut [Option<LightSample>],
) {
    let lane_jobs: [LaneJob; LANES] = std::array::from_fn(|l| {
        let (owner, light) = &jobs[batch[l.min(batch.len() - 1)]];
        let sel = light.light().expect("a light sample in lanes has a light");
        (sel.index, staged_at(begun, *owner), light.u_point())
    });
    lanes.sample(
        &scene.lights,
        estimator.lights,
        &lane_jobs,
        batch.len(),
        |l, ls| {
            samples[batch[l]] = ls;
        },
    );
}
