//! Direct-lighting estimators: one radiance sample per call of L_out(x, ω_out) =
//! ∫ f · cos θ · L_in dω (directional form) or ∫ f · G · V · Le dA (area form).
//!
//! Directional estimators draw ω and trace it to find an emitter; the light estimator
//! draws a point on a light and traces one shadow ray.

mod directional;
mod light;
pub mod mis;
pub mod probe;
mod ris;
mod shadow_rays;
mod spatial;
mod staged;

pub use crate::settings::{DEFAULT_RIS_CANDIDATES, MAX_RIS_CANDIDATES};

pub use mis::{MisHeuristic, MisSettings, OptimalPixel, TechniqueMoments};
pub use probe::{Probe, ProbeSample};
pub use shadow_rays::ShadowRays;
pub use spatial::{Reuse, SpatialReservoir, SpatialSurface};
pub use staged::{Begun, LightJob, Staged};

use std::borrow::Cow;
use std::cell::RefCell;

use glam::Vec3;

use crate::bsdf::{Bsdf, Material};
use crate::geometry::{NO_LIGHT, Ray, SurfaceHit};
use crate::light::select::{LightSelect, Selector, silent_lights};
use crate::light::{LightSample, LightStrategy, ShadingPoint};
use crate::math::{Frame, Spectrum};
use crate::sampling::Uniform;
use crate::scene::Scene;

pub use crate::settings::EstimatorKind;

/// A direct-lighting estimator bound to a scene: the strategy and the light selector.
#[derive(Clone, Debug)]
pub struct Estimator {
    /// The strategy.
    pub kind: EstimatorKind,
    /// Chooses a light for the light and MIS estimators.
    pub selector: Selector,
    /// Which selector that is (rebuilt when the light strategy changes what lights draw).
    select: LightSelect,
    /// Whether `selector` leaves out lights that draw nothing under `lights`.
    selector_excludes: bool,
    /// Whether some light draws samples under `lights` (false when every light draws
    /// none, e.g. a compensated constant sky alone): one-sample MIS then always takes
    /// the BSDF technique.
    lights_sample: bool,
    /// Sample counts and weighting of the MIS estimator.
    pub mis: MisSettings,
    /// How every light is sampled (per-shape strategy, environment compensation).
    pub lights: LightStrategy,
    /// Candidates per light sample under resampled importance sampling (light selection
    /// `ris`); `None` for the other selectors.
    pub ris: Option<u32>,
    /// Shadow rays traced so far (light and MIS estimators).
    pub shadow_rays: ShadowRays,
    /// Whether a ray can reach an emitter (an area light or the environment): false when
    /// every light is a delta light, and then BSDF-sampled rays, which can only score by
    /// reaching one, contribute exactly zero and are not traced.
    emitters_reachable: bool,
}

impl Estimator {
    /// The estimator `kind` for `scene`, choosing lights with `select` (`ris` resamples
    /// [`DEFAULT_RIS_CANDIDATES`] candidates; see [`Estimator::with_ris_candidates`]).
    pub fn new(scene: &Scene, kind: EstimatorKind, select: LightSelect) -> Estimator {
        Estimator {
            kind,
            selector: Selector::new(select, &scene.lights),
            select,
            selector_excludes: false,
            lights_sample: !scene.lights.is_empty(),
            mis: MisSettings::default(),
            lights: LightStrategy::default(),
            ris: (select == LightSelect::Ris).then_some(DEFAULT_RIS_CANDIDATES),
            shadow_rays: ShadowRays::default(),
            emitters_reachable: scene.lights.iter().any(|l| !l.is_delta()),
        }
    }

    /// The same estimator resampling light samples from `m` candidates when its light
    /// selection is `ris` (no effect otherwise).
    pub fn with_ris_candidates(mut self, m: u32) -> Estimator {
        self.ris = self.ris.map(|_| m);
        self
    }

    /// The same estimator sampling the lights of `scene` (the scene it was made for) with
    /// `lights`; its light selection leaves out lights that draw nothing under them
    /// ([`Selector::without_silent`]).
    /// Compensation only applies under `mis` (it would be biased with the others).
    pub fn with_light_strategy(mut self, scene: &Scene, mut lights: LightStrategy) -> Estimator {
        lights.env_compensation &= self.kind == EstimatorKind::Mis;
        if self.selector_excludes {
            self.selector = Selector::new(self.select, &scene.lights);
        }
        // The selector is patched, not rebuilt: a light BVH over 10⁶ lights takes a while.
        self.selector_excludes = silent_lights(&scene.lights, lights).is_some();
        self.selector = self.selector.without_silent(&scene.lights, lights);
        self.lights_sample = scene.lights.iter().any(|l| !l.draws_no_samples(lights));
        self.lights = lights;
        self
    }

    /// The same estimator with the MIS settings `mis`.
    pub fn with_mis(mut self, mis: MisSettings) -> Estimator {
        self.mis = mis;
        self
    }

