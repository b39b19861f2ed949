//! `probe`: where one pixel's samples go. The camera ray through the pixel's centre finds
//! a shading point; the render's own estimator then runs there `spp` times, with the
//! random streams the render gives that pixel, recording every direction it draws
//! ([`Probe`]): technique, density, MIS weight, contribution, the light reached and the
//! point on it. The report is the estimate with its standard error, those samples as
//! JSON, and a picture: the hemisphere above the shading point (orthographic projection
//! of the local directions, one dot per sample) beside the light points as the shading
//! point sees them.

use std::path::Path;

use glam::{Vec2, Vec3};
use plotters::prelude::*;
use serde_json::json;

use super::LabError;
use super::plot::{FONT, register};
use super::report::write_text;
use crate::image::io::write_rgb8_png;
use crate::integrator::{Estimator, Probe, ProbeSample};
use crate::math::{Frame, Spectrum};
use crate::render::RenderSettings;
use crate::sampling::{Sampler, Uniform};
use crate::scene::Scene;

/// What `probe` found at one pixel.
#[derive(Clone, Debug)]
pub struct ProbeReport {
    /// The pixel (x right, y down).
    pub pixel: (u32, u32),
    /// The shading point.
    pub point: Vec3,
    /// Its shading frame.
    pub frame: Frame,
    /// The direction towards the camera (world, unit).
    pub w_out: Vec3,
    /// Radiance the surface emits towards the camera (not estimated).
    pub emitted: Spectrum,
    /// Mean of the estimator's values (reflected direct light).
    pub estimate: Spectrum,
    /// Standard error of that mean.
    pub std_error: Spectrum,
    /// Estimator samples run.
    pub spp: u32,
    /// Every sample the estimator drew.
    pub samples: Vec<ProbeSample>,
}

/// Runs the estimator of `settings` `spp` times at the surface seen through the centre
/// of `pixel`. Errors when the pixel is outside the image or sees no surface.
pub fn probe(
    scene: &Scene,
    settings: &RenderSettings,
    pixel: (u32, u32),
) -> Result<ProbeReport, LabError> {
    if settings.ris_spatial > 0 {
        return Err(LabError::Input(
            "--ris-spatial reuses neighbouring pixels' reservoirs, which a probe of one \
             shading point does not have: probe without it"
                .into(),
        ));
    }
    let camera = settings.camera(scene);
    let (x, y) = pixel;
    if x >= camera.width || y >= camera.height {
        return Err(LabError::Input(format!(
            "--pixel {x},{y} is outside the {}x{} image",
            camera.width, camera.height
        )));
    }
    let ray = camera.ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
    let hit = scene
        .geometry
        .intersect(&ray, f32::INFINITY)
        .ok_or_else(|| {
            LabError::Input(format!(
                "--pixel {x},{y} sees no surface (the background): nothing to probe"
            ))
        })?;
    let w_out = -ray.d.normalize();
    let emitted = crate::integrator::emitted_at(scene, &hit, w_out);
    let estimator = Estimator::new(scene, settings.estimator, settings.light_select)
        .with_mis(settings.mis)
        .with_light_strategy(scene, settings.light_strategy())
        .with_ris_candidates(settings.ris_candidates);
    let probe = Probe::new();
    let (mut sum, mut sum2) = (Spectrum::ZERO, Spectrum::ZERO);
    let spp = settings.spp.max(1);
    for s in 0..spp {
        let mut sampler = Sampler::new(
            settings.sampler,
            settings.seed,
            (y * camera.width + x) as u64,
            s,
            spp,
        );
        // The render draws the pixel position first: keep the estimator's dimensions.
        let _ = sampler.next_2d();
        probe.start_sample(s);
        let v = estimator.direct_probed(scene, &hit, w_out, &mut sampler, Some(&probe), None);
        let v = if v.is_finite() { v } else { Spectrum::ZERO };
        sum += v;
        sum2 += v * v;
    }
    let n = spp as f32;
    let mean = sum / n;
    let var = if spp > 1 {
        ((sum2 - sum * mean) / (n - 1.0)).max(Spectrum::ZERO)
    } else {
        Spectrum::ZERO
    };
    Ok(ProbeReport {
        pixel,
        point: hit.p,
        frame: hit.frame,
        w_out,
        emitted,
        estimate: mean,
        std_error: (var / n).powf(0.5),
        spp,
        samples: probe.samples(),
    })
}

