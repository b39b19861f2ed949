//! The `mis` and `light` estimates in stages, so that a renderer can choose and sample
//! the lights of many shading points together ([`crate::light::LightLanes`]):
//! [`Estimator::begin`] turns the camera ray's hit to the side it is seen from and draws
//! the numbers of each light sample, one [`LightJob`] per sample; the caller chooses
//! each job's light with [`LightJob::u_select`] (for many points together:
//! [`crate::light::select::Selector::select_lanes`]), hands it to [`LightJob::choose`]
//! and samples it at [`Staged::at`] with [`LightJob::u_point`]; [`Estimator::finish`]
//! scores the light samples and (for `mis`) draws the BSDF samples. Every number is
//! drawn in the order [`Estimator::radiance_from`] draws it, so the estimate is the same
//! bit for bit.
//!
//! Stages apply to the balance and power heuristics with any number of light samples
//! (one is the default and Mitsuba's `direct`; each sample draws its three numbers and
//! nothing else, so they can all be drawn first) and to the `light` estimator (its one
//! light sample drawn the same way, scored alone by [`super::light::score`]), without
//! resampling; [`Estimator::stages`] says when.

use glam::{Vec2, Vec3};

use super::mis::{self, LightDraw};
use super::{
    Estimator, EstimatorKind, MisHeuristic, Shading, emitted_at, light, oriented, shading_point,
};
use crate::geometry::{Ray, SurfaceHit};
use crate::light::select::Selection;
use crate::light::{LightSample, ShadingPoint};
use crate::math::Spectrum;
use crate::sampling::Uniform;
use crate::scene::Scene;

/// What [`Estimator::begin`] leaves: an estimate already complete, or one waiting for
/// its light samples.
pub enum Begun {
    /// The camera ray escaped, or met a surface from behind: nothing left to sample.
    Done(Spectrum),
    /// Waiting for the lights of its [`LightJob`]s to be chosen and sampled at
    /// [`Staged::at`].
    Light(Staged),
}

/// An estimate between [`Estimator::begin`] and [`Estimator::finish`]: small (it waits
/// in a list with a chunk's others), so [`Estimator::finish`] orients the hit again and
/// finds its material rather than keep them here. Its light samples wait as
/// [`LightJob`]s beside it.
pub struct Staged {
    emitted: Spectrum,
    at: ShadingPoint,
}

impl Staged {
    /// The shading point to sample the lights at.
    #[inline]
    pub fn at(&self) -> &ShadingPoint {
        &self.at
    }
}

/// One light sample of a [`Staged`] estimate, waiting for its light: the numbers that
/// choose it and place its point, then the light chosen.
#[derive(Clone, Copy)]
pub struct LightJob {
    draw: LightDraw,
    u_select: f32,
    /// Whether [`LightJob::choose`] has recorded the light.
    chosen: bool,
}

impl LightJob {
    /// The light to sample and its selection probability (`None`: no light), once
    /// [`LightJob::choose`] has recorded it.
    #[inline]
    pub fn light(&self) -> Option<Selection> {
        debug_assert!(self.chosen, "the light is chosen before it is asked for");
        self.draw.selection
    }

    /// The number that chooses the light.
    #[inline]
    pub fn u_select(&self) -> f32 {
        self.u_select
    }

    /// Records the light chosen at the estimate's [`Staged::at`] with
    /// [`LightJob::u_select`] by the estimator's selector (`None`: no light can
    /// contribute).
    #[inline]
    pub fn choose(&mut self, selection: Option<Selection>) {
        self.draw.selection = selection;
        self.chosen = true;
    }

    /// The two numbers that place the light's point.
    #[inline]
    pub fn u_point(&self) -> Vec2 {
        self.draw.u_point
    }
}

