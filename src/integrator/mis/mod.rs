//! The `mis` estimator: light sampling and BSDF sampling combined by multiple importance
//! sampling (Veach & Guibas 1995).
//!
//! Multi-sample model (Veach's thesis eq. 9.4): N light samples and M BSDF samples,
//! F = Σ_i (1/n_i) Σ_j w_i(X_ij) f(X_ij) / p_i(X_ij), with balance or power weights on the
//! effective densities n_i·p_i. One-sample model (thesis §9.2.4): choose light sampling with
//! probability c_L = N/(N+M), else BSDF sampling, and score f / Σ_k c_k p_k (the balance
//! heuristic divided by the choice probability).
//!
//! The light strategy's density of a direction is p_L(ω) = pmf(light | x) · p_light(ω | x):
//! selection probability times the light's own solid-angle density. A BSDF-sampled ray that
//! reaches an emitter asks the selector and the light for exactly that product. Samples from
//! a delta distribution (point lights, mirror lobes) can come from one strategy only, and get
//! weight 1 from it.
//!
//! The BSDF sample count may depend on the shading point (`at_point`): with
//! `--diffuse-bsdf-samples 0`, a Lambertian point takes light samples alone, with the
//! weights of M = 0 (1 for every light sample). The weights of the techniques used at a
//! point still sum to one there, and the counts depend on the point alone (its
//! material), never on its samples, so each point's estimate stays unbiased.

mod optimal;
mod optimal_estimate;
mod weights;

pub use optimal::{OptimalPixel, TechniqueMoments};
pub use weights::{MisHeuristic, mis_weight};

use super::light::light_record;
use super::probe::{ProbeSample, no_direction};
use super::{Context, emitted_at, f_cos_pdf};
use glam::Vec2;

use crate::bsdf::{Bsdf, Material};
use crate::geometry::{Along, Ray, offset_origin};
use crate::light::select::{LightSelector, Selection, Selector};
use crate::light::{LightSample, ShadingPoint};
use crate::math::Spectrum;
use crate::sampling::Uniform;
use optimal_estimate::optimal_estimate;

pub use crate::settings::MisSettings;

/// `mis` at the shading point of `ctx`: [`MisSettings::diffuse_bsdf_samples`] BSDF
/// samples where the material is Lambertian and light samples alone reach every emitter
/// (not where BSDF samples are the only technique, nor under a sky: see
/// `Context::lights_cover`), else `mis` as it is. Never under optimal weights, whose
/// control variate takes both techniques everywhere (renders refuse the pair; a probe
/// or resampled light samples would reach here), nor where it would leave no sample.
#[inline(always)]
fn at_point(ctx: &Context<'_>, mis: MisSettings) -> MisSettings {
    let Some(m) = mis.diffuse_bsdf_samples else {
        return mis;
    };
    let applies = ctx.lights_cover()
        && matches!(ctx.material, Material::Diffuse(_))
        && mis.heuristic != MisHeuristic::Optimal
        && (m > 0 || mis.light_samples > 0);
    if applies {
        MisSettings {
            bsdf_samples: m,
            ..mis
        }
    } else {
        mis
    }
}

/// One estimate of the `mis` estimator.
pub(super) fn estimate(ctx: &Context<'_>, mis: MisSettings, src: &mut impl Uniform) -> Spectrum {
    // Resampled light samples carry no density for the control variate: there optimal
    // weights reduce to their α = 0, the balance heuristic (renders refuse the pair). A
    // probe has no pixel state either (α = 0), and the balance path records its samples.
    if mis.heuristic == MisHeuristic::Optimal && ctx.ris.is_none() && ctx.probe.is_none() {
        return optimal_estimate(ctx, mis, src);
    }
    estimate_with(ctx, mis, src, &mut Drawn)
}

/// How the MIS estimator gets its light samples: drawn here ([`Drawn`]), or combined
/// from reservoirs filled earlier (spatial reuse, [`super::spatial`]).
pub(super) trait LightTechnique {
    /// One light sample: `scale(p_light, p_bsdf)` is the factor that multiplies f·cos·Le
    /// (the MIS weight over the density); `delta_scale` multiplies f·cos·Le/pmf for delta
    /// lights.
    fn sample(
        &mut self,
        ctx: &Context<'_>,
        src: &mut impl Uniform,
        scale: impl Fn(f32, f32) -> f32,
        delta_scale: f32,
    ) -> Spectrum;
}

