//! `compare`: renders strategies at equal spp or equal time and judges each against a
//! reference: MSE, relMSE, relative bias, and relative efficiency 1/(relMSE·time)
//! (the inverse of the work needed for a given error; Veach 1997 §2.4 calls this the
//! efficiency of an estimator), normalised to the best strategy.
//!
//! Writes into its folder: `index.html` (viewer, table, insets, error maps),
//! `results.json`, `results.md`, and under `img/` each image as PNG and EXR, its
//! false-colour relMSE map, and magnified insets.

use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use serde_json::json;

use crate::image::io::write_film;
use crate::image::metrics::{ErrorReport, compare, false_color, signed_difference};
use crate::lab::LabError;
use crate::lab::budget::{Budget, render_budget};
use crate::lab::experiment::{
    ReferenceImage, ReferenceSource, load_scene, obtain_reference, resolve,
};
use crate::lab::insets::{Inset, check_insets, pick_insets, region_table, write_insets};
use crate::lab::report::{
    Gallery, Report, Table, ViewerImage, command_line, write_report, write_text, write_viewer_image,
};
use crate::lab::strategy::Strategy;
use crate::render::Control;
use crate::settings::RenderPatch;

/// What to compare.
#[derive(Clone, Debug)]
pub struct CompareConfig {
    /// The scene (`builtin:NAME`).
    pub scene: String,
    /// Strategies, in table order.
    pub strategies: Vec<Strategy>,
    /// Equal spp or equal time.
    pub budget: Budget,
    /// Render flags applied to every strategy (`--width 64 --seed 3`).
    pub base: RenderPatch,
    /// The reference.
    pub reference: ReferenceSource,
    /// Inset rectangles; empty picks two high-error regions.
    pub insets: Vec<Inset>,
    /// Report title (default: scene and budget).
    pub title: Option<String>,
    /// Paragraphs for the report.
    pub notes: Vec<String>,
    /// Links shown in the report (label, path relative to the report folder).
    pub links: Vec<(String, String)>,
}

/// One strategy's result.
#[derive(Clone, Debug)]
pub struct StrategyResult {
    /// Label.
    pub label: String,
    /// The flags that reproduce its render.
    pub flags: String,
    /// Samples per pixel rendered.
    pub spp: u32,
    /// Render time.
    pub time: Duration,
    /// Error against the reference.
    pub error: ErrorReport,
    /// 1/(relMSE·seconds).
    pub efficiency: f64,
    /// `efficiency` over the best strategy's.
    pub relative_efficiency: f64,
    /// Non-finite samples scored as zero.
    pub invalid_samples: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
}

/// |relative bias| above this many standard errors marks a result as biased.
pub const BIAS_Z_FLAG: f64 = 4.0;

/// Whether `error` shows bias beyond [`BIAS_Z_FLAG`] standard errors.
pub fn looks_biased(error: &ErrorReport) -> bool {
    error.bias_z().is_some_and(|z| z.abs() > BIAS_Z_FLAG)
}

