//! Conformance of the Mitsuba XML loader: every scene in `tests/scenes/` rendered by
//! lightlab must agree with Mitsuba 3's reference (`tests/scenes/refs/`, made by
//! `tests/scenes/make_refs.py`) within noise; so must the built-in scenes Mitsuba 3 can
//! read once `lightlab export` has written them out.
//!
//! The render is split into `PASSES` independent seeds; the spread of each 8×8 block's
//! mean over the passes gives its standard error whatever the pixel filter (wide filters
//! correlate neighbouring pixels, so per-pixel variances would understate it). Each
//! block's Student t statistic (PASSES − 1 degrees of freedom) is tested two-sided at a
//! Šidák-corrected 1% level over the blocks, as Mitsuba's own render tests do, and the
//! image mean must be within 1% of the reference's. The reference's own noise enters the
//! standard error through the variance channels `make_refs.py` stores (from 8 passes),
//! and so does the rounding of Mitsuba's f32 film sums ([`FILM_ROUNDING`]), which matters
//! only in blocks with almost no noise.

mod common;
use common::blocks::{block_means, block_variances};
use common::chi2::sidak;

use std::path::PathBuf;

use lightlab::image::io::read_image;
use lightlab::image::metrics::compare;
use lightlab::math::Spectrum;
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::scene::{Scene, load, xml};
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Independent renders per scene.
const PASSES: u64 = 12;
/// Samples per pixel of each pass.
const SPP: u32 = 24;
/// Side of a test block in pixels.
const BLOCK: u32 = 8;
/// Family-wise level per scene.
const ALPHA: f64 = 0.01;
/// Relative rounding of a reference's pixel means (f32 sums of its samples).
const FILM_ROUNDING: f64 = 2e-5;

/// (scene, plugins it covers).
const CASES: &[(&str, &str)] = &[
    (
        "cbox_diffuse",
        "direct, rectangle, sphere, area, diffuse, id/ref, box, independent, $spp",
    ),
    (
        "gaussian_stratified",
        "hdrfilm default gaussian, stratified + seed, shading_samples, near_clip, sphere center/radius/to_world, scale x/y/z, spectrum, default bsdf",
    ),
    (
        "tent_point",
        "tent, multijitter, point (position, to_world), cube, fov_axis y, rotate",
    ),
    (
        "disk_twosided",
        "disk, twosided, named ref, flip_normals (rectangle, disk emitter), emitter_samples 2",
    ),
    (
        "mesh_obj",
        "obj (quads, smoothed normals), face_normals, path max_depth 2",
    ),
    (
        "mesh_ply_serialized",
        "ply binary (normals, uv), serialized (shape_index 0/1), emitting mesh",
    ),
    (
        "path_include",
        "include, default + $name, float reflectance, matrix 4x4 and 3x3, gaussian stddev, ldsampler, fov_axis diagonal",
    ),
    (
        "legacy_v06",
        "version 0.6 upgrade (toWorld, sampleCount, fovAxis, nearClip, emitterSamples, bsdfSamples), scale x=-1 camera, bsdf_samples 2",
    ),
    (
        "textures_bitmap",
        "bitmap PNG (sRGB, nearest, to_uv) by ref, JPEG (bilinear, clamp) in twosided on an OBJ with uv (flip_tex_coords), EXR (mirror)",
    ),
    (
        "textured_emitter",
        "bitmap radiance on area emitters (rectangle PNG nearest, disk EXR mirrored by to_uv, sphere JPEG), emitters without a BSDF reflect nothing",
    ),
    (
        "envmap_rotated",
        "envmap (EXR, scale, to_world rotation), disk",
    ),
    (
        "constant_env",
        "constant (uniform spectrum = illuminant E), bsdf_samples 3, gaussian on 48x48, stratified",
    ),
    (
        "microfacet_conductor",
        "roughconductor (ggx + Au, beckmann + Al + specular_reflectance), conductor (Cu)",
    ),
    (
        "microfacet_plastic",
        "roughplastic (alpha, int_ior), plastic",
    ),
];

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/scenes")
}

/// Renders `name` in passes and checks it; returns a table row or the failure.
fn check(name: &str) -> Result<String, String> {
    let path = dir().join(format!("{name}.xml"));
    let loaded = xml::load(&path, &[]).map_err(|e| e.to_string())?;
    if let Some(warning) = loaded.warnings.first() {
        return Err(format!("{name}: unexpected loader warning: {warning}"));
    }
    let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
    check_scene(name, &loaded.scene, (w, h), name)
}