/// Light samples drawn at the shading point (RIS when the context asks for it).
struct Drawn;

impl LightTechnique for Drawn {
    #[inline(always)]
    fn sample(
        &mut self,
        ctx: &Context<'_>,
        src: &mut impl Uniform,
        scale: impl Fn(f32, f32) -> f32,
        delta_scale: f32,
    ) -> Spectrum {
        light_sample(ctx, src, scale, delta_scale)
    }
}

/// The balance, power and one-sample estimates with light samples from `light`.
#[inline]
pub(super) fn estimate_with(
    ctx: &Context<'_>,
    mis: MisSettings,
    src: &mut impl Uniform,
    light: &mut impl LightTechnique,
) -> Spectrum {
    let mis = at_point(ctx, mis);
    let (n, m) = (mis.light_samples as f32, mis.bsdf_samples as f32);
    if mis.heuristic == MisHeuristic::OneSample {
        // With no light to draw from, every estimate takes the BSDF technique.
        let c_light = if ctx.lights_sample { n / (n + m) } else { 0.0 };
        // f / Σ_k c_k p_k: the balance heuristic over the choice probability.
        let scale =
            |p_light: f32, p_bsdf: f32| 1.0 / (c_light * p_light + (1.0 - c_light) * p_bsdf);
        let u = src.next_1d();
        return if u < c_light {
            light.sample(ctx, src, scale, 1.0 / c_light)
        } else if !ctx.traces_bsdf_rays() {
            Spectrum::ZERO // only delta lights: no BSDF-sampled ray can score
        } else {
            bsdf_sample(ctx, src, |pb, pl| scale(pl, pb), 1.0 / (1.0 - c_light))
        };
    }
    let mut sum = Spectrum::ZERO;
    for _ in 0..mis.light_samples {
        sum += light.sample(ctx, src, light_scale(mis), 1.0 / n);
    }
    add_bsdf_samples(ctx, mis, src, sum)
}

/// The factor on a light sample's f·cos·Le under the balance or power heuristic: its MIS
/// weight over its effective density n·p_light.
#[inline(always)]
fn light_scale(mis: MisSettings) -> impl Fn(f32, f32) -> f32 {
    let (n, m, h) = (
        mis.light_samples as f32,
        mis.bsdf_samples as f32,
        mis.heuristic,
    );
    move |pl, pb| mis_weight(h, n * pl, m * pb) / (n * pl)
}

/// `sum` plus the balance or power estimate's BSDF samples.
#[inline(always)]
fn add_bsdf_samples(
    ctx: &Context<'_>,
    mis: MisSettings,
    src: &mut impl Uniform,
    mut sum: Spectrum,
) -> Spectrum {
    let (n, m, h) = (
        mis.light_samples as f32,
        mis.bsdf_samples as f32,
        mis.heuristic,
    );
    // With only delta lights no BSDF-sampled ray can reach an emitter: every BSDF sample
    // is exactly zero (the sampler's later dimensions are not used by this estimate).
    let bsdf_samples = if ctx.traces_bsdf_rays() {
        mis.bsdf_samples
    } else {
        0
    };
    for _ in 0..bsdf_samples {
        sum += bsdf_sample(
            ctx,
            src,
            |pb, pl| mis_weight(h, m * pb, n * pl) / (m * pb),
            1.0 / m,
        );
    }
    sum
}

/// The numbers and the light of one light sample, drawn before the light itself is
/// sampled: [`light_sample`]'s first step, and the heart of each
/// [`LightJob`](super::LightJob) that [`super::Estimator::begin`] hands on.
#[derive(Clone, Copy, Debug)]
pub(super) struct LightDraw {
    /// The light chosen (`None`: no light can contribute).
    pub selection: Option<Selection>,
    /// The two numbers that place the point on it.
    pub u_point: Vec2,
}

/// The numbers of one light sample, in the order every estimate draws them: the one
/// that chooses the light, then the two that place the point on it.
#[inline(always)]
pub(super) fn light_numbers(src: &mut impl Uniform) -> (f32, Vec2) {
    let u_select = src.next_1d();
    let u_point = src.next_2d();
    (u_select, u_point)
}

