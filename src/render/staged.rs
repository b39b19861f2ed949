//! A chunk of camera samples shaded in stages, so that their lights can be chosen and
//! sampled [`LANES`] shading points at a time: the light tree's walks interleaved
//! ([`Selector::select_lanes`]), the light samples of rectangles and spheres under
//! `solid-angle` in SIMD lanes ([`LightLanes`]). Without either (an environment map,
//! one triangle), the stages alone still pay: see [`Staging::new`].
//!
//! Where the estimator runs in stages ([`Estimator::stages`]: `mis` with the balance or
//! power heuristic and one light sample, and `light`), the camera packets shade a chunk
//! in up to four passes: every sample's hit and numbers ([`Estimator::begin`]), the
//! light choices ([`LANES`] at a time where the light tree's walks go together, else
//! made in the first pass), the light samples (those of lights with lanes [`LANES`] at a
//! time), every sample's score and BSDF samples ([`Estimator::finish`]).
//! The estimates are the one-at-a-time ones bit for bit; only the choosing and the light
//! sampling's work is shared.

use glam::Vec2;

use super::packets::{CameraPackets, Pending};
use crate::geometry::SurfaceHit;
use crate::integrator::{Begun, Estimator};
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
    /// (1.18× on `envmap_rotated`, 1.03–1.09× on most scenes under `area`, 0.95× on
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
        let (scene, estimator) = (job.scene, job.estimator);
        let len = traced.len();
        let order = (0..n).flat_map(move |lane| (lane..len).step_by(n));
        self.begun.clear();
        let selector = &estimator.selector;
        for i in order.clone() {
            let (p, hit) = &mut traced[i];
            let mut begun = estimator.begin(scene, &p.ray, hit.as_ref(), &mut p.sampler);
            if let (Begun::Light(staged), false) = (&mut begun, staging.walks) {
                staged.choose(selector.select(staged.at(), staged.u_select()));
            }
            self.begun.push(begun);
        }
        if staging.walks {
            self.choose_lights(selector);
        }
        self.sample_lights(scene, estimator, staging.lanes.as_ref());
        for (k, i) in order.enumerate() {
            let (p, hit) = &mut traced[i];
            // Each arm hands its estimate on itself: merged into one value first, the
            // estimate went through the stack, whose wide reload stalled on the narrow
            // stores that had just written it.
            match (&self.begun[k], hit) {
                (Begun::Light(staged), Some(hit)) => {
                    let ls = self.samples[k];
                    let l = estimator.finish(scene, &p.ray, hit, staged, ls, &mut p.sampler);
                    sink(p.x, p.y, p.film, job.counted(l));
                }
                (Begun::Done(l), _) => sink(p.x, p.y, p.film, job.counted(*l)),
                (Begun::Light(_), None) => unreachable!("a staged estimate has a hit"),
            }
        }
    }

    /// The light of every staged estimate, chosen [`LANES`] at a time.
    fn choose_lights(&mut self, selector: &Selector) {
        let begun = &mut self.begun;
        let mut batch = [0usize; LANES];
        let mut waiting = 0;
        for k in 0..begun.len() {
            if let Begun::Light(_) = begun[k] {
                batch[waiting] = k;
                waiting += 1;
                if waiting == LANES {
                    choose_batch(selector, begun, &batch);
                    waiting = 0;
                }
            }
        }
        if waiting > 0 {
            choose_batch(selector, begun, &batch[..waiting]);
        }
    }

    /// The light sample of every staged estimate: those of lights with `lanes`
    /// [`LANES`] at a time, batched by kernel (rectangles with rectangles, spheres
    /// with spheres), the others (all, without lanes) one by one.
    fn sample_lights(&mut self, scene: &Scene, estimator: &Estimator, lanes: Option<&LightLanes>) {
        let Stages { begun, samples } = self;
        samples.clear();
        samples.resize(begun.len(), None);
        let mut batch = [[0usize; LANES]; KERNELS];
        let mut waiting = [0; KERNELS];
        for (k, staged) in begun.iter().enumerate() {
            let Begun::Light(staged) = staged else {
                continue;
            };
            let Some(sel) = staged.light() else { continue };
            let kernel = lanes.and_then(|l| l.kernel(sel.index));
            if let (Some(lanes), Some(kernel)) = (lanes, kernel) {
                batch[kernel][waiting[kernel]] = k;
                waiting[kernel] += 1;
                if waiting[kernel] == LANES {
                    sample_batch(scene, estimator, lanes, begun, &batch[kernel], samples);
                    waiting[kernel] = 0;
                }
            } else {
                let light = &scene.lights[sel.index];
                samples[k] = light.sample(staged.at(), staged.u_point(), estimator.lights);
            }
        }
        // The short batches left (there are none without lanes).
        let Some(lanes) = lanes else { return };
        for (batch, &waiting) in batch.iter().zip(&waiting) {
            if waiting > 0 {
                sample_batch(scene, estimator, lanes, begun, &batch[..waiting], samples);
            }
        }
    }
}

/// The lights of the staged estimates `begun[k]`, for `k` in `batch` (1 to [`LANES`] of
/// them, all staged), chosen together.
fn choose_batch(selector: &Selector, begun: &mut [Begun], batch: &[usize]) {
    let mut chosen = [None; LANES];
    let chosen = &mut chosen[..batch.len()];
    {
        let jobs: [(&ShadingPoint, f32); LANES] =
            std::array::from_fn(|l| match &begun[batch[l.min(batch.len() - 1)]] {
                Begun::Light(staged) => (staged.at(), staged.u_select()),
                Begun::Done(_) => unreachable!("only staged estimates choose lights"),
            });
        selector.select_lanes(&jobs[..batch.len()], chosen);
    }
    for (&k, &selection) in batch.iter().zip(chosen.iter()) {
        if let Begun::Light(staged) = &mut begun[k] {
            staged.choose(selection);
        }
    }
}

/// The light samples of the staged estimates `begun[k]`, for `k` in `batch` (1 to
/// [`LANES`] of them, all of lights with lanes of one kernel), into `samples[k]`; a short
/// batch fills its other lanes (with its last job here, with the kernel's first job in
/// [`LightLanes::sample`]) and drops their samples.
fn sample_batch(
    scene: &Scene,
    estimator: &Estimator,
    lanes: &LightLanes,
    begun: &[Begun],
    batch: &[usize],
    samples: &mut [Option<LightSample>],
) {
    let jobs: [LaneJob; LANES] =
        std::array::from_fn(|l| match &begun[batch[l.min(batch.len() - 1)]] {
            Begun::Light(staged) => {
                let sel = staged.light().expect("a staged light sample has a light");
                (sel.index, staged.at(), staged.u_point())
            }
            Begun::Done(_) => unreachable!("only staged light samples are batched"),
        });
    lanes.sample(
        &scene.lights,
        estimator.lights,
        &jobs,
        batch.len(),
        |l, ls| {
            samples[batch[l]] = ls;
        },
    );
}
