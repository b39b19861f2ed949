//! Resampled importance sampling of lights (Talbot, Cline & Egbert 2005, "Importance
//! Resampling for Global Illumination"; the per-pixel core of ReSTIR, Bitterli et al. 2020).
//!
//! Draw M candidates y_j from the source strategy p (the light BVH's pmf times the light's
//! own density), weigh each by w_j = p̂(y_j) / p(y_j) with the target p̂ = luminance of the
//! unshadowed contribution f·cos·Le, keep one, y, with probability w_y / Σ w_j, and trace
//! one shadow ray to it. With the unbiased contribution weight
//! W = Σ_j w_j / (M · p̂(y)), E[g(y) · W] = ∫ g for every g that is zero wherever p is
//! (Talbot 2005 eq. 3.4), so f·Le·V·W is unbiased. The estimator's cost is M light samples
//! and M BSDF evaluations per shadow ray.
//!
//! Under MIS the weights need a density for every direction that both strategies can
//! draw; RIS has none in closed form, so the light strategy's weight uses the source
//! density p (deterministic, and the same number a BSDF-sampled hit asks the selector
//! and the light for). The light and BSDF weights of a direction then still sum to one,
//! which is all that unbiasedness asks of MIS weights (Veach's thesis §9.2, condition W1).

use glam::Vec3;

use super::light::light_record;
use super::probe::no_direction;
use super::{Context, f_cos};
use crate::light::select::LightSelector;
use crate::light::{LightSample, ShadingPoint};
use crate::math::{Spectrum, spectrum::luminance};
use crate::sampling::Uniform;

use crate::settings::MAX_RIS_CANDIDATES;

/// The candidate kept by resampling, unshadowed.
#[derive(Clone, Copy, Debug)]
pub(super) struct Resampled {
    /// The light sample (direction, distance, radiance, the light's own pdf).
    pub ls: LightSample,
    /// Which light it is on.
    pub light: usize,
    /// The incident direction in the local shading frame.
    pub w_in: Vec3,
    /// f·|cos θ| at that direction.
    pub f: Spectrum,
    /// The source density of the kept sample: selection pmf × the light's density
    /// (a Dirac weight for delta lights).
    pub p_source: f32,
    /// The unbiased contribution weight W = Σ w_j / (M · p̂(y)).
    pub weight: f32,
}

/// Draws `candidates` light samples from the context's selector and lights, and keeps one
/// ∝ luminance(f·cos·Le)/p (a streaming weighted reservoir whose single random number is
/// rescaled at every step, as the lecture reuses one number for two choices). `None`
/// when no candidate carries light. With `horizons`, candidates below the geometric or
/// the shading normal's horizon are skipped (the target of spatial reuse, which must be
/// zero wherever a pixel's own candidates cannot land; see [`super::spatial`]).
#[inline(always)]
pub(super) fn resample(
    ctx: &Context<'_>,
    src: &mut impl Uniform,
    candidates: u32,
    horizons: bool,
) -> Option<Resampled> {
    let m = candidates.clamp(1, MAX_RIS_CANDIDATES);
    let mut reservoir = Reservoir::new(src.next_1d());
    let mut kept: Option<(Resampled, f32)> = None;
    for _ in 0..m {
        let u_select = src.next_1d();
        let u_point = src.next_2d();
        let Some(sel) = ctx.selector.select(ctx.at, u_select) else {
            continue;
        };
        let Some(ls) = ctx.scene.lights[sel.index].sample(ctx.at, u_point, ctx.lights) else {
            continue;
        };
        if horizons && !above_horizons(ctx.at, ls.w_in) {
            continue;
        }
        let w_in = ctx.hit.frame.to_local(ls.w_in);
        let f = f_cos(ctx.material, w_in, ctx.w_out);
        let p_source = sel.pmf * ls.pdf;
        let target = luminance(f * ls.radiance);
        if !(target > 0.0 && target.is_finite() && p_source > 0.0 && p_source.is_finite()) {
            continue;
        }
        if reservoir.offer((target / p_source) as f64) {
            let r = Resampled {
                ls,
                light: sel.index,
                w_in,
                f,
                p_source,
                weight: 0.0,
            };
            kept = Some((r, target));
        }
    }
    let (mut r, target) = kept?;
    r.weight = (reservoir.w_sum / (m as f64 * target as f64)) as f32;
    (r.weight > 0.0 && r.weight.is_finite()).then_some(r)
}

