//! The chi-square harness for tests: runs `lightlab::sampling::chi2` on a table of cases
//! (the registry, or any closures), corrects the significance for the number of cases
//! (Šidák), prints every p-value, and on failure writes the observed and expected
//! histograms to `target/chi2-failures/NAME.txt`, naming the file in the panic. Tables
//! run their cases in parallel (rayon), each on a fixed seed, so results do not depend
//! on the order; each case's line is printed afterwards, in the table's order, by the
//! test's own thread (whose output the harness captures: rayon's workers are not it).
//!
//! Later suites (BSDFs, lights, environment maps) call [`check`] with their own sample
//! and pdf closures and a [`Domain`]; see `tests/chi2_warps.rs` for the pattern.

use std::path::PathBuf;

use glam::{Vec2, Vec3};
use lightlab::sampling::Rng32;
use lightlab::sampling::chi2::{Chi2Config, Chi2Report, Domain, chi2_test, integrate_pdf};
use lightlab::sampling::registry::{self, Draw, Entry, Family};
use rayon::prelude::*;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Family-wise significance level of a table of tests.
pub const SIGNIFICANCE: f64 = 0.01;

/// Fixed seed of every chi-square stream.
pub const SEED: u64 = 0x5eed_c412;

/// Šidák-corrected level for one of `tests` tests at family-wise level `alpha`:
/// 1 − (1 − α)^(1/tests).
pub fn sidak(alpha: f64, tests: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / tests.max(1) as f64)
}

/// [`sidak`] at the chi-square tables' level [`SIGNIFICANCE`].
pub fn sidak_alpha(tests: usize) -> f64 {
    sidak(SIGNIFICANCE, tests)
}

/// Where failing histograms go: `target/chi2-failures/`.
fn failure_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("..")
        .join("chi2-failures")
}

/// A case's printed line (its p-value) and its verdict: [`judge`] without the printing,
/// for cases run on other threads.
pub type Verdict = (String, Result<(), String>);

/// Checks a report at level `alpha`: prints its p-value, and on failure writes the tables
/// and returns a message naming the file.
pub fn judge(name: &str, report: &Chi2Report, alpha: f64) -> Result<(), String> {
    let (line, verdict) = verdict(name, report, alpha);
    println!("{line}");
    verdict
}

/// [`judge`], the line returned rather than printed.
pub fn verdict(name: &str, report: &Chi2Report, alpha: f64) -> Verdict {
    let line = format!(
        "{name:32} p-value: {:.6}  (chi2 = {:.1}, dof = {})",
        report.p_value, report.statistic, report.dof
    );
    // Cross-check the library's incomplete gamma against statrs.
    if report.failure.is_none() && report.dof > 0 {
        let reference = ChiSquared::new(report.dof as f64)
            .map(|d| d.sf(report.statistic))
            .unwrap_or(f64::NAN);
        if (reference - report.p_value).abs() >= 1e-6 || reference.is_nan() {
            let why = format!(
                "{name}: p-value {} but statrs says {reference}",
                report.p_value
            );
            return (line, Err(why));
        }
    }
    if report.passed(alpha) {
        return (line, Ok(()));
    }
    let dir = failure_dir();
    let path = dir.join(format!("{name}.txt"));
    let why = report
        .failure
        .clone()
        .unwrap_or_else(|| format!("p-value {:.3e} < {alpha:.3e}", report.p_value));
    let written = std::fs::create_dir_all(&dir)
        .and_then(|_| std::fs::write(&path, format!("{name}: {why}\n{}", report.tables())));
    let saved = match written {
        Ok(()) => format!("histograms in {}", path.display()),
        Err(e) => format!("could not write {}: {e}", path.display()),
    };
    (line, Err(format!("{name}: {why}; {saved}")))
}

/// Prints the verdicts' lines in order and returns their failures.
pub fn report_all(verdicts: Vec<Verdict>) -> Vec<String> {
    verdicts
        .into_iter()
        .filter_map(|(line, verdict)| {
            println!("{line}");
            verdict.err()
        })
        .collect()
}

