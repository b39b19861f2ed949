//! Reference images: progressive passes until the estimated error is small enough or a
//! budget runs out.
//!
//! Two error estimates come from the film's per-pixel variance of the mean:
//! - the relative standard error of the image mean, √(Σ Var(mean)) / Σ mean over pixels
//!   and channels (the error of the image's average brightness);
//! - the 90th percentile over pixels of the relative standard error of each pixel,
//!   √(Var(mean)) / (mean + 0.01·image mean), channel-averaged (the error a viewer
//!   sees: most pixels are at least this good). The 0.01·image mean keeps black pixels
//!   from making the quantile infinite.
//!
//! Pass k renders with seed `round_seed(seed, k)`, so passes are independent and merge
//! exactly (`Film::merge`); pass sizes double, starting at 4 spp.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::image::Film;
use crate::lab::budget::round_seed;
use crate::render::{Carry, Control, RenderOutput, RenderSettings, render_carrying};
use crate::scene::Scene;

/// The quantile of per-pixel relative error a reference is held to.
pub const PIXEL_QUANTILE: f64 = 0.9;

/// When to stop refining a reference: the first limit reached ends it. At least one
/// limit must be set.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReferenceTarget {
    /// Stop when both relative error estimates are below this.
    pub rel_error: Option<f64>,
    /// Stop at this many samples per pixel.
    pub max_spp: Option<u32>,
    /// Stop once this much time has passed.
    pub max_time: Option<Duration>,
}

/// The two error estimates of a film (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorEstimate {
    /// Relative standard error of the image mean.
    pub mean_rel_error: f64,
    /// 90th percentile of per-pixel relative standard error.
    pub pixel_rel_error: f64,
}

impl ErrorEstimate {
    /// The larger of the two.
    pub fn worst(&self) -> f64 {
        self.mean_rel_error.max(self.pixel_rel_error)
    }
}

/// Estimates the error of `film` from its per-pixel variance of the mean.
pub fn estimate_error(film: &Film) -> ErrorEstimate {
    let (mut sum, mut var) = (0f64, 0f64);
    for p in &film.pixels {
        sum += p.mean.element_sum() as f64;
        var += p.variance_of_mean().element_sum() as f64;
    }
    let mean_rel_error = if sum > 0.0 {
        var.sqrt() / sum
    } else {
        f64::INFINITY
    };
    let floor = 0.01 * sum / (3 * film.pixels.len().max(1)) as f64;
    let mut per_pixel: Vec<f64> = film
        .pixels
        .iter()
        .map(|p| {
            let m = p.mean.element_sum() as f64 / 3.0;
            let v = p.variance_of_mean().element_sum() as f64 / 3.0;
            v.sqrt() / (m.max(0.0) + floor).max(1e-30)
        })
        .collect();
    per_pixel.sort_by(f64::total_cmp);
    let pixel_rel_error = if per_pixel.is_empty() {
        f64::INFINITY
    } else {
        let i = ((per_pixel.len() - 1) as f64 * PIXEL_QUANTILE).round() as usize;
        per_pixel[i]
    };
    ErrorEstimate {
        mean_rel_error,
        pixel_rel_error,
    }
}

/// A finished reference.
#[derive(Clone, Debug)]
pub struct Reference {
    /// The merged render (time is the total).
    pub output: RenderOutput,
    /// Its error estimate.
    pub error: ErrorEstimate,
    /// Number of passes rendered.
    pub passes: u32,
    /// Whether the error target was met (false when a budget or a stop ended it).
    pub converged: bool,
}

