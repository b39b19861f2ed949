//! The lecture's comparisons as data: each figure is one or more panels, a panel a scene
//! and labelled strategy flags, parsed and checked before anything renders.

use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use serde_json::json;

use crate::lab::LabError;
use crate::lab::budget::Budget;
use crate::lab::compare::{CompareConfig, StrategyResult, run_compare};
use crate::lab::converge::{ConvergeConfig, run_converge};
use crate::lab::experiment::{ReferenceSource, load_scene, resolve};
use crate::lab::insets::Inset;
use crate::lab::report::{Report, Table, command_line, write_report, write_text};
use crate::lab::strategy::{Strategy, slug};
use crate::settings::RenderPatch;

mod catalogue;
mod variance_1d;

pub use catalogue::FIGURES;
use variance_1d::write_variance_1d;

/// One comparison of a figure.
#[derive(Clone, Copy, Debug)]
pub struct Panel {
    /// Title (also the sub-folder name when a figure has several panels).
    pub title: &'static str,
    /// The scene.
    pub scene: &'static str,
    /// (label, flags) of each strategy.
    pub strategies: &'static [(&'static str, &'static str)],
    /// Equal spp of the comparison.
    pub spp: u32,
    /// The reference strategy's flags.
    pub reference: &'static str,
    /// Reference spp.
    pub reference_spp: u32,
    /// Regions to magnify and measure (empty: the two of highest error).
    pub insets: &'static [Inset],
}

/// What a figure computes.
#[derive(Clone, Copy, Debug)]
pub enum FigureKind {
    /// Image comparisons.
    Panels(&'static [Panel]),
    /// The lecture's 1D table: ∫cos vs ∫4cos¹⁶ under three densities.
    Variance1d,
}

/// A lecture figure.
#[derive(Clone, Copy, Debug)]
pub struct Figure {
    /// `lightlab figure NAME`.
    pub name: &'static str,
    /// What it shows.
    pub description: &'static str,
    /// Its content.
    pub kind: FigureKind,
}

/// The figure named `name`.
pub fn find(name: &str) -> Result<&'static Figure, LabError> {
    FIGURES.iter().find(|f| f.name == name).ok_or_else(|| {
        let known: Vec<_> = FIGURES.iter().map(|f| f.name).collect();
        LabError::Input(format!(
            "unknown figure \"{name}\" (known: {})",
            known.join(", ")
        ))
    })
}

/// Run-time choices: flags for every render, optional spp overrides, or an equal-time
/// budget.
#[derive(Clone, Debug, Default)]
pub struct FigureOptions {
    /// Flags applied to every strategy (`--width`, `--seed`, ...).
    pub base: RenderPatch,
    /// Override of the panels' equal spp.
    pub spp: Option<u32>,
    /// Equal wall-clock time per strategy instead of the panels' equal spp.
    pub time: Option<Duration>,
    /// Override of the reference spp.
    pub reference_spp: Option<u32>,
    /// Also plot convergence up to this spp (sub-report `converge/` of each panel).
    pub converge: Option<u32>,
}

/// Seeds per point of a figure's convergence plot.
const CONVERGE_SEEDS: u32 = 4;

/// Runs one panel: the comparison, then (if asked) its convergence plot against the
/// comparison's reference.
fn run_panel(
    config: &CompareConfig,
    options: &FigureOptions,
    dir: &Path,
    stop: &AtomicBool,
    log: &dyn Fn(&str),
) -> Result<Vec<StrategyResult>, LabError> {
    let mut config = config.clone();
    if options.converge.is_some() {
        config
            .links
            .push(("convergence plots".into(), "converge/index.html".into()));
    }
    let results = run_compare(&config, dir, stop, log)?;
    if let Some(max_spp) = options.converge {
        let converge = ConvergeConfig {
            scene: config.scene.clone(),
            strategies: config.strategies.clone(),
            max_spp,
            seeds: CONVERGE_SEEDS,
            base: config.base.clone(),
            reference: ReferenceSource::File(dir.join("img/reference.pfm")),
            title: config.title.as_ref().map(|t| format!("{t}: convergence")),
        };
        run_converge(&converge, &dir.join("converge"), stop, log)?;
    }
    Ok(results)
}