/// Draws the numbers of one light sample and chooses its light at `at` (which needs
/// the shading point alone, not its material).
#[inline(always)]
pub(super) fn draw_light(
    selector: &Selector,
    at: &ShadingPoint,
    src: &mut impl Uniform,
) -> LightDraw {
    let (u_select, u_point) = light_numbers(src);
    LightDraw {
        selection: selector.select(at, u_select),
        u_point,
    }
}

/// The rest of a balance or power estimate after [`draw_light`] drew each light
/// sample's `draw` and its light was sampled (`ls`), the pairs `drawn` in the order of
/// the draws: the light samples' scores and the BSDF samples, the same as [`estimate`]
/// gives from the same state.
#[inline(always)]
pub(super) fn finish<'d>(
    ctx: &Context<'_>,
    mis: MisSettings,
    drawn: impl Iterator<Item = (&'d LightDraw, Option<LightSample>)>,
    src: &mut impl Uniform,
) -> Spectrum {
    debug_assert!(ctx.ris.is_none());
    let mis = at_point(ctx, mis);
    let n = mis.light_samples as f32;
    let mut sum = Spectrum::ZERO;
    let mut scored = 0;
    for (draw, ls) in drawn {
        sum += score_light_sample(ctx, draw.selection, ls, light_scale(mis), 1.0 / n);
        scored += 1;
    }
    debug_assert_eq!(scored, mis.light_samples, "one score per light sample");
    add_bsdf_samples(ctx, mis, src, sum)
}

/// One light sample: `scale(p_light, p_bsdf)` is the factor that multiplies f·cos·Le (the
/// MIS weight over the density); `delta_scale` multiplies f·cos·Le/pmf for delta lights.
fn light_sample(
    ctx: &Context<'_>,
    src: &mut impl Uniform,
    scale: impl Fn(f32, f32) -> f32,
    delta_scale: f32,
) -> Spectrum {
    if let Some(m) = ctx.ris {
        return resampled_light_sample(ctx, src, m, scale, delta_scale);
    }
    let draw = draw_light(ctx.selector, ctx.at, src);
    let ls = draw
        .selection
        .and_then(|sel| ctx.scene.lights[sel.index].sample(ctx.at, draw.u_point, ctx.lights));
    score_light_sample(ctx, draw.selection, ls, scale, delta_scale)
}

/// A light sample's contribution, given its light `selection` and the light's sample
/// `ls` (either `None`: nothing).
#[inline(always)]
fn score_light_sample(
    ctx: &Context<'_>,
    selection: Option<Selection>,
    ls: Option<LightSample>,
    scale: impl Fn(f32, f32) -> f32,
    delta_scale: f32,
) -> Spectrum {
    let (Some(sel), Some(ls)) = (selection, ls) else {
        ctx.record(|| no_direction("light"));
        return Spectrum::ZERO;
    };
    let w_in = ctx.hit.frame.to_local(ls.w_in);
    // f and the BSDF's density of w_in together: they share terms (see Bsdf::eval_pdf).
    let (f, p_bsdf) = f_cos_pdf(ctx.material, w_in, ctx.w_out);
    let p_light = sel.pmf * ls.pdf;
    let occluded = f != Spectrum::ZERO && ctx.occluded(&ls);
    if f == Spectrum::ZERO || occluded {
        ctx.record(|| {
            light_record(
                "light",
                &ls,
                sel.index,
                p_light,
                0.0,
                Spectrum::ZERO,
                occluded,
            )
        });
        return Spectrum::ZERO;
    }
    let factor = if ls.delta {
        delta_scale / (ls.pdf * sel.pmf)
    } else {
        scale(p_light, p_bsdf)
    };
    let value = f * ls.radiance * factor;
    // factor = w / (n·p) (or w / (c·p) one-sample) and delta_scale = 1/n (or 1/c).
    ctx.record(|| {
        let w = factor * p_light / delta_scale;
        light_record("light", &ls, sel.index, p_light, w, value, false)
    });
    value
}