/// Whether `w` (world, towards the light) is above both the geometric and the shading
/// horizon of `at`.
#[inline]
pub(super) fn above_horizons(at: &ShadingPoint, w: Vec3) -> bool {
    at.ng.dot(w) > 0.0 && at.n.dot(w) > 0.0
}

/// A streaming weighted reservoir of size one driven by a single uniform number: after
/// offers w_1 … w_k, the kept offer is j with probability w_j / Σ w. The number is
/// rescaled after each decision so it stays uniform for the next one.
pub(super) struct Reservoir {
    u: f64,
    /// Σ of the weights offered so far.
    pub w_sum: f64,
}

impl Reservoir {
    pub fn new(u: f32) -> Reservoir {
        Reservoir {
            u: u as f64,
            w_sum: 0.0,
        }
    }

    /// Offers a candidate of weight `w` > 0; true when it replaces the kept one (with
    /// probability w / Σw so far).
    pub fn offer(&mut self, w: f64) -> bool {
        self.w_sum += w;
        let p = w / self.w_sum;
        let keep = self.u < p;
        self.u = if keep {
            self.u / p
        } else {
            (self.u - p) / (1.0 - p)
        };
        self.u = self.u.clamp(0.0, 1.0 - f64::EPSILON);
        keep
    }
}

/// One sample of the light estimator with resampling: f·cos·Le·V·W.
pub(super) fn estimate(ctx: &Context<'_>, src: &mut impl Uniform, candidates: u32) -> Spectrum {
    let Some(r) = resample(ctx, src, candidates, false) else {
        ctx.record(|| no_direction("ris"));
        return Spectrum::ZERO;
    };
    let occluded = ctx.occluded(&r.ls);
    let value = if occluded {
        Spectrum::ZERO
    } else {
        r.f * r.ls.radiance * r.weight
    };
    ctx.record(|| light_record("ris", &r.ls, r.light, r.p_source, 1.0, value, occluded));
    value
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng32;
    use crate::sampling::chi2::chi2_p_value;

    #[test]
    fn reservoir_keeps_each_offer_in_proportion_to_its_weight() {
        let weights = [1.0, 0.0001, 5.0, 2.5, 0.5, 3.0, 1e-3, 8.0];
        let total: f64 = weights.iter().sum();
        let n = 400_000;
        let mut counts = [0u64; 8];
        let mut rng = Rng32::new(17);
        for _ in 0..n {
            let mut r = Reservoir::new(rng.next_f32());
            let mut kept = None;
            for (j, &w) in weights.iter().enumerate() {
                if r.offer(w) {
                    kept = Some(j);
                }
            }
            counts[kept.expect("one kept")] += 1;
        }
        let expected: Vec<f64> = weights.iter().map(|w| n as f64 * w / total).collect();
        let observed: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
        let p = p_value(&observed, &expected);
        assert!(p > 1e-3, "p = {p}: {counts:?} vs {expected:?}");
        // The same test rejects a reservoir that keeps the later offers 1% more often.
        let skewed: Vec<f64> = (0..8)
            .map(|j| expected[j] * (1.0 + 0.01 * j as f64))
            .collect();
        let scale = n as f64 / skewed.iter().sum::<f64>();
        let skewed: Vec<f64> = skewed.iter().map(|e| e * scale).collect();
        assert!(p_value(&observed, &skewed) < 1e-3);
    }

    /// Pearson's χ² p-value, cells expecting fewer than five pooled.
    fn p_value(observed: &[f64], expected: &[f64]) -> f64 {
        let (mut stat, mut cells, mut pool) = (0.0, 0, (0.0, 0.0));
        for (o, e) in observed.iter().zip(expected) {
            pool = (pool.0 + o, pool.1 + e);
            if pool.1 >= 5.0 {
                stat += (pool.0 - pool.1) * (pool.0 - pool.1) / pool.1;
                cells += 1;
                pool = (0.0, 0.0);
            }
        }
        chi2_p_value(stat, cells - 1)
    }
}
