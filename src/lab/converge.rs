//! `converge`: relMSE against spp and against time, on log–log axes, for every strategy.
//!
//! Each strategy renders at spp = 1, 2, 4, … up to the maximum, once per seed; a point
//! is the mean relMSE over seeds, its bar the spread (min to max). The slope is the
//! least-squares fit of log relMSE against log spp (or log time): −1 for independent
//! Monte Carlo (variance ∝ 1/N), steeper for stratified or QMC samplers where the
//! integrand is smooth (Owen 1997; Pharr et al., pbrt 4th ed. §8.2).

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::image::metrics::compare;
use crate::lab::LabError;
use crate::lab::budget::round_seed;
use crate::lab::experiment::{ReferenceSource, load_scene, obtain_reference, resolve};
use crate::lab::plot::{Curve, LogLogPlot, write_plot};
use crate::lab::report::{Gallery, Report, Table, command_line, write_report, write_text};
use crate::lab::strategy::Strategy;
use crate::math::Spectrum;
use crate::render::{RenderSettings, render_quiet};
use crate::scene::Scene;
use crate::settings::RenderPatch;

/// What to measure.
#[derive(Clone, Debug)]
pub struct ConvergeConfig {
    /// The scene.
    pub scene: String,
    /// Strategies.
    pub strategies: Vec<Strategy>,
    /// Largest spp (the points are powers of two up to it, and it).
    pub max_spp: u32,
    /// Seeds per point.
    pub seeds: u32,
    /// Flags applied to every strategy.
    pub base: RenderPatch,
    /// The reference.
    pub reference: ReferenceSource,
    /// Report title (default: scene).
    pub title: Option<String>,
}

/// One point: spp, mean time, and relMSE over seeds (mean, min, max).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConvergePoint {
    /// Samples per pixel.
    pub spp: u32,
    /// Mean render time in seconds.
    pub time: f64,
    /// Mean relMSE over seeds.
    pub rel_mse: f64,
    /// Smallest relMSE over seeds.
    pub rel_mse_min: f64,
    /// Largest relMSE over seeds.
    pub rel_mse_max: f64,
}

/// One strategy's curve and fitted slopes.
#[derive(Clone, Debug)]
pub struct ConvergeSeries {
    /// Label.
    pub label: String,
    /// Points in spp order.
    pub points: Vec<ConvergePoint>,
    /// Slope of log relMSE against log spp.
    pub slope_spp: f64,
    /// Slope of log relMSE against log time.
    pub slope_time: f64,
}

/// The spp of the points: 1, 2, 4, … below `max`, then `max`.
pub fn spp_points(max: u32) -> Vec<u32> {
    let mut v: Vec<u32> = (0..32)
        .map(|k| 1u32 << k)
        .take_while(|&n| n < max)
        .collect();
    v.push(max.max(1));
    v
}

/// Least-squares slope of log y against log x over points with x, y > 0
/// (NaN with fewer than two).
pub fn fit_log_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = logs.len() as f64;
    if logs.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        logs.iter().map(|p| p.0).sum::<f64>() / n,
        logs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx > 0.0 { sxy / sxx } else { f64::NAN }
}

/// Measures every strategy (no files written).
pub fn measure(
    config: &ConvergeConfig,
    stop: &AtomicBool,
    log: &dyn Fn(&str),
) -> Result<(Vec<ConvergeSeries>, String), LabError> {
    if config.seeds == 0 || config.max_spp == 0 {
        return Err(LabError::Input(
            "--seeds and --max-spp must be at least 1".into(),
        ));
    }
    let scene = load_scene(&config.scene)?;
    let settings = resolve(
        &scene,
        &config.strategies,
        &config.base,
        &RenderPatch::default(),
    )?;
    let camera = settings[0].camera(&scene);
    let size = (camera.width, camera.height);
    let reference = obtain_reference(&scene, &config.reference, &config.base, size, stop)?;
    log(&reference.description);
    let labels: Vec<String> = config.strategies.iter().map(|s| s.label.clone()).collect();
    let series = measure_settings(
        &scene,
        &labels,
        &settings,
        &spp_points(config.max_spp),
        config.seeds,
        &reference.rgb,
        stop,
        log,
    )?;
    Ok((series, reference.description))
}

/// Measures already resolved `settings` (one per label) on `scene` at each spp of
/// `spp_list`, `seeds` renders per point, against `reference` (linear RGB).
#[allow(clippy::too_many_arguments)] // reason: one flat list of the experiment's inputs
pub fn measure_settings(
    scene: &Scene,
    labels: &[String],
    settings: &[RenderSettings],
    spp_list: &[u32],
    seeds: u32,
    reference: &[Spectrum],
    stop: &AtomicBool,
    log: &dyn Fn(&str),
) -> Result<Vec<ConvergeSeries>, LabError> {
    let mut series = Vec::new();
    for (label, s) in labels.iter().zip(settings) {
        let mut points = Vec::new();
        for &spp in spp_list {
            let (mut errors, mut time) = (Vec::new(), 0.0);
            for k in 0..seeds {
                let run = RenderSettings {
                    spp,
                    seed: round_seed(s.seed, k),
                    ..s.clone()
                };
                let out = render_quiet(scene, &run);
                time += out.time.as_secs_f64();
                let e = compare(&out.film.means(), None, reference, None);
                errors.push(e.rel_mse);
            }
            if stop.load(Ordering::Relaxed) {
                return Err(LabError::Input("stopped".into()));
            }
            let n = errors.len() as f64;
            points.push(ConvergePoint {
                spp,
                time: time / n,
                rel_mse: errors.iter().sum::<f64>() / n,
                rel_mse_min: errors.iter().copied().fold(f64::INFINITY, f64::min),
                rel_mse_max: errors.iter().copied().fold(0.0, f64::max),
            });
        }
        let by_spp: Vec<_> = points.iter().map(|p| (p.spp as f64, p.rel_mse)).collect();
        let by_time: Vec<_> = points.iter().map(|p| (p.time, p.rel_mse)).collect();
        let (slope_spp, slope_time) = (fit_log_slope(&by_spp), fit_log_slope(&by_time));
        log(&format!(
            "{}: slope {:.3} (spp), {:.3} (time)",
            label, slope_spp, slope_time
        ));
        series.push(ConvergeSeries {
            label: label.clone(),
            points,
            slope_spp,
            slope_time,
        });
    }
    Ok(series)
}