impl Estimator {
    /// Whether [`Estimator::begin`] and [`Estimator::finish`] apply: the `light`
    /// estimator, and the `mis` estimator with the balance or power heuristic and at
    /// least one light sample; neither with resampling.
    pub fn stages(&self) -> bool {
        let staged_kind = match self.kind {
            EstimatorKind::Light => true,
            EstimatorKind::Mis => {
                matches!(
                    self.mis.heuristic,
                    MisHeuristic::Balance | MisHeuristic::Power
                ) && self.mis.light_samples >= 1
            }
            _ => false,
        };
        staged_kind && self.ris.is_none()
    }

    /// The light samples of one estimate in stages: the [`LightJob`]s
    /// [`Estimator::begin`] leaves for a [`Begun::Light`] (`mis`'s light samples, one
    /// for `light`).
    #[inline]
    pub fn staged_light_samples(&self) -> usize {
        match self.kind {
            EstimatorKind::Mis => self.mis.light_samples as usize,
            _ => 1,
        }
    }

    /// The first stage of [`Estimator::radiance_from`] along camera ray `ray` with
    /// closest hit `hit` (see the module doc), which leaves the lights to be chosen:
    /// for a [`Begun::Light`], hands the numbers of its `per` light samples (the
    /// [`Estimator::staged_light_samples`], passed in so that a caller can make the
    /// common one a constant) to `put` with its shading point, in the order they are
    /// drawn; only when [`Estimator::stages`].
    #[inline(always)]
    pub fn begin(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: Option<&SurfaceHit>,
        src: &mut impl Uniform,
        per: usize,
        mut put: impl FnMut(&ShadingPoint, LightJob),
    ) -> Begun {
        debug_assert!(self.stages());
        debug_assert_eq!(per, self.staged_light_samples());
        let Some(hit) = hit else {
            return Begun::Done(scene.escaped(ray.d.normalize()));
        };
        let w_out: Vec3 = -ray.d.normalize();
        let emitted = emitted_at(scene, hit, w_out);
        let Some((hit, _)) = oriented(scene, hit, w_out) else {
            return Begun::Done(emitted + Spectrum::ZERO);
        };
        let at = shading_point(&hit);
        // The numbers `mis::draw_light` draws for each light sample, one sample after
        // another (nothing else is drawn between them); the lights are chosen later.
        for _ in 0..per {
            let (u_select, u_point) = mis::light_numbers(src);
            let draw = LightDraw {
                selection: None,
                u_point,
            };
            let job = LightJob {
                draw,
                u_select,
                chosen: false,
            };
            put(&at, job);
        }
        Begun::Light(Staged { emitted, at })
    }

    /// The last stage, for the same `ray` and `hit` as [`Estimator::begin`], given the
    /// estimate's light `jobs` (the ones [`Estimator::begin`] handed on, in their order,
    /// each with its light chosen: [`LightJob::choose`]) with their light samples at
    /// `staged`'s shading point (`scene.lights[i].sample(staged.at(), job.u_point(),
    /// self.lights)`, or `None` without a light), drawing on from `src` where
    /// [`Estimator::begin`] left it. Always inlined (called, it returned the estimate
    /// through memory).
    #[inline(always)]
    pub fn finish<'j>(
        &self,
        scene: &Scene,
        (ray, hit): (&Ray, &SurfaceHit),
        staged: &Staged,
        jobs: impl Iterator<Item = (&'j LightJob, Option<LightSample>)>,
        src: &mut impl Uniform,
    ) -> Spectrum {
        let w_out = -ray.d.normalize();
        let sh = Shading::at(scene, hit, w_out).expect("begin found the hit seen from the front");
        let ctx = self.context(scene, &sh.at, &sh.hit, &sh.material, sh.w_out);
        let mut drawn = jobs.map(|(job, ls)| {
            debug_assert!(
                job.chosen,
                "the light is chosen before the estimate finishes"
            );
            (&job.draw, ls)
        });
        let reflected = if self.kind == EstimatorKind::Light {
            let (draw, ls) = drawn.next().expect("one light sample");
            debug_assert!(drawn.next().is_none(), "the light estimate has one sample");
            light::score(&ctx, draw.selection, ls)
        } else {
            mis::finish(&ctx, self.mis, drawn, src)
        };
        staged.emitted + reflected
    }
}