/// One light sample resampled from `m` candidates (RIS, see [`super::ris`]): f·cos·Le·W
/// in place of f·cos·Le/p, weighted against BSDF sampling with the source density p̃ that
/// BSDF-sampled hits also ask for. `scale(p̃, p_bsdf)·p̃` is the MIS weight over the sample
/// count (or the choice probability) for every heuristic.
fn resampled_light_sample(
    ctx: &Context<'_>,
    src: &mut impl Uniform,
    m: u32,
    scale: impl Fn(f32, f32) -> f32,
    delta_scale: f32,
) -> Spectrum {
    let Some(r) = super::ris::resample(ctx, src, m, false) else {
        ctx.record(|| no_direction("ris"));
        return Spectrum::ZERO;
    };
    if ctx.occluded(&r.ls) {
        ctx.record(|| light_record("ris", &r.ls, r.light, r.p_source, 0.0, Spectrum::ZERO, true));
        return Spectrum::ZERO;
    }
    let weight = if r.ls.delta {
        delta_scale
    } else {
        let p_bsdf = ctx.material.pdf(r.w_in, ctx.w_out);
        scale(r.p_source, p_bsdf) * r.p_source
    };
    let value = r.f * r.ls.radiance * (r.weight * weight);
    ctx.record(|| {
        let w = weight / delta_scale;
        light_record("ris", &r.ls, r.light, r.p_source, w, value, false)
    });
    value
}

/// One BSDF sample: `scale(p_bsdf, p_light)` as in [`light_sample`]; `delta_scale`
/// multiplies f·cos·Le/pdf for delta lobes.
fn bsdf_sample(
    ctx: &Context<'_>,
    src: &mut impl Uniform,
    scale: impl Fn(f32, f32) -> f32,
    delta_scale: f32,
) -> Spectrum {
    let Some(s) = ctx.material.sample(ctx.w_out, src.next_2d()) else {
        ctx.record(|| no_direction("bsdf"));
        return Spectrum::ZERO;
    };
    if s.pdf.is_nan() || s.pdf <= 0.0 || s.f == Spectrum::ZERO {
        ctx.record(|| no_direction("bsdf"));
        return Spectrum::ZERO;
    }
    let w_world = ctx.hit.frame.to_world(s.w_in);
    let ray = Ray::new(offset_origin(ctx.hit.p, ctx.hit.ng, w_world), w_world);
    let record = |light: Option<usize>, point: Option<glam::Vec3>, w: f32, value: Spectrum| {
        ctx.record(|| ProbeSample {
            sample: 0,
            technique: "bsdf",
            w_in: Some(w_world),
            pdf: s.pdf,
            mis_weight: w,
            contribution: value,
            light,
            light_point: point,
            occluded: false,
        })
    };
    let Some(Reached {
        index,
        le,
        pdf_light,
        point,
    }) = emitter_along(ctx, &ray, s.delta)
    else {
        record(None, None, 0.0, Spectrum::ZERO);
        return Spectrum::ZERO;
    };
    if le == Spectrum::ZERO {
        record(Some(index), point, 0.0, Spectrum::ZERO);
        return Spectrum::ZERO;
    }
    let f = s.f * s.w_in.z.abs();
    let factor = if s.delta {
        delta_scale / s.pdf
    } else {
        let p_light = ctx.selector.pmf(ctx.at, index) * pdf_light;
        scale(s.pdf, p_light)
    };
    let value = f * le * factor;
    record(Some(index), point, factor * s.pdf / delta_scale, value);
    value
}

/// The emitter a BSDF-sampled ray reaches: a surface light, or the environment if it
/// escapes.
struct Reached {
    /// The light's index.
    index: usize,
    /// Its radiance towards the shading point.
    le: Spectrum,
    /// The light's own density for the direction (0 for a delta BSDF sample); the
    /// selection probability is not included.
    pdf_light: f32,
    /// The point reached on a surface light.
    point: Option<glam::Vec3>,
}

/// Traces `ray` (from the shading point) to the emitter it reaches, if any.
#[inline]
fn emitter_along(ctx: &Context<'_>, ray: &Ray, delta: bool) -> Option<Reached> {
    let scene = ctx.scene;
    match scene
        .geometry
        .first_emitter(ray, scene.environment.is_some())
    {
        Along::Emitter(y) => {
            let index = y.light as usize;
            let pdf_light = if delta {
                0.0
            } else {
                scene.lights[index].pdf(ctx.at, y.p, y.ng, ctx.lights)
            };
            Some(Reached {
                index,
                le: emitted_at(scene, &y, -ray.d),
                pdf_light,
                point: Some(y.p),
            })
        }
        Along::Blocked => None,
        Along::Escapes => scene.environment.map(|index| {
            let (le, pdf_light) = scene.lights[index].infinite_radiance_pdf(ray.d, ctx.lights);
            Reached {
                index,
                le,
                pdf_light,
                point: None,
            }
        }),
    }
}
