//! Sample budgets of an experiment: a fixed number of samples per pixel, or a wall-clock
//! time filled by rendering in rounds.
//!
//! A timed render runs rounds and merges their films (Chan et al. 1979, `Film::merge`).
//! With the Sobol and independent samplers round k continues the sequence where the
//! earlier rounds stopped (same seed, sample indices from the samples done), so a timed
//! render of N samples per pixel uses the very points of one N-sample render (its image
//! is that render's up to the order of the sums; under optimal MIS α is updated at other
//! round boundaries, so there the weights differ too): restarting
//! Sobol with a new seed per round made a timed render several short, independent Sobol
//! sets, 3–5× the error of one sequence at equal spp (BENCHMARKS.md). Stratified
//! sampling fixes its strata by the sample count, so its rounds are independent renders
//! under decorrelated seeds (round 0 uses the strategy's own seed): unbiased estimates
//! whose merge is unbiased with the pooled variance. Each
//! round asks for about a quarter of the time left at the speed measured so far, so the
//! total converges to the budget from below; rounds stop when less than half a sample per
//! pixel of time is left, or when a watcher thread signals the deadline (`render` then
//! finishes its current internal round: an eighth of the call, or on a small image up to
//! the whole call, about 10⁶ samples). Under optimal MIS the rounds hand on each pixel's
//! α and technique moments (`render::Carry`): learning α afresh in every round (each
//! starting from the balance heuristic) left 1.4× the relMSE of one render of as many
//! samples on `veach-mis` (BENCHMARKS.md).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::render::{Carry, Control, RenderOutput, RenderSettings, render, render_carrying};
use crate::scene::Scene;
use crate::settings::SamplerKind;

/// How much work each strategy gets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    /// Equal samples per pixel.
    Spp(u32),
    /// Equal wall-clock time.
    Time(Duration),
}

impl Budget {
    /// `equal spp (N)` or `equal time (S s)`.
    pub fn describe(&self) -> String {
        match self {
            Budget::Spp(n) => format!("equal spp ({n} spp)"),
            Budget::Time(t) => format!("equal time ({:.2} s)", t.as_secs_f64()),
        }
    }
}

/// The longest time budget, in seconds (a [`Duration`] holds up to about 1.8447e19).
pub const MAX_SECONDS: f64 = 1.8e19;

/// A wall-clock budget of `seconds`, or what is wrong with it: it must be positive (at
/// least a nanosecond), finite and at most [`MAX_SECONDS`] (`--time 1e300` is refused
/// here rather than panicking in the conversion to a [`Duration`]).
pub fn time_budget(seconds: f64) -> Result<Duration, String> {
    // Very large and very small values in exponent form: `{}` writes 1e300 with all its
    // 301 digits.
    let shown = if seconds != 0.0 && !(1e-6..1e15).contains(&seconds.abs()) {
        format!("{seconds:e}")
    } else {
        format!("{seconds}")
    };
    match Duration::try_from_secs_f64(seconds) {
        Ok(t) if seconds > 0.0 && seconds <= MAX_SECONDS && !t.is_zero() => Ok(t),
        _ if seconds > 0.0 && seconds < 1e-9 => Err(format!(
            "must be at least a nanosecond (1e-9 seconds), not {shown}"
        )),
        _ => Err(format!(
            "must be positive and at most {MAX_SECONDS:e} seconds, not {shown}"
        )),
    }
}

