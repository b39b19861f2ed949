//! The light estimator (area form): choose a light, draw a point y on it, and score
//! f · G · V · Le / p_A — computed here as f · cos θ_x · Le / p_ω with the density
//! converted to solid angle, which is the same quantity.

use super::probe::{ProbeSample, no_direction};
use super::{Context, f_cos};
use crate::light::LightSample;
use crate::light::select::LightSelector;
use crate::math::Spectrum;
use crate::sampling::Uniform;

/// One sample of the light estimator. The selection number is reused for nothing else
/// here; the point on the light takes its own two numbers.
pub(super) fn estimate(ctx: &Context<'_>, src: &mut impl Uniform) -> Spectrum {
    let Context {
        scene,
        selector,
        lights,
        at,
        hit,
        material,
        w_out,
        ..
    } = *ctx;
    if let Some(m) = ctx.ris {
        return super::ris::estimate(ctx, src, m);
    }
    let u_select = src.next_1d();
    let u_point = src.next_2d();
    let Some(sel) = selector.select(at, u_select) else {
        ctx.record(|| no_direction("light"));
        return Spectrum::ZERO;
    };
    let light = &scene.lights[sel.index];
    // Horizon rejection happens inside `sample`, before any shadow ray (lecture: check
    // cos θ₁ < 0 before evaluating visibility); without it the shadow ray comes first,
    // as in the naive loop, and f·cos = 0 scores the sample.
    let Some(ls) = light.sample(at, u_point, lights) else {
        ctx.record(|| no_direction("light"));
        return Spectrum::ZERO;
    };
    let w_in = hit.frame.to_local(ls.w_in);
    let f = f_cos(material, w_in, w_out);
    let occluded = !(lights.horizon_rejection && f == Spectrum::ZERO) && ctx.occluded(&ls);
    let value = if occluded || f == Spectrum::ZERO {
        Spectrum::ZERO
    } else {
        f * ls.radiance / (ls.pdf * sel.pmf)
    };
    ctx.record(|| {
        light_record(
            "light",
            &ls,
            sel.index,
            sel.pmf * ls.pdf,
            1.0,
            value,
            occluded,
        )
    });
    value
}

/// The probe record of a light sample.
pub(super) fn light_record(
    technique: &'static str,
    ls: &LightSample,
    light: usize,
    pdf: f32,
    mis_weight: f32,
    contribution: Spectrum,
    occluded: bool,
) -> ProbeSample {
    ProbeSample {
        sample: 0,
        technique,
        w_in: Some(ls.w_in),
        pdf,
        mis_weight,
        contribution,
        light: Some(light),
        light_point: ls.distance.is_finite().then_some(ls.point),
        occluded,
    }
}