/// Measures and writes `index.html`, `converge.csv`, `results.md` and the plots
/// `plots/error-vs-spp.{svg,png}` and `plots/error-vs-time.{svg,png}` into `dir`.
pub fn run_converge(
    config: &ConvergeConfig,
    dir: &Path,
    stop: &AtomicBool,
    log: &dyn Fn(&str),
) -> Result<Vec<ConvergeSeries>, LabError> {
    let (series, reference) = measure(config, stop, log)?;
    crate::lab::report::create_dirs(dir)?;
    let title = config
        .title
        .clone()
        .unwrap_or_else(|| format!("Convergence on {}", config.scene));
    for (stem, x_label, x_of) in [
        (
            "error-vs-spp",
            "samples per pixel",
            (|p: &ConvergePoint| p.spp as f64) as fn(&ConvergePoint) -> f64,
        ),
        ("error-vs-time", "render time (s)", |p: &ConvergePoint| {
            p.time
        }),
    ] {
        let plot = LogLogPlot {
            title: format!("relMSE vs {x_label}"),
            x_label: x_label.into(),
            y_label: "relMSE".into(),
            curves: series
                .iter()
                .map(|s| Curve {
                    label: format!(
                        "{} (slope {:.2})",
                        s.label,
                        if stem == "error-vs-spp" {
                            s.slope_spp
                        } else {
                            s.slope_time
                        }
                    ),
                    points: s
                        .points
                        .iter()
                        .map(|p| (x_of(p), p.rel_mse, p.rel_mse_min, p.rel_mse_max))
                        .collect(),
                })
                .collect(),
        };
        write_plot(&plot, &dir.join("plots").join(stem))?;
    }
    let mut csv = String::from("strategy,spp,time_s,rel_mse_mean,rel_mse_min,rel_mse_max,seeds\n");
    for s in &series {
        for p in &s.points {
            csv += &format!(
                "{},{},{:.6},{:.6e},{:.6e},{:.6e},{}\n",
                s.label.replace(',', ";"),
                p.spp,
                p.time,
                p.rel_mse,
                p.rel_mse_min,
                p.rel_mse_max,
                config.seeds
            );
        }
    }
    write_text(&dir.join("converge.csv"), &csv)?;
    let table = Table {
        caption: "Fitted slopes of log relMSE (−1: independent Monte Carlo)".into(),
        header: [
            "strategy",
            "slope vs spp",
            "slope vs time",
            "relMSE at max spp",
        ]
        .map(String::from)
        .to_vec(),
        rows: series
            .iter()
            .map(|s| {
                vec![
                    s.label.clone(),
                    format!("{:.3}", s.slope_spp),
                    format!("{:.3}", s.slope_time),
                    format!("{:.4e}", s.points.last().map_or(f64::NAN, |p| p.rel_mse)),
                ]
            })
            .collect(),
    };
    let seeds: Vec<u64> = (0..config.seeds)
        .map(|k| round_seed(config.base.seed.unwrap_or(0), k))
        .collect();
    let notes = vec![
        format!(
            "scene {}; spp {:?}; {} seeds per point; bars span the smallest to the largest relMSE over seeds; the data are in converge.csv.",
            config.scene,
            spp_points(config.max_spp),
            config.seeds
        ),
        reference,
    ];
    let report = Report {
        title: title.clone(),
        command: command_line(),
        seeds,
        notes: notes.clone(),
        viewer: vec![],
        tables: vec![table.clone()],
        galleries: vec![Gallery {
            title: "Plots".into(),
            note: "SVG versions sit beside the PNGs in plots/.".into(),
            columns: vec![],
            rows: vec![
                ("vs spp".into(), vec!["plots/error-vs-spp.png".into()]),
                ("vs time".into(), vec!["plots/error-vs-time.png".into()]),
            ],
        }],
        links: vec![("points (CSV)".into(), "converge.csv".into())],
    };
    write_report(dir, &report)?;
    write_text(
        &dir.join("results.md"),
        &format!(
            "# {title}\n\n`{}`\n\n{}\n\n{}",
            report.command,
            notes.join("\n\n"),
            table.markdown()
        ),
    )?;
    Ok(series)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_power_law_and_spp_points() {
        let pts: Vec<(f64, f64)> = [1.0, 2.0, 4.0, 8.0].iter().map(|&x| (x, 3.0 / x)).collect();
        assert!((fit_log_slope(&pts) + 1.0).abs() < 1e-12);
        assert!(fit_log_slope(&pts[..1]).is_nan());
        assert_eq!(spp_points(8), vec![1, 2, 4, 8]);
        assert_eq!(spp_points(6), vec![1, 2, 4, 6]);
        assert_eq!(spp_points(1), vec![1]);
    }
}