/// The seed of round `k` of a timed or progressive render: the base seed for round 0,
/// a decorrelated one after (the seed is hashed with the pixel, so any distinct value
/// gives independent streams).
pub fn round_seed(seed: u64, k: u32) -> u64 {
    if k == 0 {
        seed
    } else {
        seed ^ (k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
    }
}

/// Renders `settings` (whose `spp` is ignored for a time budget) within `budget`.
/// A stop request (`control.stop`) ends the render after the current round; progress
/// goes to `control.progress` as (samples done, samples total) for an spp budget and as
/// (milliseconds elapsed, milliseconds of budget) for a time budget.
pub fn render_budget(
    scene: &Scene,
    settings: &RenderSettings,
    budget: Budget,
    control: &Control<'_>,
) -> RenderOutput {
    match budget {
        Budget::Spp(n) => {
            let s = RenderSettings {
                spp: n,
                ..settings.clone()
            };
            render(scene, &s, control)
        }
        Budget::Time(limit) => render_timed(scene, settings, limit, control),
    }
}

fn render_timed(
    scene: &Scene,
    settings: &RenderSettings,
    limit: Duration,
    control: &Control<'_>,
) -> RenderOutput {
    let start = Instant::now();
    // A watcher raises `deadline` at the budget (or on an outside stop request), so a
    // round whose speed estimate was too optimistic still ends within one of `render`'s
    // own rounds (an eighth of the call, or about 10⁶ samples where that is more).
    let deadline = AtomicBool::new(false);
    let finished = AtomicBool::new(false);
    let millis = |d: Duration| u64::try_from(d.as_millis()).unwrap_or(u64::MAX);
    let progress = |_: u64, _: u64| (control.progress)(millis(start.elapsed()), millis(limit));
    let timed = Control {
        progress: &progress,
        stop: &deadline,
        frame: control.frame,
    };
    let out = std::thread::scope(|scope| {
        scope.spawn(|| {
            while !finished.load(Ordering::Relaxed) {
                if control.stop.load(Ordering::Relaxed) || start.elapsed() >= limit {
                    deadline.store(true, Ordering::Relaxed);
                    break;
                }
                std::thread::sleep(Duration::from_micros(500));
            }
        });
        // Optimal MIS goes on learning its weights from round to round.
        let out = rounds(scene, settings, limit, start, &timed, &mut Carry::default());
        finished.store(true, Ordering::Relaxed);
        out
    });
    RenderOutput {
        time: start.elapsed(),
        stopped: control.stop.load(Ordering::Relaxed),
        ..out
    }
}

/// The samples per pixel of a timed render's next round, with `left` seconds left at
/// `per_spp` seconds per spp and sample indices used up to `used`: a quarter of the time
/// left, at least one spp (it converges to the budget from below, and a round cut by the
/// deadline overshoots by at most one of `render`'s rounds), at most 2²⁰ spp, and never
/// past the last u32 sample index (`--time 1e9` asked for more; zero when none is left).
fn next_round_spp(left: f64, per_spp: f64, used: u32) -> u32 {
    let want = (0.25 * left / per_spp).ceil().min((1u32 << 20) as f64) as u32;
    want.max(1).min(u32::MAX - used)
}

/// Samples per pixel rendered so far.
fn total_spp(total: &Option<RenderOutput>) -> u32 {
    total.as_ref().map_or(0, |t| t.spp)
}

/// The rounds of a timed render (see the module docs), handing `carry` from each to
/// the next.
fn rounds(
    scene: &Scene,
    settings: &RenderSettings,
    limit: Duration,
    start: Instant,
    control: &Control<'_>,
    carry: &mut Carry,
) -> RenderOutput {
    let mut spp_next = 1u32;
    let mut total: Option<RenderOutput> = None;
    // Stratified strata need the sample count up front: its rounds are independent
    // renders under new seeds. The other samplers continue one sequence.
    let continues = settings.sampler != SamplerKind::Stratified;
    for k in 0.. {
        let done = total_spp(&total);
        let s = RenderSettings {
            spp: spp_next,
            seed: if continues {
                settings.seed
            } else {
                round_seed(settings.seed, k)
            },
            first_sample: if continues {
                settings.first_sample + done
            } else {
                settings.first_sample
            },
            ..settings.clone()
        };
        let out = render_carrying(scene, &s, control, carry);
        let merged = RenderOutput::merge(total.take(), out);
        let elapsed = start.elapsed().as_secs_f64();
        let per_spp = elapsed / merged.spp.max(1) as f64;
        let left = limit.as_secs_f64() - elapsed;
        let stopped = control.stop.load(Ordering::Relaxed);
        total = Some(merged);
        if stopped || left < 0.5 * per_spp {
            break;
        }
        let used = settings.first_sample.saturating_add(total_spp(&total));
        spp_next = next_round_spp(left, per_spp, used);
        if spp_next == 0 {
            break; // every u32 sample index is used
        }
    }
    total.expect("at least one round ran")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    #[test]
    fn time_budgets_are_positive_and_fit_a_duration() {
        assert_eq!(time_budget(1.5), Ok(Duration::from_millis(1500)));
        assert_eq!(
            time_budget(1e18),
            Ok(Duration::from_secs(1_000_000_000_000_000_000))
        );
        for (t, shown) in [
            (0.0, "not 0"),
            (-5.0, "not -5"),
            (f64::NAN, "not NaN"),
            (f64::INFINITY, "not inf"),
            (1e300, "not 1e300"),
            (1.81e19, "not 1.81e19"),
            (-1e20, "not -1e20"),
            (1e-12, "at least a nanosecond (1e-9 seconds), not 1e-12"),
            (1e-300, "not 1e-300"),
        ] {
            let e = time_budget(t).unwrap_err();
            assert!(e.ends_with(shown), "{t}: {e}");
        }
    }

    #[test]
    fn timed_render_is_whole_rounds_of_whole_images() {
        let scene = scene::load("builtin:assignment").unwrap();
        let mut s = RenderSettings::for_scene(&scene);
        s.resolution = Some((32, 24));
        let stop = AtomicBool::new(false);
        let limit = Duration::from_millis(300);
        let control = Control::quiet(&stop);
        let out = render_budget(&scene, &s, Budget::Time(limit), &control);
        // How close the time comes to the budget is measured outside the tests (`render
        // --time`, BENCHMARKS.md); here: several rounds, every pixel with every sample.
        assert!(out.spp > 1 && !out.stopped, "{} spp", out.spp);
        assert!(out.film.pixels.iter().all(|p| p.count == out.spp));
        assert_ne!(round_seed(3, 1), 3);
    }

    #[test]
    fn a_round_asks_for_at_most_a_million_spp_and_no_index_past_u32() {
        assert_eq!(next_round_spp(1.0, 0.01, 0), 25);
        assert_eq!(next_round_spp(1e-9, 0.01, 0), 1);
        assert_eq!(next_round_spp(1e9, 0.001, 0), 1 << 20);
        assert_eq!(next_round_spp(1e18, 1e-9, u32::MAX - 5), 5);
    }

    /// Under optimal MIS the rounds of a timed render hand their α on: the carry comes
    /// back filled (dropping it in `rounds` leaves it empty).
    #[test]
    fn timed_optimal_mis_rounds_carry_their_alpha() {
        let (scene, s) = crate::render::optimal_mis_veach(32, 24);
        let stop = AtomicBool::new(false);
        let control = Control::quiet(&stop);
        let mut carry = Carry::default();
        let start = Instant::now();
        let out = rounds(
            &scene,
            &s,
            Duration::from_millis(200),
            start,
            &control,
            &mut carry,
        );
        assert!(out.spp > 1, "{} spp", out.spp);
        assert!(!carry.is_empty());
    }

    /// With Sobol, a timed render in rounds is one sequence: its image is that of a single
    /// render of as many samples with the same seed (up to the order of the sums).
    #[test]
    fn timed_sobol_rounds_continue_one_sequence() {
        let scene = scene::load("builtin:assignment").unwrap();
        let mut s = RenderSettings::for_scene(&scene);
        s.resolution = Some((32, 24));
        s.sampler = SamplerKind::Sobol;
        let stop = AtomicBool::new(false);
        let control = Control::quiet(&stop);
        let timed = render_budget(
            &scene,
            &s,
            Budget::Time(Duration::from_millis(300)),
            &control,
        );
        assert!(timed.samples.len() > 1, "one round only");
        let once = render_budget(&scene, &s, Budget::Spp(timed.spp), &control);
        let (a, b) = (timed.film.means(), once.film.means());
        for (p, q) in a.iter().zip(&b) {
            let tolerance = 1e-4 * q.max_element() + 1e-6;
            assert!((*p - *q).abs().max_element() <= tolerance, "{p:?} vs {q:?}");
        }
    }
}
