//! Figures on a scene: camera (primary) and shadow ray throughput, and samples per second
//! of every estimator.

use glam::Vec2;
use rayon::prelude::*;

use super::{Figure, median_rate};
use crate::integrator::EstimatorKind;
use crate::light::ShadingPoint;
use crate::render::{RenderSettings, render_quiet};
use crate::sampling::{Rng32, Uniform};
use crate::scene::Scene;

/// Camera rays through every pixel (`per_pixel` jittered rays each), closest hit; then from
/// every hit one shadow ray to a point drawn on a light, any hit.
pub fn scene_ray_figures(scene: &Scene, per_pixel: u32, runs: usize) -> Vec<Figure> {
    let camera = &scene.camera;
    let mut rng = Rng32::new(11);
    let mut primary = Vec::new();
    for y in 0..camera.height {
        for x in 0..camera.width {
            for _ in 0..per_pixel {
                let p = Vec2::new(x as f32, y as f32) + rng.next_2d();
                primary.push(camera.ray(p));
            }
        }
    }
    let n = primary.len() as f64;
    let (closest, closest_range) = median_rate(
        runs,
        || {
            let hits: usize = primary
                .par_chunks(4096)
                .map(|c| {
                    c.iter()
                        .filter(|r| scene.geometry.intersect(r, f32::INFINITY).is_some())
                        .count()
                })
                .sum();
            std::hint::black_box(hits);
        },
        |s| n / s / 1e6,
    );
    // Shadow segments from the visible points to points drawn on the lights.
    let mut segments = Vec::new();
    for r in &primary {
        let Some(hit) = scene.geometry.intersect(r, f32::INFINITY) else {
            continue;
        };
        if scene.lights.is_empty() {
            break;
        }
        let at = ShadingPoint {
            p: hit.p,
            ng: hit.ng,
            n: hit.frame.n,
        };
        let light = &scene.lights[(rng.next_u32() as usize) % scene.lights.len()];
        if let Some(ls) = light.sample(&at, rng.next_2d(), Default::default()) {
            segments.push((
                hit.p,
                hit.ng,
                ls.point,
                ls.normal,
                ls.delta,
                ls.w_in,
                ls.distance,
            ));
        }
    }
    let m = segments.len() as f64;
    let (shadow, shadow_range) = median_rate(
        runs,
        || {
            let blocked: usize = segments
                .par_chunks(4096)
                .map(|c| {
                    c.iter()
                        .filter(|&&(x, nx, y, ny, delta, w, d)| {
                            if delta {
                                scene.geometry.direction_occluded(x, nx, w, d)
                            } else {
                                scene.geometry.segment_occluded(x, nx, y, ny)
                            }
                        })
                        .count()
                })
                .sum();
            std::hint::black_box(blocked);
        },
        |s| m / s / 1e6,
    );
    vec![
        Figure {
            what: "camera rays, closest hit".into(),
            on: scene.name.clone(),
            median: closest,
            range: closest_range,
            unit: "Mrays/s",
        },
        Figure {
            what: "shadow rays to light samples, any hit".into(),
            on: scene.name.clone(),
            median: shadow,
            range: shadow_range,
            unit: "Mrays/s",
        },
    ]
}

/// Samples (camera ray + one estimate) per second of every estimator on `scene` at `spp`.
pub fn estimator_figures(
    scene: &Scene,
    base: &RenderSettings,
    estimators: &[EstimatorKind],
    runs: usize,
) -> Vec<Figure> {
    estimators
        .iter()
        .map(|&kind| {
            let mut s = base.clone();
            s.estimator = kind;
            let camera = s.camera(scene);
            let samples = (camera.width * camera.height) as f64 * s.spp as f64;
            let (median, range) = median_rate(
                runs,
                || {
                    std::hint::black_box(render_quiet(scene, &s));
                },
                |secs| samples / secs / 1e6,
            );
            Figure {
                what: format!("samples, estimator {kind}"),
                on: format!("{} at {} spp, {} sampler", scene.name, s.spp, s.sampler),
                median,
                range,
                unit: "Msamples/s",
            }
        })
        .collect()
}