/// Renders passes of `settings` (its `spp` is ignored) until `target` is met.
/// `progress` gets (spp so far, estimate) after each pass.
pub fn render_reference(
    scene: &Scene,
    settings: &RenderSettings,
    target: &ReferenceTarget,
    stop: &AtomicBool,
    progress: &dyn Fn(u32, &ErrorEstimate),
) -> Reference {
    let start = Instant::now();
    let control = Control::quiet(stop);
    let mut total: Option<RenderOutput> = None;
    let mut pass_spp = 4u32;
    let mut passes = 0;
    // Optimal MIS goes on learning its weights from pass to pass (its α comes from
    // earlier passes' samples only, so each pass stays unbiased under its own seed).
    let mut carry = Carry::default();
    loop {
        let done = total.as_ref().map_or(0, |t| t.spp);
        let mut spp = pass_spp;
        if let Some(max) = target.max_spp {
            spp = spp.min(max.saturating_sub(done));
        }
        // Keep a pass within the time left, at the speed seen so far.
        if let (Some(limit), Some(t)) = (target.max_time, &total) {
            let per_spp = start.elapsed().as_secs_f64() / t.spp.max(1) as f64;
            let left = limit.as_secs_f64() - start.elapsed().as_secs_f64();
            spp = spp.min((left / per_spp).floor().max(1.0) as u32);
        }
        let s = RenderSettings {
            spp,
            seed: round_seed(settings.seed, passes),
            ..settings.clone()
        };
        let out = render_carrying(scene, &s, &control, &mut carry);
        passes += 1;
        let merged = RenderOutput::merge(total.take(), out);
        let error = estimate_error(&merged.film);
        progress(merged.spp, &error);
        let converged = target.rel_error.is_some_and(|e| error.worst() <= e);
        let out_of_budget = target.max_spp.is_some_and(|m| merged.spp >= m)
            || target
                .max_time
                .is_some_and(|t| start.elapsed() >= t.mul_f64(0.98))
            || merged.stopped
            || stop.load(Ordering::Relaxed);
        let no_limit =
            target.rel_error.is_none() && target.max_spp.is_none() && target.max_time.is_none();
        total = Some(merged);
        if converged || out_of_budget || no_limit {
            let mut output = total.expect("one pass ran");
            output.time = start.elapsed();
            return Reference {
                output,
                error,
                passes,
                converged,
            };
        }
        pass_spp = pass_spp.saturating_mul(2).min(1 << 20);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Spectrum;
    use crate::scene;

    #[test]
    fn error_estimate_of_a_known_film() {
        let mut film = Film::new(2, 1);
        // Pixel 0: samples 1 and 3 (mean 2, Var(mean) = 2/2 = 1); pixel 1: constant 2.
        film.pixels[0].add(Spectrum::splat(1.0));
        film.pixels[0].add(Spectrum::splat(3.0));
        film.pixels[1].add(Spectrum::splat(2.0));
        film.pixels[1].add(Spectrum::splat(2.0));
        let e = estimate_error(&film);
        // √(3·1) / (3·2 + 3·2)
        assert!((e.mean_rel_error - 3f64.sqrt() / 12.0).abs() < 1e-9);
        // Quantile index round(0.9) = 1 of sorted [0, 1/(2 + 0.02)].
        assert!((e.pixel_rel_error - 1.0 / 2.02).abs() < 1e-6);
    }

    /// Under optimal MIS a reference's passes hand their α on: two passes (4 and 8 spp)
    /// give the film of the same two renders carried by hand, and not that of the
    /// second pass started afresh.
    #[test]
    fn optimal_mis_passes_carry_their_alpha() {
        let (scene, mut s) = crate::render::optimal_mis_veach(32, 24);
        s.seed = 7;
        let stop = AtomicBool::new(false);
        let target = ReferenceTarget {
            rel_error: None,
            max_spp: Some(12),
            max_time: None,
        };
        let reference = render_reference(&scene, &s, &target, &stop, &|_, _| {});
        assert_eq!((reference.passes, reference.output.spp), (2, 12));
        let control = Control::quiet(&stop);
        let pass = |k: u32, spp: u32, carry: &mut Carry| {
            let p = RenderSettings {
                spp,
                seed: round_seed(s.seed, k),
                ..s.clone()
            };
            render_carrying(&scene, &p, &control, carry)
        };
        let mut carry = Carry::default();
        let first = pass(0, 4, &mut carry);
        let carried = RenderOutput::merge(Some(first), pass(1, 8, &mut carry));
        let mut carry = Carry::default();
        let first = pass(0, 4, &mut carry);
        let afresh = RenderOutput::merge(Some(first), pass(1, 8, &mut Carry::default()));
        let bits = |o: &RenderOutput| crate::render::mean_bits(&o.film);
        assert_eq!(bits(&reference.output), bits(&carried));
        assert_ne!(bits(&carried), bits(&afresh));
    }

    #[test]
    fn stops_at_the_error_target_or_the_spp_limit() {
        let scene = scene::load("builtin:assignment").unwrap();
        let mut s = RenderSettings::for_scene(&scene);
        s.resolution = Some((24, 16));
        let stop = AtomicBool::new(false);
        let by_spp = ReferenceTarget {
            max_spp: Some(40),
            ..Default::default()
        };
        let r = render_reference(&scene, &s, &by_spp, &stop, &|_, _| {});
        assert_eq!((r.output.spp, r.passes), (40, 4)); // 4 + 8 + 16 + 12
        let by_error = ReferenceTarget {
            rel_error: Some(0.05),
            max_spp: Some(1 << 16),
            ..Default::default()
        };
        let r = render_reference(&scene, &s, &by_error, &stop, &|_, _| {});
        assert!(r.converged && r.error.worst() <= 0.05, "{:?}", r.error);
    }
}