/// Runs the comparison and writes its report into `dir`. `log` gets one line per step.
pub fn run_compare(
    config: &CompareConfig,
    dir: &Path,
    stop: &AtomicBool,
    log: &dyn Fn(&str),
) -> Result<Vec<StrategyResult>, LabError> {
    let scene = load_scene(&config.scene)?;
    let extra = match config.budget {
        Budget::Spp(n) => RenderPatch::spp(n),
        Budget::Time(_) => RenderPatch::default(),
    };
    let settings = resolve(&scene, &config.strategies, &config.base, &extra)?;
    let camera = settings[0].camera(&scene);
    let size = (camera.width, camera.height);
    // Before any rendering or writing: a bad inset must not leave a half-written report.
    check_insets(&config.insets, size.0, size.1)?;
    log(&format!(
        "reference for {} ({}x{})",
        config.scene, size.0, size.1
    ));
    let reference = obtain_reference(&scene, &config.reference, &config.base, size, stop)?;
    let mut results = Vec::new();
    let mut films = Vec::new();
    for (strategy, s) in config.strategies.iter().zip(&settings) {
        let control = Control::quiet(stop);
        let out = render_budget(&scene, s, config.budget, &control);
        let means = out.film.means();
        let variance: Vec<_> = out
            .film
            .pixels
            .iter()
            .map(|p| p.variance_of_mean())
            .collect();
        let error = compare(
            &means,
            Some(&variance),
            &reference.rgb,
            reference.variance.as_deref(),
        );
        let efficiency = 1.0 / (error.rel_mse.max(1e-300) * out.time.as_secs_f64().max(1e-9));
        log(&format!(
            "{}: {} spp in {:.2} s, relMSE {:.4e}",
            strategy.label,
            out.spp,
            out.time.as_secs_f64(),
            error.rel_mse
        ));
        results.push(StrategyResult {
            label: strategy.label.clone(),
            flags: crate::render::RenderSettings {
                spp: out.spp,
                ..s.clone()
            }
            .patch()
            .to_string(),
            spp: out.spp,
            time: out.time,
            error,
            efficiency,
            relative_efficiency: 0.0,
            invalid_samples: out.invalid_samples,
            shadow_rays: out.shadow_rays,
        });
        films.push(out.film);
    }
    let best = results.iter().map(|r| r.efficiency).fold(0.0, f64::max);
    for r in &mut results {
        r.relative_efficiency = r.efficiency / best;
    }
    write_outputs(config, dir, &reference, &results, &films)?;
    Ok(results)
}

fn write_outputs(
    config: &CompareConfig,
    dir: &Path,
    reference: &ReferenceImage,
    results: &[StrategyResult],
    films: &[crate::image::Film],
) -> Result<(), LabError> {
    crate::lab::report::create_dirs(dir)?;
    let (w, h) = (reference.width, reference.height);
    let slugs: Vec<String> = config.strategies.iter().map(Strategy::slug).collect();
    write_viewer_image(dir, "reference", w, h, &reference.rgb)?;
    // Linear copy, so later experiments (a figure's convergence plot) reuse the reference.
    crate::image::io::write_pfm(w, h, &reference.rgb, &dir.join("img/reference.pfm"))?;
    let mut viewer = vec![ViewerImage {
        label: "reference".into(),
        key: "reference".into(),
    }];
    let mut error_rows = Vec::new();
    let mut all_means = Vec::new();
    for ((r, film), slug) in results.iter().zip(films).zip(&slugs) {
        let means = film.means();
        write_viewer_image(dir, slug, w, h, &means)?;
        write_film(film, &dir.join("img").join(format!("{slug}.exr")), 0.0)?;
        let map = format!("img/{slug}-error.png");
        crate::image::io::write_rgb8_png(
            w,
            h,
            false_color(&means, &reference.rgb),
            &dir.join(&map),
        )?;
        viewer.push(ViewerImage {
            label: r.label.clone(),
            key: slug.clone(),
        });
        let bias = format!("img/{slug}-bias.png");
        crate::image::io::write_rgb8_png(
            w,
            h,
            signed_difference(&means, &reference.rgb, w, h),
            &dir.join(&bias),
        )?;
        error_rows.push((r.label.clone(), vec![format!("img/{slug}.png"), map, bias]));
        all_means.push(means);
    }
    let insets = if config.insets.is_empty() {
        pick_insets(&all_means, &reference.rgb, w, h, 2)
    } else {
        config.insets.clone()
    };
    let inset_gallery = write_insets(
        dir,
        &insets,
        reference,
        &all_means,
        &slugs,
        &config.strategies,
    )?;
    let table = results_table(results);
    let mut tables = vec![table.clone()];
    if !config.insets.is_empty() {
        let labels: Vec<String> = results.iter().map(|r| r.label.clone()).collect();
        tables.push(region_table(
            &insets,
            &reference.rgb,
            w,
            &all_means,
            &labels,
        ));
    }
    let title = config
        .title
        .clone()
        .unwrap_or_else(|| format!("{} at {}", config.scene, config.budget.describe()));
    let seeds = vec![config.base.seed.unwrap_or(0)];
    let mut notes = config.notes.clone();
    notes.push(format!(
        "scene: {}, {}x{}, {}",
        config.scene,
        w,
        h,
        config.budget.describe()
    ));
    notes.push(reference.description.clone());
    let rays: Vec<String> = results
        .iter()
        .map(|r| format!("{} {}", r.label, r.shadow_rays))
        .collect();
    notes.push(format!("shadow rays traced: {}", rays.join(", ")));
    for r in results.iter().filter(|r| looks_biased(&r.error)) {
        notes.push(format!(
            "warning: \"{}\" differs from the reference by {} = {:+.1} standard errors: biased (or the reference is)",
            r.label,
            r.error.relative_bias_percent(),
            r.error.bias_z().unwrap_or(0.0)
        ));
    }
    let report = Report {
        title: title.clone(),
        command: command_line(),
        seeds: seeds.clone(),
        notes: notes.clone(),
        viewer,
        tables: tables.clone(),
        galleries: vec![
            inset_gallery,
            Gallery {
                title: "Images and relMSE maps".into(),
                note: "False colour: per-pixel relMSE on a log scale, 1e-4 (dark blue) to 10 (yellow); magenta marks NaN/Inf. Difference: (image − reference)/reference of luminance over 8×8 blocks, red brighter, blue darker, saturated at ±50 %.".into(),
                columns: vec!["image".into(), "relMSE".into(), "difference".into()],
                rows: error_rows,
            },
        ],
        links: config.links.clone(),
    };
    write_report(dir, &report)?;
    let md = format!(
        "# {title}\n\n`{}`\n\nseeds: {:?}, lightlab {}\n\n{}\n\n{}",
        report.command,
        seeds,
        crate::lab::report::VERSION,
        notes.join("\n\n"),
        tables
            .iter()
            .map(Table::markdown)
            .collect::<Vec<_>>()
            .join("\n\n")
    );
    write_text(&dir.join("results.md"), &md)?;
    let json = json!({
        "title": title,
        "command": report.command,
        "seeds": seeds,
        "lightlab_version": crate::lab::report::VERSION,
        "scene": config.scene,
        "budget": config.budget.describe(),
        "width": w,
        "height": h,
        "reference": reference.description,
        "strategies": results.iter().map(|r| json!({
            "label": r.label,
            "flags": r.flags,
            "spp": r.spp,
            "time_s": r.time.as_secs_f64(),
            "mse": r.error.mse,
            "rel_mse": r.error.rel_mse,
            "relative_bias": r.error.relative_bias,
            "bias_std_error": r.error.bias_std_error,
            "biased": looks_biased(&r.error),
            "nan_pixels": r.error.nan_pixels,
            "inf_pixels": r.error.inf_pixels,
            "invalid_samples": r.invalid_samples,
            "shadow_rays": r.shadow_rays,
            "efficiency": r.efficiency,
            "relative_efficiency": r.relative_efficiency,
        })).collect::<Vec<_>>(),
    });
    let text = serde_json::to_string_pretty(&json).map_err(|e| LabError::Input(e.to_string()))?;
    write_text(&dir.join("results.json"), &text)?;
    Ok(())
}

