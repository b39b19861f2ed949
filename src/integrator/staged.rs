//! The `mis` and `light` estimates in stages, so that a renderer can choose and sample
//! the lights of many shading points together ([`crate::light::LightLanes`]):
//! [`Estimator::begin`] turns the camera ray's hit to the side it is seen from and draws
//! the light sample's numbers; the caller chooses the light with [`Staged::u_select`]
//! (for many points together: [`crate::light::select::Selector::select_lanes`]), hands
//! it to [`Staged::choose`] and samples it at [`Staged::at`] with [`Staged::u_point`];
//! [`Estimator::finish`] scores the light sample and (for `mis`) draws the BSDF samples.
//! Every number is drawn in the order [`Estimator::radiance_from`] draws it, so the
//! estimate is the same bit for bit.
//!
//! Stages apply to the balance and power heuristics with one light sample (the default
//! and Mitsuba's `direct`) and to the `light` estimator (its one light sample drawn
//! the same way, scored alone by [`super::light::score`]), without resampling;
//! [`Estimator::stages`] says when.

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
/// its light sample.
pub enum Begun {
    /// The camera ray escaped, or met a surface from behind: nothing left to sample.
    Done(Spectrum),
    /// Waiting for its light to be chosen ([`Staged::choose`]) and sampled at
    /// [`Staged::at`].
    Light(Staged),
}

/// An estimate between [`Estimator::begin`] and [`Estimator::finish`]: small (it waits
/// in a list with a chunk's others), so [`Estimator::finish`] orients the hit again and
/// finds its material rather than keep them here.
pub struct Staged {
    emitted: Spectrum,
    at: ShadingPoint,
    draw: LightDraw,
    u_select: f32,
    /// Whether [`Staged::choose`] has recorded the light.
    chosen: bool,
}

impl Staged {
    /// The light to sample and its selection probability (`None`: no light), once
    /// [`Staged::choose`] has recorded it.
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

    /// Records the light chosen at [`Staged::at`] with [`Staged::u_select`] by the
    /// estimator's selector (`None`: no light can contribute).
    #[inline]
    pub fn choose(&mut self, selection: Option<Selection>) {
        self.draw.selection = selection;
        self.chosen = true;
    }

    /// The shading point to sample the light at.
    #[inline]
    pub fn at(&self) -> &ShadingPoint {
        &self.at
    }

    /// The two numbers that place the light's point.
    #[inline]
    pub fn u_point(&self) -> Vec2 {
        self.draw.u_point
    }
}

impl Estimator {
    /// Whether [`Estimator::begin`] and [`Estimator::finish`] apply: the `light`
    /// estimator, and the `mis` estimator with the balance or power heuristic and one
    /// light sample; neither with resampling.
    pub fn stages(&self) -> bool {
        let staged_kind = match self.kind {
            EstimatorKind::Light => true,
            EstimatorKind::Mis => {
                matches!(
                    self.mis.heuristic,
                    MisHeuristic::Balance | MisHeuristic::Power
                ) && self.mis.light_samples == 1
            }
            _ => false,
        };
        staged_kind && self.ris.is_none()
    }

    /// The first stage of [`Estimator::radiance_from`] along camera ray `ray` with
    /// closest hit `hit` (see the module doc), which leaves the light to be chosen;
    /// only when [`Estimator::stages`].
    #[inline(always)]
    pub fn begin(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: Option<&SurfaceHit>,
        src: &mut impl Uniform,
    ) -> Begun {
        debug_assert!(self.stages());
        let Some(hit) = hit else {
            return Begun::Done(scene.escaped(ray.d.normalize()));
        };
        let w_out: Vec3 = -ray.d.normalize();
        let emitted = emitted_at(scene, hit, w_out);
        let Some((hit, _)) = oriented(scene, hit, w_out) else {
            return Begun::Done(emitted + Spectrum::ZERO);
        };
        let at = shading_point(&hit);
        // The numbers `mis::draw_light` draws; the light is chosen later.
        let (u_select, u_point) = mis::light_numbers(src);
        let draw = LightDraw {
            selection: None,
            u_point,
        };
        Begun::Light(Staged {
            emitted,
            at,
            draw,
            u_select,
            chosen: false,
        })
    }

    /// The last stage, for the same `ray` and `hit` as [`Estimator::begin`], given the
    /// light chosen ([`Staged::choose`]) and the sample `ls` of `staged`'s light at its
    /// shading point (`scene.lights[i].sample(staged.at(), staged.u_point(),
    /// self.lights)`, or `None` without a light), drawing
    /// on from `src` where [`Estimator::begin`] left it. Always inlined (called, it
    /// returned the estimate through memory).
    #[inline(always)]
    pub fn finish(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: &SurfaceHit,
        staged: &Staged,
        ls: Option<LightSample>,
        src: &mut impl Uniform,
    ) -> Spectrum {
        let w_out = -ray.d.normalize();
        let sh = Shading::at(scene, hit, w_out).expect("begin found the hit seen from the front");
        let ctx = self.context(scene, &sh.at, &sh.hit, &sh.material, sh.w_out);
        debug_assert!(
            staged.chosen,
            "the light is chosen before the estimate finishes"
        );
        let reflected = if self.kind == EstimatorKind::Light {
            light::score(&ctx, staged.draw.selection, ls)
        } else {
            mis::finish(&ctx, self.mis, &staged.draw, ls, src)
        };
        staged.emitted + reflected
    }
}