/// One chi-square test of a sampler against a pdf over `domain` with `samples` samples:
/// its line and verdict ([`verdict`]; [`report_all`] prints the lines).
pub fn checked(
    name: &str,
    domain: &Domain,
    sample: &mut dyn FnMut(&mut Rng32) -> (Vec3, f32),
    pdf: &dyn Fn(Vec3) -> f32,
    samples: usize,
    alpha: f64,
) -> Verdict {
    let report = chi2_test(domain, sample, pdf, &Chi2Config::new(domain, samples, SEED));
    verdict(name, &report, alpha)
}

/// Panics listing every failure, after all cases have run.
fn conclude(failures: Vec<String>) {
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The registry's entries of one family.
pub fn entries(family: Family) -> Vec<Entry> {
    registry::all()
        .into_iter()
        .filter(|e| e.family == family)
        .collect()
}

/// Chi-square test of every entry of `family`, Šidák-corrected over the table.
pub fn chi2_all(family: Family) {
    let table = entries(family);
    let alpha = sidak_alpha(table.len());
    // One stream per row, so rows that are affine images of each other stay independent.
    let verdicts = table
        .par_iter()
        .enumerate()
        .map(|(i, e)| verdict(&e.name, &e.chi2(SEED + i as u64), alpha))
        .collect();
    conclude(report_all(verdicts));
}

/// Every pdf of `family` integrates to one over its domain (to within 2·10⁻³: caps
/// around peaked lobes leave out up to 10⁻⁴ of the mass by design).
pub fn integrates_to_one(family: Family) {
    let failures = entries(family)
        .par_iter()
        .filter_map(|e| {
            let resolution = e.chi2_config(SEED).resolution;
            match integrate_pdf(&e.domain, &*e.pdf, resolution) {
                Ok(total) if (total - 1.0).abs() < 2e-3 => None,
                Ok(total) => Some(format!("{}: pdf integrates to {total}", e.name)),
                Err(why) => Some(format!("{}: {why}", e.name)),
            }
        })
        .collect();
    conclude(failures);
}

/// The u grid of round-trip tests, away from the singular edges.
fn interior_grid() -> impl Iterator<Item = Vec2> {
    (0..=24).flat_map(|i| {
        (0..=24).map(move |j| Vec2::new(0.02 + 0.04 * i as f32, 0.02 + 0.04 * j as f32))
    })
}

/// |inverse(sample(u)) − u| < 10⁻⁴ for every entry of `family` with an inverse.
pub fn inverses_round_trip(family: Family) {
    let mut failures = Vec::new();
    for e in entries(family) {
        let (Draw::Square(draw), Some(inverse)) = (&e.draw, &e.inverse) else {
            continue;
        };
        let one_d = e.domain.is_one_dimensional();
        for u in interior_grid() {
            let back = inverse(draw(u).0);
            let error = if one_d {
                (back.x - u.x).abs()
            } else {
                (back - u).abs().max_element()
            };
            if error.is_nan() || error >= 1e-4 {
                failures.push(format!("{}: u = {u} comes back as {back}", e.name));
                break;
            }
        }
    }
    conclude(failures);
}

/// u = 0 and u → 1 (in each coordinate) give a finite value and a pdf that is finite
/// unless the pdf function itself is singular there (x = ξ² at 0).
pub fn edges_are_finite(family: Family) {
    let top = 1.0 - f32::EPSILON / 2.0;
    let corners = [
        Vec2::ZERO,
        Vec2::splat(top),
        Vec2::new(0.0, top),
        Vec2::new(top, 0.0),
    ];
    let mut failures = Vec::new();
    for e in entries(family) {
        let Draw::Square(draw) = &e.draw else {
            continue;
        };
        for u in corners {
            let (x, pdf) = draw(u);
            let singular = (e.pdf)(x).is_infinite() && pdf.is_infinite();
            if !x.is_finite() || pdf.is_nan() || pdf < 0.0 || (pdf.is_infinite() && !singular) {
                failures.push(format!("{}: u = {u} gives {x} with pdf {pdf}", e.name));
            }
        }
    }
    conclude(failures);
}