fn v3(v: Vec3) -> serde_json::Value {
    json!([v.x, v.y, v.z])
}

/// The report as JSON (every sample with its fields; directions in world space and in
/// the local shading frame, z along the normal).
pub fn to_json(report: &ProbeReport, scene: &str, flags: &str) -> serde_json::Value {
    let samples: Vec<serde_json::Value> = report
        .samples
        .iter()
        .map(|s| {
            json!({
                "sample": s.sample,
                "technique": s.technique,
                "direction": s.w_in.map(v3),
                "local_direction": s.w_in.map(|w| v3(report.frame.to_local(w))),
                "pdf": s.pdf,
                "mis_weight": s.mis_weight,
                "contribution": v3(s.contribution),
                "light": s.light,
                "light_point": s.light_point.map(v3),
                "occluded": s.occluded,
            })
        })
        .collect();
    json!({
        "scene": scene,
        "settings": flags,
        "pixel": [report.pixel.0, report.pixel.1],
        "point": v3(report.point),
        "normal": v3(report.frame.n),
        "w_out": v3(report.w_out),
        "emitted": v3(report.emitted),
        "spp": report.spp,
        "estimate": v3(report.estimate),
        "std_error": v3(report.std_error),
        "samples": samples,
    })
}

/// Writes `probe.json` and `probe.png` into `dir`.
pub fn write_probe(
    report: &ProbeReport,
    scene: &str,
    flags: &str,
    dir: &Path,
) -> Result<(), LabError> {
    let text = serde_json::to_string_pretty(&to_json(report, scene, flags))
        .map_err(|e| LabError::Input(e.to_string()))?;
    write_text(&dir.join("probe.json"), &text)?;
    let (w, h) = SIZE;
    let mut buffer = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        draw(report, scene, &root).map_err(|e| LabError::Input(format!("probe picture: {e}")))?;
    }
    write_rgb8_png(w, h, buffer, &dir.join("probe.png"))?;
    Ok(())
}

const SIZE: (u32, u32) = (1000, 560);

/// Colour of a technique: light sampling orange, BSDF blue, RIS red, directional green.
fn colour(technique: &str) -> RGBColor {
    match technique {
        "light" => RGBColor(230, 120, 10),
        "bsdf" => RGBColor(31, 100, 200),
        "ris" => RGBColor(200, 30, 40),
        _ => RGBColor(30, 150, 60),
    }
}

/// Dot radius from a contribution: 2 px for zero, up to 7 px for the largest.
fn radius(s: &ProbeSample, largest: f32) -> i32 {
    let c = crate::math::spectrum::luminance(s.contribution).max(0.0);
    if largest > 0.0 && c > 0.0 {
        2 + (5.0f32 * (c / largest).sqrt()).round() as i32
    } else {
        2
    }
}

/// A sample's dot at `at`: filled in its technique's colour when it contributes, hollow
/// when it adds zero, grey when shadowed.
fn marker(s: &ProbeSample, at: (f32, f32), largest: f32) -> Circle<(f32, f32), i32> {
    let c = colour(s.technique);
    let style = if s.occluded {
        RGBColor(150, 150, 150).stroke_width(1)
    } else if s.contribution == Spectrum::ZERO {
        c.stroke_width(1)
    } else {
        c.filled()
    };
    Circle::new(at, radius(s, largest), style)
}

