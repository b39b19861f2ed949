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

mod weights;

pub use weights::{MisHeuristic, mis_weight};

use super::light::light_record;
use super::probe::{ProbeSample, no_direction};
use super::{Context, emitted_at, f_cos};
use crate::bsdf::Bsdf;
use crate::geometry::{NO_LIGHT, Ray, offset_origin};
use crate::light::select::LightSelector;
use crate::math::Spectrum;
use crate::sampling::Uniform;

pub use crate::settings::MisSettings;

/// One estimate of the `mis` estimator.
pub(super) fn estimate(ctx: &Context<'_>, mis: MisSettings, src: &mut impl Uniform) -> Spectrum {
    let (n, m) = (mis.light_samples as f32, mis.bsdf_samples as f32);
    if mis.heuristic == MisHeuristic::OneSample {
        let c_light = n / (n + m);
        // f / Σ_k c_k p_k: the balance heuristic over the choice probability.
        let scale =
            |p_light: f32, p_bsdf: f32| 1.0 / (c_light * p_light + (1.0 - c_light) * p_bsdf);
        let u = src.next_1d();
        return if u < c_light {
            light_sample(ctx, src, scale, 1.0 / c_light)
        } else {
            bsdf_sample(ctx, src, |pb, pl| scale(pl, pb), 1.0 / (1.0 - c_light))
        };
    }
    let h = mis.heuristic;
    let mut sum = Spectrum::ZERO;
    for _ in 0..mis.light_samples {
        sum += light_sample(
            ctx,
            src,
            |pl, pb| mis_weight(h, n * pl, m * pb) / (n * pl),
            1.0 / n,
        );
    }
    for _ in 0..mis.bsdf_samples {
        sum += bsdf_sample(
            ctx,
            src,
            |pb, pl| mis_weight(h, m * pb, n * pl) / (m * pb),
            1.0 / m,
        );
    }
    sum
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
    let u_select = src.next_1d();
    let u_point = src.next_2d();
    let Some(sel) = ctx.selector.select(ctx.at, u_select) else {
        ctx.record(|| no_direction("light"));
        return Spectrum::ZERO;
    };
    let light = &ctx.scene.lights[sel.index];
    let Some(ls) = light.sample(ctx.at, u_point, ctx.lights) else {
        ctx.record(|| no_direction("light"));
        return Spectrum::ZERO;
    };
    let w_in = ctx.hit.frame.to_local(ls.w_in);
    let f = f_cos(ctx.material, w_in, ctx.w_out);
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
        let p_bsdf = ctx.material.pdf(w_in, ctx.w_out);
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
    let Some(r) = super::ris::resample(ctx, src, m) else {
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
    // The emitter the ray reaches (a surface light, or the environment if it escapes),
    // its radiance, and the light strategy's density for this direction.
    let scene = ctx.scene;
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
    let (index, le, pdf_light, point) = match scene.geometry.intersect(&ray, f32::INFINITY) {
        Some(y) if y.light != NO_LIGHT => {
            let i = y.light as usize;
            let le = emitted_at(scene, &y, -w_world);
            let pdf = if s.delta {
                0.0
            } else {
                scene.lights[i].pdf(ctx.at, y.p, y.ng, ctx.lights)
            };
            (i, le, pdf, Some(y.p))
        }
        Some(_) => {
            record(None, None, 0.0, Spectrum::ZERO);
            return Spectrum::ZERO;
        }
        None => match scene.environment {
            Some(i) => {
                let light = &scene.lights[i];
                (
                    i,
                    light.infinite_radiance(w_world),
                    light.infinite_pdf(w_world, ctx.lights),
                    None,
                )
            }
            None => {
                record(None, None, 0.0, Spectrum::ZERO);
                return Spectrum::ZERO;
            }
        },
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