/// The compare configuration of each panel of `figure`, with its strategies parsed and
/// checked against the panel's scene.
pub fn plan(figure: &Figure, options: &FigureOptions) -> Result<Vec<CompareConfig>, LabError> {
    let FigureKind::Panels(panels) = figure.kind else {
        return Ok(vec![]);
    };
    let strategy = |label: &str, flags: &str| {
        Strategy::parse(&format!("{label}:{flags}")).map_err(LabError::Input)
    };
    let mut configs = Vec::new();
    for panel in panels {
        let strategies = panel
            .strategies
            .iter()
            .map(|(label, flags)| strategy(label, flags))
            .collect::<Result<Vec<_>, _>>()?;
        let reference = strategy("reference", panel.reference)?;
        let scene = load_scene(panel.scene)?;
        resolve(&scene, &strategies, &options.base, &RenderPatch::default())?;
        resolve(
            &scene,
            std::slice::from_ref(&reference),
            &options.base,
            &RenderPatch::default(),
        )?;
        configs.push(CompareConfig {
            scene: panel.scene.to_string(),
            strategies,
            budget: match options.time {
                Some(t) => Budget::Time(t),
                None => Budget::Spp(options.spp.unwrap_or(panel.spp)),
            },
            base: options.base.clone(),
            reference: ReferenceSource::Render {
                strategy: reference,
                spp: options.reference_spp.unwrap_or(panel.reference_spp),
            },
            insets: panel.insets.to_vec(),
            title: Some(if panels.len() == 1 {
                format!("figure {}", figure.name)
            } else {
                format!("figure {}: {}", figure.name, panel.title)
            }),
            notes: vec![format!("Figure {}: {}.", figure.name, figure.description)],
            links: vec![],
        });
    }
    Ok(configs)
}

/// Runs `figure` and writes its report into `dir`. Returns each panel's results.
pub fn run_figure(
    figure: &Figure,
    options: &FigureOptions,
    dir: &Path,
    stop: &AtomicBool,
    log: &dyn Fn(&str),
) -> Result<Vec<(String, Vec<StrategyResult>)>, LabError> {
    if let FigureKind::Variance1d = figure.kind {
        if options.time.is_some() {
            return Err(LabError::Input(format!(
                "figure {} is a table of variances, not renders: it takes no --time",
                figure.name
            )));
        }
        write_variance_1d(figure, options.base.seed, dir)?;
        return Ok(vec![]);
    }
    let configs = plan(figure, options)?;
    if configs.len() == 1 {
        let results = run_panel(&configs[0], options, dir, stop, log)?;
        return Ok(vec![(figure.name.to_string(), results)]);
    }
    let mut all = Vec::new();
    let mut links = Vec::new();
    let mut table = Table {
        caption: format!(
            "Every panel at {}; relative efficiency within each panel",
            match options.time {
                Some(t) => Budget::Time(t).describe(),
                None => "equal spp".into(),
            }
        ),
        header: [
            "panel",
            "strategy",
            "spp",
            "time (s)",
            "relMSE",
            "rel. efficiency",
        ]
        .map(String::from)
        .to_vec(),
        rows: vec![],
    };
    let FigureKind::Panels(panels) = figure.kind else {
        return Ok(all);
    };
    for (config, panel) in configs.iter().zip(panels.iter()) {
        let name = slug(panel.title);
        let results = run_panel(config, options, &dir.join(&name), stop, log)?;
        for r in &results {
            table.rows.push(vec![
                config.scene.clone(),
                r.label.clone(),
                r.spp.to_string(),
                format!("{:.3}", r.time.as_secs_f64()),
                format!("{:.4e}", r.error.rel_mse),
                crate::lab::compare::format_efficiency(r.relative_efficiency),
            ]);
        }
        links.push((
            config.title.clone().unwrap_or_default(),
            format!("{name}/index.html"),
        ));
        all.push((name, results));
    }
    let report = Report {
        title: format!("figure {}", figure.name),
        command: command_line(),
        seeds: vec![options.base.seed.unwrap_or(0)],
        notes: vec![figure.description.to_string()],
        viewer: vec![],
        tables: vec![table.clone()],
        galleries: vec![],
        links,
    };
    write_report(dir, &report)?;
    write_text(
        &dir.join("results.md"),
        &format!(
            "# figure {}\n\n{}\n\n{}",
            figure.name,
            figure.description,
            table.markdown()
        ),
    )?;
    let json = json!({
        "figure": figure.name,
        "command": report.command,
        "lightlab_version": crate::lab::report::VERSION,
        "panels": all.iter().map(|(name, rs)| json!({
            "panel": name,
            "results": format!("{name}/results.json"),
            "rel_mse": rs.iter().map(|r| (r.label.clone(), r.error.rel_mse)).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    });
    write_text(
        &dir.join("results.json"),
        &serde_json::to_string_pretty(&json).map_err(|e| LabError::Input(e.to_string()))?,
    )?;
    Ok(all)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_figure_plans() {
        let opts = FigureOptions::default();
        assert_eq!(plan(find("assignment").unwrap(), &opts).unwrap().len(), 1);
        for f in FIGURES {
            let configs = plan(f, &opts).unwrap();
            assert_eq!(
                configs.is_empty(),
                matches!(f.kind, FigureKind::Variance1d),
                "{}",
                f.name
            );
        }
        assert!(find("nope").is_err());
    }

    #[test]
    fn a_time_budget_replaces_every_panels_spp() {
        let opts = FigureOptions {
            time: Some(Duration::from_millis(1500)),
            spp: Some(7),
            ..FigureOptions::default()
        };
        for f in FIGURES {
            for config in plan(f, &opts).unwrap() {
                assert_eq!(config.budget, Budget::Time(Duration::from_millis(1500)));
            }
        }
        let configs = plan(find("ris").unwrap(), &FigureOptions::default()).unwrap();
        assert!(matches!(configs[0].budget, Budget::Spp(_)));
    }
}