/// A relative efficiency: three decimals, or two significant digits when tiny.
pub fn format_efficiency(e: f64) -> String {
    if e >= 0.001 || e == 0.0 {
        format!("{e:.3}")
    } else {
        format!("{e:.2e}")
    }
}

/// The results table: spp, time, MSE, relMSE, bias, efficiency.
pub fn results_table(results: &[StrategyResult]) -> Table {
    Table {
        caption: "Error against the reference; relative efficiency = 1/(relMSE·time), best = 1"
            .into(),
        header: [
            "strategy",
            "spp",
            "time (s)",
            "MSE",
            "relMSE",
            "bias (z)",
            "rel. efficiency",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .iter()
            .map(|r| {
                vec![
                    r.label.clone(),
                    r.spp.to_string(),
                    format!("{:.3}", r.time.as_secs_f64()),
                    format!("{:.4e}", r.error.mse),
                    format!("{:.4e}", r.error.rel_mse),
                    match r.error.bias_z() {
                        Some(z) => format!(
                            "{} ({:+.1}){}",
                            r.error.relative_bias_percent(),
                            z,
                            if looks_biased(&r.error) {
                                " biased"
                            } else {
                                ""
                            }
                        ),
                        None => r.error.relative_bias_percent(),
                    },
                    format_efficiency(r.relative_efficiency),
                ]
            })
            .collect(),
    }
}
