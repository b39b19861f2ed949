//! The light estimator (area form): choose a light, draw a point y on it, and score
//! f · G · V · Le / p_A — computed here as f · cos θ_x · Le / p_ω with the density
//! converted to solid angle, which is the same quantity.

use super::mis::draw_light;
use super::probe::{ProbeSample, no_direction};
use super::{Context, f_cos};
use crate::light::LightSample;
use crate::light::select::Selection;
use crate::math::Spectrum;
use crate::sampling::Uniform;

/// One sample of the light estimator. The selection number is reused for nothing else
/// here; the point on the light takes its own two numbers (drawn in that order by
/// [`draw_light`], as the `mis` estimate draws them).
pub(super) fn estimate(ctx: &Context<'_>, src: &mut impl Uniform) -> Spectrum {
    if let Some(m) = ctx.ris {
        return super::ris::estimate(ctx, src, m);
    }
    let draw = draw_light(ctx.selector, ctx.at, src);
    // Horizon rejection happens inside `sample`, before any shadow ray (lecture: check
    // cos θ₁ < 0 before evaluating visibility); without it the shadow ray comes first,
    // as in the naive loop, and f·cos = 0 scores the sample.
    let ls = draw
        .selection
        .and_then(|sel| ctx.scene.lights[sel.index].sample(ctx.at, draw.u_point, ctx.lights));
    score(ctx, draw.selection, ls)
}

/// The light estimate of the light sample `ls` of the light `selection` chose (either
/// `None`: nothing): f · cos θ_x · Le / p_ω unless the light is hidden. [`estimate`]'s
/// last step, and the light estimator's last stage ([`super::Estimator::finish`]).
#[inline(always)]
pub(super) fn score(
    ctx: &Context<'_>,
    selection: Option<Selection>,
    ls: Option<LightSample>,
) -> Spectrum {
    let Context {
        lights,
        hit,
        material,
        w_out,
        ..
    } = *ctx;
    let (Some(sel), Some(ls)) = (selection, ls) else {
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
