//! The lab end to end: error metrics on hand-computed images, convergence slopes, the
//! equal-time budget, the report's self-containment, and the merge of render passes.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use glam::Vec3;
use lightlab::bsdf::{Diffuse, Material};
use lightlab::image::io::read_image;
use lightlab::image::metrics::compare;
use lightlab::integrator::EstimatorKind;
use lightlab::lab::budget::Budget;
use lightlab::lab::compare::{CompareConfig, looks_biased, run_compare};
use lightlab::lab::converge::measure_settings;
use lightlab::lab::experiment::ReferenceSource;
use lightlab::lab::strategy::Strategy;
use lightlab::math::Spectrum;
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::sampling::SamplerKind;
use lightlab::scene::Camera;
use lightlab::scene::builder::Emission;
use lightlab::scene::{Scene, SceneBuilder};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lightlab-lab-{name}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Fails with the command's stderr unless it exited 0.
fn assert_succeeded(out: &std::process::Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn flags(text: &str) -> Vec<String> {
    text.split_whitespace().map(str::to_string).collect()
}

#[test]
fn metrics_on_hand_computed_images() {
    // Reference 2 pixels: (1,1,1) and (0.5,0.5,0.5); image: (1.1,1,0.9) and (0.5,0.5,0.7).
    let r = [Spectrum::splat(1.0), Spectrum::splat(0.5)];
    let v = [Spectrum::new(1.1, 1.0, 0.9), Spectrum::new(0.5, 0.5, 0.7)];
    let e = compare(&v, None, &r, None);
    // Squared errors: 0.01, 0, 0.01, 0, 0, 0.04 -> MSE = 0.06/6.
    assert!((e.mse - 0.01).abs() < 1e-7, "{e:?}");
    // relMSE: 0.01/1.01 twice, 0.04/0.26 once, over 6 values.
    let rel = (2.0 * 0.01 / 1.01 + 0.04 / 0.26) / 6.0;
    assert!((e.rel_mse - rel).abs() < 1e-6, "{e:?}");
    // Bias: (Σv − Σr)/Σr = (4.7 − 4.5)/4.5.
    assert!((e.relative_bias.unwrap() - 0.2 / 4.5).abs() < 1e-6);
    // Against itself: exactly zero.
    let same = compare(&v, None, &v, None);
    assert_eq!(
        (same.mse, same.rel_mse, same.relative_bias),
        (0.0, 0.0, Some(0.0))
    );
    // A render 5% too bright with a small per-pixel variance is flagged; the same image
    // with a variance that explains the difference is not.
    let n = 400;
    let reference = vec![Spectrum::splat(1.0); n];
    let biased = vec![Spectrum::splat(1.05); n];
    let small = vec![Spectrum::splat(1e-4); n];
    let large = vec![Spectrum::splat(1.0); n];
    assert!(looks_biased(&compare(
        &biased,
        Some(&small),
        &reference,
        None
    )));
    assert!(!looks_biased(&compare(
        &biased,
        Some(&large),
        &reference,
        None
    )));
    assert!(!looks_biased(&compare(
        &reference,
        Some(&small),
        &reference,
        None
    )));
}

/// A white Lambertian floor lit by a large rectangle overhead, seen from above: every
/// pixel's radiance is E/π with E from Lambert's polygon formula, smooth and bounded,
/// so per-sample variance is finite and relMSE falls as 1/N.
fn lambert_scene() -> Scene {
    let mut b = SceneBuilder::new("lambert");
    let white = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::ONE,
    }));
    b.rectangle(
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0),
        white,
        None,
    );
    b.rectangle(
        Vec3::new(-0.8, 1.0, -0.8),
        Vec3::new(1.6, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.6),
        white,
        Some(Emission::new(Spectrum::splat(2.0))),
    );
    let camera = Camera::look_at(Vec3::new(0.0, 0.9, 0.01), Vec3::ZERO, Vec3::Y, 60.0, 12, 12);
    b.build(camera, 1).expect("scene")
}

#[test]
fn independent_sampler_converges_at_slope_minus_one() {
    let scene = lambert_scene();
    let stop = AtomicBool::new(false);
    let mut settings = RenderSettings::for_scene(&scene);
    settings.sampler = SamplerKind::Independent;
    settings.seed = 11;
    // The answer: the same estimator at 64× the largest spp (its own relMSE is 1/64 of
    // the last point's and flattens the slope by under 0.01).
    let reference = render_quiet(
        &scene,
        &RenderSettings {
            spp: 4096,
            seed: 99,
            ..settings.clone()
        },
    )
    .film
    .means();
    let mut labels = Vec::new();
    let mut all = Vec::new();
    for kind in [EstimatorKind::Cosine, EstimatorKind::Light] {
        labels.push(kind.to_string());
        all.push(RenderSettings {
            estimator: kind,
            ..settings.clone()
        });
    }
    let spp = [1, 2, 4, 8, 16, 32, 64];
    let series =
        measure_settings(&scene, &labels, &all, &spp, 8, &reference, &stop, &|_| {}).unwrap();
    for s in &series {
        println!("{}: slope {:.3}", s.label, s.slope_spp);
        assert!(
            (s.slope_spp + 1.0).abs() < 0.15,
            "{}: slope {}",
            s.label,
            s.slope_spp
        );
    }
    // The test can fail: Sobol points on this smooth integrand converge faster than 1/N.
    let sobol: Vec<_> = all
        .iter()
        .map(|s| RenderSettings {
            sampler: SamplerKind::Sobol,
            ..s.clone()
        })
        .collect();
    let series =
        measure_settings(&scene, &labels, &sobol, &spp, 8, &reference, &stop, &|_| {}).unwrap();
    for s in &series {
        println!("{} (sobol): slope {:.3}", s.label, s.slope_spp);
        assert!(
            s.slope_spp < -1.15,
            "{}: Sobol slope {}",
            s.label,
            s.slope_spp
        );
    }
}