/// Renders `scene` at `w`×`h` in passes and checks it against `refs/REFERENCE.exr`;
/// returns a table row (labelled `name`) or the failure.
fn check_scene(
    name: &str,
    scene: &Scene,
    (w, h): (u32, u32),
    reference: &str,
) -> Result<String, String> {
    let reference = read_image(&dir().join("refs").join(format!("{reference}.exr")))
        .map_err(|e| e.to_string())?;
    if (reference.width, reference.height) != (w, h) {
        return Err(format!(
            "{name}: reference is {}x{}, scene {w}x{h}",
            reference.width, reference.height
        ));
    }
    let mut passes = Vec::new();
    let mut total = vec![Spectrum::ZERO; (w * h) as usize];
    for k in 0..PASSES {
        let mut s = RenderSettings::for_scene(scene);
        s.spp = SPP;
        s.seed = 1000 + k;
        s.resolution = Some((w, h));
        let means = render_quiet(scene, &s).film.means();
        for (t, m) in total.iter_mut().zip(&means) {
            *t += *m / PASSES as f32;
        }
        passes.push(block_means(&means, w, h, BLOCK));
    }
    let refs = block_means(&reference.rgb, w, h, BLOCK);
    let ref_vars = match &reference.variance {
        Some(v) => block_variances(v, w, h, BLOCK),
        None => vec![0.0; refs.len()],
    };
    let blocks = refs.len();
    let alpha = sidak(ALPHA, blocks);
    let t = StudentsT::new(0.0, 1.0, (PASSES - 1) as f64).map_err(|e| e.to_string())?;
    let n = PASSES as f64;
    let mut worst = (1.0f64, 0usize);
    for b in 0..blocks {
        let xs: Vec<f64> = passes.iter().map(|p| p[b]).collect();
        let mean = xs.iter().sum::<f64>() / n;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        // The test's standard error, the reference's own noise, and the rounding of
        // Mitsuba's f32 film sums (about 1e-5 of a block's mean after 8192 samples: a
        // block that sees only a constant emitter reads 1.8000178 for 1.8, with no
        // variance in either image).
        let rounding = FILM_ROUNDING * refs[b].abs();
        let se = (var / n + ref_vars[b] + rounding * rounding).sqrt();
        let diff = mean - refs[b];
        let p = if se > 0.0 {
            2.0 * (1.0 - t.cdf((diff / se).abs()))
        } else if diff.abs() <= 1e-4 * (1.0 + refs[b].abs()) {
            1.0
        } else {
            0.0
        };
        if p < worst.0 {
            worst = (p, b);
        }
    }
    let report = compare(&total, None, &reference.rgb, None);
    let mean_test: f64 = total.iter().map(|c| c.element_sum() as f64).sum();
    let mean_ref: f64 = reference.rgb.iter().map(|c| c.element_sum() as f64).sum();
    let bias = mean_test / mean_ref - 1.0;
    let row = format!(
        "{name:<22} relMSE {:.3e}  mean bias {:+.3}%  min block p {:.2e} (block {}, level {:.1e})",
        report.rel_mse,
        100.0 * bias,
        worst.0,
        worst.1,
        alpha
    );
    if worst.0 < alpha {
        return Err(format!("{row}: block {} disagrees with Mitsuba", worst.1));
    }
    if bias.abs() > 0.01 {
        return Err(format!("{row}: image mean off by more than 1%"));
    }
    Ok(row)
}

#[test]
fn scenes_match_mitsuba_references() {
    let mut failures = Vec::new();
    for &(name, plugins) in CASES {
        match check(name) {
            Ok(row) => println!("{row}  [{plugins}]"),
            Err(e) => {
                println!("FAIL {e}");
                failures.push(e);
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} scene(s) disagree:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Built-in scenes Mitsuba 3 can read once written out (`lightlab export`; the others
/// have Phong materials), with the size of their references (the same list as
/// `make_refs.py`'s `BUILTINS`): the built-in scene itself,
/// rendered at that size, must agree with Mitsuba's render of the exported file
/// (`make_refs.py --builtins`, references `refs/builtin_NAME.exr`).
const BUILTIN_CASES: &[(&str, (u32, u32))] =
    &[("sphere-near-plane", (96, 64)), ("materials", (96, 64))];

#[test]
fn builtin_scenes_match_mitsuba_references() {
    let mut failures = Vec::new();
    for &(name, size) in BUILTIN_CASES {
        let scene = load(&format!("builtin:{name}")).unwrap();
        match check_scene(name, &scene, size, &format!("builtin_{name}")) {
            Ok(row) => println!("{row}"),
            Err(e) => {
                println!("FAIL {e}");
                failures.push(e);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
