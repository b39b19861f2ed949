//! The `variance-1d` figure: the lecture's table of ∫cos x and ∫4cos¹⁶x under uniform,
//! cosine and tabulated densities, as a report.

use std::path::Path;

use serde_json::json;

use super::Figure;
use crate::lab::LabError;
use crate::lab::report::{Report, Table, command_line, write_report, write_text};
use crate::lab::variance_1d::variance_table;

/// Samples per strategy in the 1D table.
const VARIANCE_1D_SAMPLES: usize = 100_000;

/// Seed of the table when `--seed` is not given.
const DEFAULT_SEED: u64 = 1;

/// Writes the figure's report into `dir`, drawing from `seed` (`--seed`, default 1).
pub fn write_variance_1d(figure: &Figure, seed: Option<u64>, dir: &Path) -> Result<(), LabError> {
    let seed = seed.unwrap_or(DEFAULT_SEED);
    let rows = variance_table(VARIANCE_1D_SAMPLES, seed);
    let table = Table {
        caption: format!(
            "{VARIANCE_1D_SAMPLES} samples per row: the smoother f/p, the lower the variance"
        ),
        header: [
            "integrand",
            "density p",
            "estimate",
            "exact",
            "variance of f/p",
            "std. error",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.integrand.to_string(),
                    r.strategy.to_string(),
                    format!("{:.5}", r.estimate),
                    format!("{:.5}", r.exact),
                    format!("{:.4e}", r.variance),
                    format!("{:.2e}", r.standard_error()),
                ]
            })
            .collect(),
    };
    let report = Report {
        title: format!("figure {}", figure.name),
        command: command_line(),
        seeds: vec![seed],
        notes: vec![
            figure.description.to_string(),
            "Sampling with p = cos x makes f/p constant for ∫cos (zero variance) but not for ∫4cos¹⁶, which is far more peaked than p: importance sampling helps only as far as p follows f.".into(),
        ],
        tables: vec![table.clone()],
        ..Default::default()
    };
    write_report(dir, &report)?;
    write_text(
        &dir.join("results.md"),
        &format!("# figure {}\n\n{}\n", figure.name, table.markdown()),
    )?;
    let json = json!({
        "figure": figure.name,
        "command": report.command,
        "lightlab_version": crate::lab::report::VERSION,
        "rows": rows.iter().map(|r| json!({
            "integrand": r.integrand, "strategy": r.strategy, "estimate": r.estimate,
            "exact": r.exact, "variance": r.variance, "samples": r.samples,
        })).collect::<Vec<_>>(),
    });
    write_text(
        &dir.join("results.json"),
        &serde_json::to_string_pretty(&json).map_err(|e| LabError::Input(e.to_string()))?,
    )?;
    Ok(())
}
