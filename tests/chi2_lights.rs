//! Every light-sampling strategy of every shape against its own solid-angle pdf:
//! chi-square of the sampled directions from near, far, grazing and partly-below-horizon
//! shading points (one table, Šidák-corrected); and one test showing the harness rejects
//! a strategy checked against another strategy's pdf.

mod common;

use common::chi2::{SEED, Verdict, checked, report_all, sidak_alpha};
use common::lights::{
    PLACEMENTS, STRATEGIES, TestLight, TestShape, cap, direction_pdf, light, placement,
};
use glam::Vec2;
use glam::Vec3;
use lightlab::geometry::Shape;
use lightlab::light::{Light, LightSampling, ShadingPoint};
use lightlab::sampling::chi2::{Chi2Config, Domain, chi2_test};
use lightlab::sampling::{Rng32, Uniform};
use rayon::prelude::*;

const SAMPLES: usize = 100_000;

/// The chi-square case of `shape` sampled by `strategy` from `at`, the pdf taken from
/// the light sampled by `claimed` (the same strategy, except in the failing demo).
fn report(
    shape: TestShape,
    strategy: LightSampling,
    claimed: LightSampling,
    at: &ShadingPoint,
    seed: u64,
) -> lightlab::sampling::chi2::Chi2Report {
    let sampled = light(shape, strategy);
    let claimed = light(shape, claimed);
    let (axis, z_min) = cap(shape, at.p);
    let domain = Domain::cap(axis, z_min);
    // The sampler claims the other pdf too, so only the histogram can tell.
    let mut sample = |rng: &mut Rng32| match sampled.sample(at, rng.next_2d()) {
        Some(ls) => (ls.w_in, direction_pdf(&claimed, at, ls.w_in)),
        None => (-axis, 0.0),
    };
    let pdf = |w| direction_pdf(&claimed, at, w);
    chi2_test(
        &domain,
        &mut sample,
        &pdf,
        &Chi2Config::new(&domain, SAMPLES, seed),
    )
}

#[test]
fn every_light_strategy_passes_chi_square() {
    let cases: Vec<_> = STRATEGIES
        .iter()
        .flat_map(|&(shape, strategies)| {
            strategies
                .iter()
                .flat_map(move |&s| PLACEMENTS.iter().map(move |&p| (shape, s, p)))
        })
        .collect();
    let alpha = sidak_alpha(cases.len());
    let verdicts = cases
        .par_iter()
        .map(|&(shape, strategy, place)| {
            let name = format!("{shape:?}-{strategy}-{place:?}");
            let at = placement(shape, place);
            let light = light(shape, strategy);
            let by_area = shape == TestShape::Sphere
                && matches!(strategy, LightSampling::Area | LightSampling::VisibleArea);
            if by_area {
                return sphere_points(&name, &light, &at, alpha);
            }
            let (axis, z_min) = cap(shape, at.p);
            let domain = Domain::cap(axis, z_min);
            let pdf = |w| direction_pdf(&light, &at, w);
            // A sample that carries no light is reported as the direction away from the
            // light, outside the domain, with density 0 (the pdf function's value there).
            let mut sample = |rng: &mut Rng32| match light.sample(&at, rng.next_2d()) {
                Some(ls) => (ls.w_in, ls.pdf),
                None => (-axis, 0.0),
            };
            checked(&name, &domain, &mut sample, &pdf, SAMPLES, alpha)
        })
        .collect();
    let failures = report_all(verdicts);
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Sphere strategies that draw points by area have a solid-angle pdf p_A·d²/cos θy that
/// is singular at the silhouette, where the harness's quadrature loses ~0.5% of the mass.
/// Their samples are histogrammed instead by the unit normal n_y of the sampled point
/// (over the cap visible from `at`), against the same solid-angle pdf times the
/// exact Jacobian dω/dn = r²·cos θy/d², which is bounded.
fn sphere_points(name: &str, light: &TestLight, at: &ShadingPoint, alpha: f64) -> Verdict {
    let Light::Area(area) = &light.light else {
        unreachable!("sphere lights are area lights")
    };
    let Shape::Sphere(sphere) = area.shape else {
        unreachable!("a sphere")
    };
    let jacobian = |y: Vec3, ny: Vec3| {
        let d = y - at.p;
        sphere.radius * sphere.radius * ny.dot(-d).max(0.0) / d.length() / d.length_squared()
    };
    let pdf = |ny: Vec3| {
        let y = sphere.center + sphere.radius * ny;
        let w = (y - at.p).normalize();
        // Only points a sample can return: facing `at` (and so not hidden by the sphere)
        // and above its horizon.
        if ny.dot(-w) <= 0.0 || at.n.dot(w) <= 0.0 {
            return 0.0;
        }
        light.pdf(at, y, ny) * jacobian(y, ny)
    };
    // The domain is the cap visible from `at` (n_y·axis ≥ r/D), widened by 10⁻⁵ for
    // rounding: its edge is the support's, which no cell then straddles. (An edge just
    // inside a cell, between its quadrature nodes, is integrated as support: at Far the
    // strip 0.047 ≤ n_y·axis < r/D = 0.049 of the old domain (z ≥ −0.1) added 0.22% of
    // mass that the harness, counting every surplus since issue 18, rejected.)
    let to_at = at.p - sphere.center;
    let axis = to_at.normalize();
    let domain = Domain::cap(axis, sphere.radius / to_at.length() - 1e-5);
    let mut sample = |rng: &mut Rng32| match light.sample(at, rng.next_2d()) {
        Some(ls) => (ls.normal, ls.pdf * jacobian(ls.point, ls.normal)),
        // No light: the point straight behind, outside the domain, density 0.
        None => (-axis, 0.0),
    };
    checked(name, &domain, &mut sample, &pdf, SAMPLES, alpha)
}

#[test]
fn harness_rejects_solid_angle_samples_under_the_area_pdf() {
    let at = placement(TestShape::Rectangle, common::lights::Placement::Near);
    let r = report(
        TestShape::Rectangle,
        LightSampling::SolidAngle,
        LightSampling::Area,
        &at,
        SEED,
    );
    println!("solid-angle samples vs area pdf: p-value {:e}", r.p_value);
    assert!(r.failure.is_none(), "{:?}", r.failure);
    assert!(
        r.p_value < 1e-12,
        "the wrong pdf was accepted: p = {}",
        r.p_value
    );
}

#[test]
fn sampled_pdf_matches_pdf_at_the_sampled_point() {
    let u = Vec2::new(0.37, 0.61);
    for &(shape, strategies) in &STRATEGIES {
        for &s in strategies {
            for &p in &PLACEMENTS {
                let at = placement(shape, p);
                let l = light(shape, s);
                if let Some(ls) = l.sample(&at, u) {
                    let pdf = l.pdf(&at, ls.point, ls.normal);
                    assert!(
                        (pdf - ls.pdf).abs() <= 1e-5 * pdf,
                        "{shape:?} {s} {p:?}: sample pdf {} vs pdf {pdf}",
                        ls.pdf
                    );
                }
            }
        }
    }
}