#[test]
fn equal_time_compare_and_a_self_contained_report() {
    let dir = scratch("compare");
    let budget = 0.4;
    let config = CompareConfig {
        scene: "builtin:assignment".into(),
        strategies: Strategy::parse_list("light,cosine:--estimator cosine").unwrap(),
        budget: Budget::Time(Duration::from_secs_f64(budget)),
        base: "--width 48".parse().unwrap(),
        reference: ReferenceSource::Render {
            strategy: Strategy::parse("light").unwrap(),
            spp: 64,
        },
        insets: vec![],
        title: None,
        notes: vec![],
        links: vec![],
    };
    let stop = AtomicBool::new(false);
    let results = run_compare(&config, &dir, &stop, &|_| {}).unwrap();
    // How close a timed render comes to its budget is measured in a benchmark, not here.
    for r in &results {
        assert!(r.spp >= 1 && r.error.rel_mse > 0.0, "{}", r.label);
    }
    for file in [
        "index.html",
        "results.json",
        "results.md",
        "report.js",
        "report.css",
    ] {
        assert!(dir.join(file).is_file(), "{file} missing");
    }
    let json = fs::read_to_string(dir.join("results.json")).unwrap();
    assert!(json.contains("\"relative_efficiency\"") && json.contains("\"seeds\""));
    check_references(&dir);
    let _ = fs::remove_dir_all(dir);
}

/// Every `src="…"` and `href="…"` in `dir/index.html` names a file inside `dir` that
/// exists (only `data:` URIs are allowed besides).
fn check_references(dir: &Path) {
    let html = fs::read_to_string(dir.join("index.html")).unwrap();
    let mut count = 0;
    for attr in ["src=\"", "href=\""] {
        for (i, _) in html.match_indices(attr) {
            let rest = &html[i + attr.len()..];
            let target = &rest[..rest.find('"').unwrap()];
            if target.starts_with("data:") {
                continue;
            }
            assert!(
                !target.contains("://") && !target.starts_with('/') && !target.contains(".."),
                "{target} leaves the report folder"
            );
            assert!(dir.join(target).is_file(), "{target} does not exist");
            count += 1;
        }
    }
    assert!(count > 10, "only {count} references found");
}

