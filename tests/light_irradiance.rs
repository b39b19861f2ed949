//! Every light-sampling strategy integrates correctly: Σ 1/(N·pdf) over its samples is
//! the solid angle the light subtends (within 0.5%), and its irradiance estimate
//! E ≈ (1/N) Σ L·cos θx/pdf meets the analytic irradiance within 4 standard errors
//! (sphere: π·L·(r/d)²·cos θ; rectangle, triangle and polygon: Lambert's formula; disk on
//! its axis: π·L·r²/(r² + d²)). A point light's irradiance is exact at every sample.

mod common;

use common::lambert::lambert_irradiance;
use common::lights::{
    Placement, RADIANCE, STRATEGIES, TestLight, TestShape, at, light, outline, placement,
    solid_angle,
};
use glam::Vec3;
use lightlab::light::{Light, PointLight, ShadingPoint};
use lightlab::math::Spectrum;
use lightlab::sampling::{Rng32, Uniform};

const SAMPLES: usize = 1_000_000;

/// Shading points with the whole light in front of them and above their horizon.
fn points(shape: TestShape) -> Vec<(String, ShadingPoint)> {
    match shape {
        TestShape::Disk => vec![
            ("axis-near".into(), at(Vec3::new(0.0, 0.0, 0.8), Vec3::Z)),
            ("axis-far".into(), at(Vec3::new(0.0, 0.0, -9.0), Vec3::Z)),
        ],
        _ => [Placement::Near, Placement::Far, Placement::Grazing]
            .iter()
            .map(|&p| (format!("{p:?}"), placement(shape, p)))
            .collect(),
    }
}

/// Mean and standard error of f over the light's samples (a sample with no light scores 0).
fn estimate(
    light: &TestLight,
    at: &ShadingPoint,
    seed: u64,
    f: impl Fn(Vec3, f32) -> f64,
) -> (f64, f64) {
    let mut rng = Rng32::new(seed);
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..SAMPLES {
        if let Some(ls) = light.sample(at, rng.next_2d()) {
            let v = f(ls.w_in, ls.pdf);
            sum += v;
            sum2 += v * v;
        }
    }
    let n = SAMPLES as f64;
    let mean = sum / n;
    (mean, ((sum2 / n - mean * mean).max(0.0) / (n - 1.0)).sqrt())
}

/// The analytic irradiance of the whole light at `at` (above the horizon).
fn exact_irradiance(shape: TestShape, at: &ShadingPoint) -> f64 {
    let c = Vec3::new(0.0, 0.0, 1.0);
    let (l, r) = (RADIANCE as f64, 0.5f64);
    match shape {
        TestShape::Sphere => {
            let d = (c - at.p).length() as f64;
            let cos = at.n.dot((c - at.p).normalize()) as f64;
            std::f64::consts::PI * l * (r / d).powi(2) * cos
        }
        TestShape::Disk => {
            let d = (c - at.p).length() as f64;
            std::f64::consts::PI * l * r * r / (r * r + d * d)
        }
        _ => lambert_irradiance(at.p, at.n, &outline(shape).expect("planar"), RADIANCE),
    }
}

