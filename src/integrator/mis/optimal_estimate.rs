//! The `mis` estimate with optimal weights (see [`super::optimal`] for the weights and the
//! per-pixel state): the balance heuristic plus the pixel's control variate, each sample
//! scored as (f − α·p)/(n_L p_L + n_B p_B), its moments added to the pixel's.

use super::optimal::{BSDF, LIGHT};
use super::{MisSettings, TechniqueMoments, draw_light, emitter_along};
use crate::bsdf::Bsdf;
use crate::geometry::{Ray, offset_origin};
use crate::integrator::{Context, f_cos_pdf};
use crate::light::select::LightSelector;
use crate::math::Spectrum;
use crate::sampling::Uniform;

/// One estimate with optimal weights ([`super::optimal`]): α_L + α_B plus every sample's
/// (f − α·p)/(n_L p_L + n_B p_B), with the pixel's α of earlier rounds (α = 0, the balance
/// heuristic, without a pixel state), adding this estimate's moments to the pixel.
pub(super) fn optimal_estimate(
    ctx: &Context<'_>,
    mis: MisSettings,
    src: &mut impl Uniform,
) -> Spectrum {
    let mut run = OptimalRun {
        n: mis.light_samples as f32,
        m: mis.bsdf_samples as f32,
        alpha: ctx
            .optimal
            .map_or([Spectrum::ZERO; 2], |p| p.borrow().alpha),
        moments: TechniqueMoments::default(),
    };
    let mut sum = run.alpha[LIGHT] + run.alpha[BSDF];
    for _ in 0..mis.light_samples {
        sum += optimal_light_sample(ctx, src, &mut run);
    }
    for _ in 0..mis.bsdf_samples {
        sum += optimal_bsdf_sample(ctx, src, &mut run);
    }
    if let Some(p) = ctx.optimal {
        p.borrow_mut().moments.merge(&run.moments);
    }
    sum
}

/// One estimate's sample counts, α and the moments it gathers.
struct OptimalRun {
    /// Light samples per estimate.
    n: f32,
    /// BSDF samples per estimate.
    m: f32,
    /// α_L, α_B.
    alpha: [Spectrum; 2],
    moments: TechniqueMoments,
}

impl OptimalRun {
    /// A failed sample of technique `t`: a point only `t` reaches, scoring −α_t/n_t.
    fn fail(&mut self, t: usize) -> Spectrum {
        let count = if t == LIGHT { self.n } else { self.m };
        self.moments.add_failure(t, count);
        -self.alpha[t] / count
    }

    /// A sample of the shared domain: integrand `fl`, densities `p_light`, `p_bsdf`.
    fn score(&mut self, fl: Spectrum, p_light: f32, p_bsdf: f32) -> Spectrum {
        let d = self.n * p_light + self.m * p_bsdf;
        self.moments.add(fl, p_light, p_bsdf, d);
        (fl - self.alpha[LIGHT] * p_light - self.alpha[BSDF] * p_bsdf) / d
    }
}

/// One light sample under optimal weights.
fn optimal_light_sample(
    ctx: &Context<'_>,
    src: &mut impl Uniform,
    run: &mut OptimalRun,
) -> Spectrum {
    let draw = draw_light(ctx.selector, ctx.at, src);
    let Some(sel) = draw.selection else {
        return run.fail(LIGHT);
    };
    let Some(ls) = ctx.scene.lights[sel.index].sample(ctx.at, draw.u_point, ctx.lights) else {
        return run.fail(LIGHT);
    };
    let w_in = ctx.hit.frame.to_local(ls.w_in);
    let (f, p_bsdf) = f_cos_pdf(ctx.material, w_in, ctx.w_out);
    if ls.delta {
        // A Dirac sample: weight 1, outside the control variate's domain.
        let value = if f != Spectrum::ZERO && !ctx.occluded(&ls) {
            f * ls.radiance / (run.n * ls.pdf * sel.pmf)
        } else {
            Spectrum::ZERO
        };
        return value + run.fail(LIGHT);
    }
    // Only BSDF sampling could also reach this point, and only if it is visible.
    if ls.radiance == Spectrum::ZERO || (f == Spectrum::ZERO && p_bsdf <= 0.0) || ctx.occluded(&ls)
    {
        return run.fail(LIGHT);
    }
    run.score(f * ls.radiance, sel.pmf * ls.pdf, p_bsdf)
}

/// One BSDF sample under optimal weights.
fn optimal_bsdf_sample(
    ctx: &Context<'_>,
    src: &mut impl Uniform,
    run: &mut OptimalRun,
) -> Spectrum {
    let Some(s) = ctx.material.sample(ctx.w_out, src.next_2d()) else {
        return run.fail(BSDF);
    };
    if s.pdf.is_nan() || s.pdf <= 0.0 {
        return run.fail(BSDF);
    }
    let w_world = ctx.hit.frame.to_world(s.w_in);
    let ray = Ray::new(offset_origin(ctx.hit.p, ctx.hit.ng, w_world), w_world);
    let reached = emitter_along(ctx, &ray, s.delta);
    let f = s.f * s.w_in.z.abs();
    if s.delta {
        let value = reached.map_or(Spectrum::ZERO, |r| f * r.le / (run.m * s.pdf));
        return value + run.fail(BSDF);
    }
    // Light sampling reaches the same point only where it emits towards a shading point
    // it sees above its horizon (its failures are apart, see the module notes).
    let (fl, p_light) = match reached {
        Some(r) if r.le != Spectrum::ZERO && ctx.at.n.dot(w_world) > 0.0 => {
            (f * r.le, ctx.selector.pmf(ctx.at, r.index) * r.pdf_light)
        }
        _ => (Spectrum::ZERO, 0.0),
    };
    run.score(fl, p_light, s.pdf)
}
