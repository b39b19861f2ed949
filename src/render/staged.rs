//! A chunk of camera samples shaded in stages, so that their light samples can be drawn
//! [`LANES`] shading points at a time ([`LightLanes`]: rectangles and spheres under
//! `solid-angle`).
//!
//! Where the estimator runs in stages ([`Estimator::stages`]: `mis` with the balance or
//! power heuristic and one light sample, and `light`), the camera packets shade a chunk
//! in three passes: every sample's hit and light choice ([`Estimator::begin`]), the
//! light samples (those of lights with lanes [`LANES`] at a time), every sample's score
//! and BSDF samples ([`Estimator::finish`]). The estimates are the one-at-a-time ones
//! bit for bit; only the light sampling's work is shared.

use glam::Vec2;

use super::packets::{CameraPackets, Pending};
use crate::geometry::SurfaceHit;
use crate::integrator::{Begun, Estimator};
use crate::light::{KERNELS, LaneJob, LightLanes, LightSample};
use crate::math::Spectrum;
use crate::sampling::warp::LANES;
use crate::scene::Scene;

/// The light lanes of a render with `estimator` on `scene`: `None` unless the estimate
/// runs in stages and some light has lanes.
pub(super) fn light_lanes(scene: &Scene, estimator: &Estimator) -> Option<LightLanes> {
    if estimator.stages() {
        LightLanes::new(&scene.lights, estimator.lights)
    } else {
        None
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
        lanes: &LightLanes,
        traced: &mut [(Pending, Option<SurfaceHit>)],
        n: usize,
        sink: &mut impl FnMut(u32, u32, Vec2, Spectrum),
    ) {
        let (scene, estimator) = (job.scene, job.estimator);
        let len = traced.len();
        let order = (0..n).flat_map(move |lane| (lane..len).step_by(n));
        self.begun.clear();
        for i in order.clone() {
            let (p, hit) = &mut traced[i];
            let begun = estimator.begin(scene, &p.ray, hit.as_ref(), &mut p.sampler);
            self.begun.push(begun);
        }
        self.sample_lights(scene, estimator, lanes);
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

    /// The light sample of every staged estimate: those of lights with lanes
    /// [`LANES`] at a time, batched by kernel (rectangles with rectangles, spheres
    /// with spheres), the others one by one.
    fn sample_lights(&mut self, scene: &Scene, estimator: &Estimator, lanes: &LightLanes) {
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
            if let Some(kernel) = lanes.kernel(sel.index) {
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
        for (batch, &waiting) in batch.iter().zip(&waiting) {
            if waiting > 0 {
                sample_batch(scene, estimator, lanes, begun, &batch[..waiting], samples);
            }
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