    /// Radiance along a camera ray: emission seen directly plus one estimate of direct
    /// illumination at the first hit.
    pub fn radiance(&self, scene: &Scene, ray: &Ray, src: &mut impl Uniform) -> Spectrum {
        self.radiance_in(scene, ray, src, None)
    }

    /// [`Estimator::radiance`] for a pixel whose optimal-MIS state is `optimal` (`--mis
    /// optimal`: its α weights the estimate and its moments grow).
    pub fn radiance_in(
        &self,
        scene: &Scene,
        ray: &Ray,
        src: &mut impl Uniform,
        optimal: Option<&RefCell<OptimalPixel>>,
    ) -> Spectrum {
        let hit = scene.geometry.intersect(ray, f32::INFINITY);
        self.radiance_from(scene, ray, hit.as_ref(), src, optimal)
    }

    /// [`Estimator::radiance_in`] given the camera ray's closest hit `hit` (`None`: it
    /// escapes), found by the caller (the renderer traces camera rays in packets).
    #[inline]
    pub fn radiance_from(
        &self,
        scene: &Scene,
        ray: &Ray,
        hit: Option<&SurfaceHit>,
        src: &mut impl Uniform,
        optimal: Option<&RefCell<OptimalPixel>>,
    ) -> Spectrum {
        let Some(hit) = hit else {
            return scene.escaped(ray.d.normalize()); // the background: the environment
        };
        let w_out = -ray.d.normalize();
        emitted_at(scene, hit, w_out) + self.direct_probed(scene, hit, w_out, src, None, optimal)
    }

    /// One sample of reflected direct light L_out(x, ω_out) at a surface hit.
    #[inline]
    pub fn direct(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        w_out: Vec3,
        src: &mut impl Uniform,
    ) -> Spectrum {
        self.direct_probed(scene, hit, w_out, src, None, None)
    }

    /// [`Estimator::direct`], recording every sample it draws into `probe` when given
    /// (`lightlab probe`), and weighting by a pixel's optimal-MIS state `optimal` when
    /// given (`--mis optimal`).
    #[inline(always)]
    pub fn direct_probed(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        w_out: Vec3,
        src: &mut impl Uniform,
        probe: Option<&Probe>,
        optimal: Option<&RefCell<OptimalPixel>>,
    ) -> Spectrum {
        let Some(sh) = Shading::at(scene, hit, w_out) else {
            return Spectrum::ZERO; // seen from behind: one-sided BSDFs reflect nothing
        };
        let ctx = Context {
            probe,
            optimal,
            ..self.context(scene, &sh.at, &sh.hit, &sh.material, sh.w_out)
        };
        match self.kind {
            EstimatorKind::Light => light::estimate(&ctx, src),
            EstimatorKind::Mis => mis::estimate(&ctx, self.mis, src),
            kind => directional::estimate(&ctx, kind, src),
        }
    }
}

impl Estimator {
    /// The context of one estimate at `hit` (no probe, no optimal-MIS state).
    #[inline(always)]
    fn context<'a>(
        &'a self,
        scene: &'a Scene,
        at: &'a ShadingPoint,
        hit: &'a SurfaceHit,
        material: &'a Material,
        w_out: Vec3,
    ) -> Context<'a> {
        Context {
            scene,
            selector: &self.selector,
            lights: self.lights,
            at,
            hit,
            material,
            w_out,
            ris: self.ris,
            shadow_rays: &self.shadow_rays,
            probe: None,
            optimal: None,
            emitters_reachable: self.emitters_reachable,
            lights_sample: self.lights_sample,
        }
    }
}

/// What every estimate at a surface hit starts from: its material (textured), the hit
/// (flipped to the side it is seen from when two-sided), w_out in the shading frame and
/// the shading point.
struct Shading<'a> {
    material: Cow<'a, Material>,
    hit: SurfaceHit,
    w_out: Vec3,
    at: ShadingPoint,
}