/// Runs `check` on every strategy of every shape from every point; lists all failures.
fn for_every_case(check: impl Fn(TestShape, &TestLight, &ShadingPoint, u64) -> Option<String>) {
    let mut failures = Vec::new();
    let mut seed = 1;
    for &(shape, strategies) in &STRATEGIES {
        for &s in strategies {
            for (name, at) in points(shape) {
                seed += 1;
                if let Some(why) = check(shape, &light(shape, s), &at, seed) {
                    failures.push(format!("{shape:?} {s} {name}: {why}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn inverse_pdf_sums_to_the_solid_angle() {
    for_every_case(|shape, light, at, seed| {
        let (mean, se) = estimate(light, at, seed, |_, pdf| 1.0 / pdf as f64);
        let exact = solid_angle(shape, at.p);
        let error = (mean - exact) / exact;
        println!("{shape:?}: Σ1/(N·pdf) = {mean:.6} ± {se:.1e}, Ω = {exact:.6} ({error:+.2e})");
        (error.abs() > 5e-3).then(|| format!("Σ1/(N·pdf) = {mean} but Ω = {exact}"))
    });
}

#[test]
fn irradiance_matches_the_analytic_value() {
    for_every_case(|shape, light, at, seed| {
        let (mean, se) = estimate(light, at, seed, |w, pdf| {
            RADIANCE as f64 * at.n.dot(w).max(0.0) as f64 / pdf as f64
        });
        let exact = exact_irradiance(shape, at);
        let z = (mean - exact) / (se + 1e-5 * exact);
        println!("{shape:?}: E = {mean:.6} ± {se:.1e}, exact {exact:.6} (z = {z:+.2})");
        (z.abs() > 4.0).then(|| format!("E = {mean} ± {se} but exact {exact} (z = {z:.2})"))
    });
}

#[test]
fn point_light_irradiance_is_exact() {
    let light = Light::Point(PointLight {
        position: Vec3::new(0.3, -0.2, 2.0),
        intensity: Spectrum::splat(5.0),
    });
    let mut rng = Rng32::new(3);
    for p in [Vec3::ZERO, Vec3::new(1.0, 1.0, -1.0)] {
        let at = at(p, Vec3::new(0.1, 0.0, 1.0));
        let d = Vec3::new(0.3, -0.2, 2.0) - p;
        let exact = 5.0 * at.n.dot(d.normalize()) / d.length_squared();
        for _ in 0..100 {
            let ls = light
                .sample(&at, rng.next_2d(), Default::default())
                .expect("above the horizon");
            let e = ls.radiance.x * at.n.dot(ls.w_in) / ls.pdf;
            assert!(
                ls.delta && (e - exact).abs() <= 1e-5 * exact,
                "{e} vs {exact}"
            );
        }
    }
    // Below the horizon: no light, never NaN.
    let below = at(Vec3::new(0.0, 0.0, 3.0), Vec3::Z);
    assert!(
        light
            .sample(&below, rng.next_2d(), Default::default())
            .is_none()
    );
}

/// `projected-solid-angle` draws ∝ cos θ, so on an unoccluded Lambertian plane every
/// sample's estimate L·cos θ/pdf is the irradiance itself: on a grid of receiver points
/// under a rectangle, a triangle, the concave L and a convex pentagon, each of 256
/// samples is within 2·10⁻⁵ of Lambert's formula (the issue asks for a relative variance
/// below 10⁻⁶ at 1 spp; this is below 10⁻⁹). Where the horizon cuts the light (tilted
/// receivers), the samples still agree with each other to 10⁻⁴ (there is no closed form
/// here to compare with; near the horizon cos θ is small, and the f32 rounding of the
/// light point, ~6·10⁻⁸, moves it by up to 10⁻⁴ of itself).
#[test]
fn projected_solid_angle_estimates_are_exact_on_a_lambertian_plane() {
    use lightlab::light::{LightSampling, PolygonLight};
    let pentagon: Vec<Vec3> = (0..5)
        .map(|k| {
            let a = -std::f32::consts::TAU * k as f32 / 5.0;
            Vec3::new(0.6 * a.cos(), 0.6 * a.sin(), 1.0)
        })
        .collect();
    let mut lights: Vec<(String, TestLight, Option<Vec<Vec3>>)> = [
        TestShape::Rectangle,
        TestShape::Triangle,
        TestShape::Polygon,
    ]
    .iter()
    .map(|&s| {
        (
            format!("{s:?}"),
            light(s, LightSampling::ProjectedSolidAngle),
            outline(s),
        )
    })
    .collect();
    let mut pentagon_light = light(TestShape::Polygon, LightSampling::ProjectedSolidAngle);
    pentagon_light.light =
        Light::Polygon(PolygonLight::new(&pentagon, Spectrum::splat(RADIANCE)).expect("pentagon"));
    lights.push(("pentagon".into(), pentagon_light, Some(pentagon.clone())));
    let mut rng = Rng32::new(17);
    for (name, light, outline) in &lights {
        let outline = outline.as_ref().expect("planar");
        for i in 0..9 {
            for j in 0..9 {
                let p = Vec3::new(-2.0 + 0.5 * i as f32, -2.0 + 0.5 * j as f32, 0.0);
                for (tilted, n) in [
                    (false, Vec3::Z),
                    (true, Vec3::new(0.9, 0.2, 0.4).normalize()),
                ] {
                    let at = at(p, n);
                    let estimates: Vec<f64> = (0..256)
                        .filter_map(|_| light.sample(&at, rng.next_2d()))
                        .map(|ls| RADIANCE as f64 * at.n.dot(ls.w_in) as f64 / ls.pdf as f64)
                        .collect();
                    let (lo, hi) = estimates
                        .iter()
                        .fold((f64::MAX, f64::MIN), |(lo, hi), &e| (lo.min(e), hi.max(e)));
                    if tilted {
                        assert!(
                            estimates.is_empty() || (hi - lo) <= 1e-4 * hi,
                            "{name} at {p} tilted: estimates from {lo} to {hi}"
                        );
                        continue;
                    }
                    assert_eq!(estimates.len(), 256, "{name} at {p}: samples lost");
                    let exact = lambert_irradiance(p, n, outline, RADIANCE);
                    assert!(
                        (lo - exact).abs() <= 2e-5 * exact && (hi - exact).abs() <= 2e-5 * exact,
                        "{name} at {p}: estimates from {lo} to {hi}, exact {exact}"
                    );
                }
            }
        }
    }
}