fn draw<DB: DrawingBackend>(
    report: &ProbeReport,
    scene: &str,
    root: &DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), String> {
    if !register() {
        return Err("the built-in font did not load".into());
    }
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let lum = |s: Spectrum| crate::math::spectrum::luminance(s);
    let title = format!(
        "{scene}, pixel ({}, {}): estimate {:.4} ± {:.4} (luminance, {} samples){}",
        report.pixel.0,
        report.pixel.1,
        lum(report.estimate),
        lum(report.std_error),
        report.spp,
        if report.emitted == Spectrum::ZERO {
            String::new()
        } else {
            format!(", emitted {:.3}", lum(report.emitted))
        }
    );
    let root = root.titled(&title, (FONT, 17)).map_err(e)?;
    let (left, right) = root.split_horizontally(SIZE.0 / 2);
    let largest = report
        .samples
        .iter()
        .map(|s| lum(s.contribution))
        .fold(0.0f32, f32::max);
    // Left: the hemisphere, local x right and y up, seen from above the normal.
    let mut chart = ChartBuilder::on(&left)
        .caption(
            "directions over the hemisphere (orthographic, normal at the centre)",
            (FONT, 13),
        )
        .margin(12)
        .build_cartesian_2d(-1.05f32..1.05f32, -1.05f32..1.05f32)
        .map_err(e)?;
    let circle: Vec<(f32, f32)> = (0..=128)
        .map(|k| {
            let a = k as f32 / 128.0 * std::f32::consts::TAU;
            (a.cos(), a.sin())
        })
        .collect();
    chart
        .draw_series(std::iter::once(PathElement::new(circle, BLACK)))
        .map_err(e)?;
    for s in &report.samples {
        let Some(w) = s.w_in else { continue };
        let l = report.frame.to_local(w);
        chart
            .draw_series(std::iter::once(marker(s, (l.x, l.y), largest)))
            .map_err(e)?;
    }
    // Legend: techniques present, and what hollow and grey dots mean.
    let mut names: Vec<&str> = report.samples.iter().map(|s| s.technique).collect();
    names.dedup();
    names.sort_unstable();
    names.dedup();
    for (i, name) in names.iter().enumerate() {
        let y = 64 + 18 * i as i32;
        left.draw(&Circle::new((20, y), 5, colour(name).filled()))
            .map_err(e)?;
        left.draw(&Text::new(name.to_string(), (32, y - 7), (FONT, 13)))
            .map_err(e)?;
    }
    let h = SIZE.1 as i32 - 60;
    left.draw(&Text::new(
        "filled: contributes (area ∝ contribution); hollow: zero; grey: shadowed",
        (12, h),
        (FONT, 12),
    ))
    .map_err(e)?;
    // Right: the points on the lights, projected on the plane across the mean direction
    // from the shading point to them.
    let points: Vec<(Vec3, &ProbeSample)> = report
        .samples
        .iter()
        .filter_map(|s| s.light_point.map(|p| (p, s)))
        .collect();
    let axis = points
        .iter()
        .map(|(p, _)| (*p - report.point).normalize_or_zero())
        .sum::<Vec3>()
        .normalize_or(report.frame.n);
    let view = Frame::from_normal(axis);
    let flat: Vec<(f32, f32)> = points
        .iter()
        .map(|(p, _)| {
            let l = view.to_local(*p - report.point);
            (l.x, l.y)
        })
        .collect();
    let reach = flat
        .iter()
        .fold(1e-3f32, |m, &(a, b)| m.max(a.abs()).max(b.abs()))
        * 1.1;
    let mut chart = ChartBuilder::on(&right)
        .caption(
            "points on the lights, seen from the shading point (scene units)",
            (FONT, 13),
        )
        .margin(12)
        .x_label_area_size(28)
        .y_label_area_size(48)
        .build_cartesian_2d(-reach..reach, -reach..reach)
        .map_err(e)?;
    chart
        .configure_mesh()
        .label_style((FONT, 11))
        .draw()
        .map_err(e)?;
    for (&at, (_, s)) in flat.iter().zip(&points) {
        chart
            .draw_series(std::iter::once(marker(s, at, largest)))
            .map_err(e)?;
    }
    root.present().map_err(e)
}