impl<'a> Shading<'a> {
    /// The shading at `hit` seen from world direction `w_out`, or `None` when it is seen
    /// from behind (one-sided BSDFs reflect nothing there).
    #[inline(always)]
    fn at(scene: &'a Scene, hit: &SurfaceHit, w_out: Vec3) -> Option<Shading<'a>> {
        let (hit, w_out_local) = oriented(scene, hit, w_out)?;
        let base = &scene.materials[hit.material as usize];
        let material = match scene.texture(hit.material) {
            Some(t) => Cow::Owned(t.apply(base, scene.geometry.texture_uv(&hit))),
            None => Cow::Borrowed(base),
        };
        Some(Shading {
            material,
            at: shading_point(&hit),
            hit,
            w_out: w_out_local,
        })
    }
}

/// `hit` turned to the side it is seen from along world direction `w_out` (flipped when
/// its material is two-sided and it is seen from behind), and `w_out` in its shading
/// frame; `None` when it is seen from behind.
#[inline(always)]
fn oriented(scene: &Scene, hit: &SurfaceHit, w_out: Vec3) -> Option<(SurfaceHit, Vec3)> {
    let hit = if w_out.dot(hit.ng) < 0.0 && scene.is_two_sided(hit.material) {
        flip(hit)
    } else {
        *hit
    };
    let w_out_local = hit.frame.to_local(w_out);
    if w_out_local.z <= 0.0 || w_out.dot(hit.ng) <= 0.0 {
        return None;
    }
    Some((hit, w_out_local))
}

/// What lights see of a hit: its point and normals.
#[inline(always)]
fn shading_point(hit: &SurfaceHit) -> ShadingPoint {
    ShadingPoint {
        p: hit.p,
        ng: hit.ng,
        n: hit.frame.n,
    }
}

/// `hit` with its normals flipped: Mitsuba's `twosided` shades the back face of a
/// two-sided material like the front one.
#[inline(always)]
fn flip(hit: &SurfaceHit) -> SurfaceHit {
    SurfaceHit {
        ng: -hit.ng,
        frame: Frame::from_normal(-hit.frame.n),
        ..*hit
    }
}

/// The scene and shading context every sample of one estimate shares.
#[derive(Clone, Copy)]
struct Context<'a> {
    scene: &'a Scene,
    selector: &'a Selector,
    /// How lights are sampled.
    lights: LightStrategy,
    at: &'a ShadingPoint,
    hit: &'a SurfaceHit,
    material: &'a Material,
    /// w_out in the local shading frame.
    w_out: Vec3,
    /// Light samples are resampled from this many candidates (RIS), if set.
    ris: Option<u32>,
    /// Where shadow rays are counted.
    shadow_rays: &'a ShadowRays,
    /// Where samples are recorded (`lightlab probe`), if anywhere.
    probe: Option<&'a Probe>,
    /// The pixel's optimal-MIS state (`--mis optimal`), if any.
    optimal: Option<&'a RefCell<OptimalPixel>>,
    /// Whether any ray can reach an emitter (see [`Estimator`]).
    emitters_reachable: bool,
    /// Whether some light draws samples (see [`Estimator`]).
    lights_sample: bool,
}

impl Context<'_> {
    /// Whether light samples alone reach every emitter: some light draws samples, and the
    /// scene has no environment. A sky sampled with MIS compensation has zero density
    /// wherever the map is at or below its mean; without it, its samples still stop at
    /// the geometric horizon, which a BSDF sample about a shading normal may cross (and
    /// escape through an open mesh). Only then may a shading point go without BSDF
    /// samples ([`MisSettings::diffuse_bsdf_samples`]).
    #[inline]
    fn lights_cover(&self) -> bool {
        self.lights_sample && self.scene.environment.is_none()
    }

    /// Whether BSDF-sampled rays are worth tracing: some emitter can be reached, or a
    /// probe records every sample drawn.
    #[inline]
    fn traces_bsdf_rays(&self) -> bool {
        self.emitters_reachable || self.probe.is_some()
    }

    /// Records the sample `make` describes when a probe listens (built only then).
    #[inline]
    fn record(&self, make: impl FnOnce() -> ProbeSample) {
        if let Some(p) = self.probe {
            p.record(make());
        }
    }

    /// Whether the segment to a light sample is blocked (one counted shadow ray). Point
    /// lights and lights at infinity have no surface point to aim a segment at.
    fn occluded(&self, ls: &LightSample) -> bool {
        self.shadow_rays.add();
        let geometry = &self.scene.geometry;
        if ls.delta || ls.distance.is_infinite() {
            geometry.direction_occluded(self.hit.p, self.hit.ng, ls.w_in, ls.distance)
        } else {
            geometry.segment_occluded(self.hit.p, self.hit.ng, ls.point, ls.normal)
        }
    }
}

/// Radiance emitted by the surface at `hit` towards `w` (world direction, pointing away
/// from the surface).
#[inline]
pub fn emitted_at(scene: &Scene, hit: &SurfaceHit, w: Vec3) -> Spectrum {
    if hit.light == NO_LIGHT {
        return Spectrum::ZERO;
    }
    scene.lights[hit.light as usize].emitted(hit.p, hit.ng, w)
}

/// f · |cos θ| for a local incident direction: the part of the integrand every
/// estimator shares.
#[inline]
fn f_cos(material: &impl Bsdf, w_in_local: Vec3, w_out_local: Vec3) -> Spectrum {
    material.eval(w_in_local, w_out_local) * w_in_local.z.abs()
}

/// [`f_cos`] and the BSDF's density of `w_in_local`, computed together
/// ([`Bsdf::eval_pdf`]).
#[inline]
fn f_cos_pdf(material: &impl Bsdf, w_in_local: Vec3, w_out_local: Vec3) -> (Spectrum, f32) {
    let (f, pdf) = material.eval_pdf(w_in_local, w_out_local);
    (f * w_in_local.z.abs(), pdf)
}