#[test]
fn merged_passes_equal_the_whole_render() {
    let dir = scratch("merge");
    let bin = env!("CARGO_BIN_EXE_lightlab");
    let common =
        flags("render builtin:assignment --width 40 --spp 10 --sampler stratified --seed 4");
    let run = |extra: &[&str]| {
        let out = Command::new(bin)
            .args(&common)
            .args(extra)
            .output()
            .unwrap();
        assert_succeeded(&out);
    };
    let whole = dir.join("whole.exr");
    run(&["-o", whole.to_str().unwrap()]);
    let mut parts = Vec::new();
    for i in 1..=3 {
        let part = dir.join(format!("part{i}.exr"));
        run(&["--pass", &format!("{i}/3"), "-o", part.to_str().unwrap()]);
        parts.push(part.to_str().unwrap().to_string());
    }
    let merged = dir.join("merged.exr");
    let out = Command::new(bin)
        .arg("merge")
        .args(&parts)
        .args(["-o", merged.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (a, b) = (read_image(&whole).unwrap(), read_image(&merged).unwrap());
    assert_eq!((a.width, a.height, a.spp), (b.width, b.height, b.spp));
    assert_eq!(a.spp, Some(10));
    let close = |x: f32, y: f32, tol: f32| (x - y).abs() <= tol * x.abs().max(y.abs()).max(1e-6);
    let (va, vb) = (a.variance.unwrap(), b.variance.unwrap());
    for i in 0..a.rgb.len() {
        for c in 0..3 {
            assert!(close(a.rgb[i][c], b.rgb[i][c], 1e-5), "mean at {i}");
            assert!(close(va[i][c], vb[i][c], 1e-3), "variance at {i}");
        }
    }
    // The merged file records every part's samples, so it merges on with a further seed
    // but not with one of its own parts.
    let merge = |parts: &[&Path], name: &str| {
        Command::new(bin)
            .arg("merge")
            .args(parts)
            .args(["-o", dir.join(name).to_str().unwrap()])
            .output()
            .unwrap()
    };
    let other_seed = dir.join("seed5.exr");
    let out = Command::new(bin)
        .args(flags(
            "render builtin:assignment --width 40 --spp 10 --sampler stratified --seed 5",
        ))
        .args(["-o", other_seed.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success());
    let out = merge(&[&merged, &other_seed], "twenty.exr");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(read_image(&dir.join("twenty.exr")).unwrap().spp, Some(20));
    let part1 = Path::new(&parts[0]);
    let refused = |out: std::process::Output, words: &[&str]| {
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(out.status.code(), Some(2), "{err}");
        for w in words {
            assert!(err.contains(w), "{w:?} not in {err}");
        }
    };
    refused(
        merge(&[&merged, part1], "x.exr"),
        &["part1.exr", "overlap", "4:0..3"],
    );
    let half = dir.join("half.exr");
    run(&["--pass", "1/2", "-o", half.to_str().unwrap()]);
    refused(
        merge(&[part1, &half], "x.exr"),
        &["half.exr", "4:0..5 overlap samples 4:0..3"],
    );
    let other_scene = dir.join("veach.exr");
    let height = a.height.to_string();
    let out = Command::new(bin)
        .args(flags(
            "render builtin:veach-mis --width 40 --spp 10 --sampler stratified --seed 9",
        ))
        .args(["--height", &height, "-o", other_scene.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success());
    refused(
        merge(&[&whole, &other_scene], "x.exr"),
        &["veach.exr", "scene_hash", "builtin:veach-mis"],
    );
    // A part that is not a lightlab EXR is refused with a message, not a panic.
    let png = dir.join("x.png");
    run(&["-o", png.to_str().unwrap()]);
    let out = Command::new(bin)
        .args(["merge", png.to_str().unwrap(), "-o"])
        .arg(dir.join("bad.exr"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let _ = fs::remove_dir_all(dir);
}

/// `probe` records exactly the terms the estimator adds up, with one light and one BSDF
/// record per MIS sample, weights in [0, 1], and an estimate that agrees with another
/// estimator's at the same point (z-test); it writes its files and refuses bad pixels.
#[test]
fn probe_records_the_estimators_own_terms() {
    use lightlab::lab::probe::probe;
    let scene = lightlab::scene::load("builtin:assignment").unwrap();
    let settings = |estimator: EstimatorKind, spp: u32| RenderSettings {
        estimator,
        spp,
        ..RenderSettings::for_scene(&scene)
    };
    // A floor point near the diffuse sphere's shadow, lit by the rectangle.
    let pixel = (200, 150);
    let mis = probe(&scene, &settings(EstimatorKind::Mis, 4096), pixel).unwrap();
    let light = probe(&scene, &settings(EstimatorKind::Light, 4096), pixel).unwrap();
    for r in [&mis, &light] {
        let total: Spectrum = r.samples.iter().map(|s| s.contribution).sum();
        let mean = total / r.spp as f32;
        assert!(
            (mean - r.estimate).abs().max_element() <= 1e-4 * r.estimate.max_element(),
            "recorded terms {mean} vs estimate {}",
            r.estimate
        );
        for s in &r.samples {
            assert!((0.0..=1.0 + 1e-5).contains(&s.mis_weight), "{s:?}");
            assert!(s.w_in.is_none() || s.pdf > 0.0, "{s:?}");
        }
    }
    let count = |r: &lightlab::lab::probe::ProbeReport, t: &str| {
        r.samples.iter().filter(|s| s.technique == t).count()
    };
    assert_eq!((count(&mis, "light"), count(&mis, "bsdf")), (4096, 4096));
    assert_eq!((count(&light, "light"), count(&light, "bsdf")), (4096, 0));
    assert!(
        light
            .samples
            .iter()
            .all(|s| s.mis_weight == 1.0 || s.w_in.is_none())
    );
    // Both estimate the same integral at the same point.
    let (a, b) = (mis.estimate.x as f64, light.estimate.x as f64);
    let se = ((mis.std_error.x as f64).powi(2) + (light.std_error.x as f64).powi(2)).sqrt();
    assert!(
        a > 0.0 && ((a - b) / se).abs() < 4.0,
        "mis {a} vs light {b} (se {se})"
    );
    // The CLI writes the JSON and the picture; a pixel outside the image is exit 2.
    let dir = scratch("probe");
    let bin = env!("CARGO_BIN_EXE_lightlab");
    let out = Command::new(bin)
        .args(flags(
            "probe builtin:assignment --pixel 200,150 --spp 16 -o",
        ))
        .arg(&dir)
        .output()
        .unwrap();
    assert_succeeded(&out);
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.join("probe.json")).unwrap()).unwrap();
    assert_eq!(json["samples"].as_array().unwrap().len(), 32);
    assert!(read_image(&dir.join("probe.png")).unwrap().width > 0);
    for bad in ["400,10", "1,2,3", "x,1"] {
        let out = Command::new(bin)
            .args(["probe", "--pixel", bad, "-o"])
            .arg(&dir)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "--pixel {bad}");
    }
    let _ = fs::remove_dir_all(dir);
}
