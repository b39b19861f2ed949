//! Every microfacet BSDF's `sample` against its `pdf`: chi-square at four incident
//! angles and four roughnesses (α = 0.005 … 1), and the modified Phong at five exponents
//! (n = 1 … 1000; its lobe samples below the horizon land in the outside bin), over the
//! hemisphere and, for sharp lobes, over a narrow cap around the mirror direction so the
//! grid resolves the lobe's core; the pdf's normalisation; and `sample`'s f and pdf
//! against `eval` and `pdf`.
//!
//! `sample` may return nothing (a microfacet reflection below the horizon, lost by
//! design) or a Dirac sample (the smooth plastic's mirror lobe). Both go to the harness's
//! outside bin as the marker direction −z, whose expected count is the mass the pdf
//! leaves out of the domain; the marker gets a nominal density of 1 that the quadrature
//! never sees (it lies outside every domain used here).

mod common;

use common::bsdfs::{ANGLES, Case, cases, integrate_over_half_vectors, w_out};
use common::chi2::{SEED, report_all, sidak_alpha, verdict};
use glam::{Vec2, Vec3};
use lightlab::bsdf::{Bsdf, Microfacet, MicrofacetType};
use lightlab::sampling::Rng32;
use lightlab::sampling::chi2::{Chi2Config, Domain, chi2_test};
use rayon::prelude::*;

/// Where lost and Dirac samples go.
const MARKER: Vec3 = Vec3::NEG_Z;

/// Samples per chi-square test.
const SAMPLES: usize = 300_000;

/// The pdf the harness sees: the BSDF's, with the marker's nominal density.
fn test_pdf(case: &Case, w_out: Vec3) -> impl Fn(Vec3) -> f32 + '_ {
    move |w| {
        if w == MARKER {
            1.0
        } else {
            case.material.pdf(w, w_out)
        }
    }
}

/// The sampler the harness sees.
fn test_sample(case: &Case, w_out: Vec3) -> impl FnMut(&mut Rng32) -> (Vec3, f32) + '_ {
    move |rng| {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        match case.material.sample(w_out, u) {
            Some(s) if !s.delta => (s.w_in, s.pdf),
            _ => (MARKER, 1.0),
        }
    }
}

/// Where a test histograms its samples.
#[derive(Clone, Copy)]
enum Space {
    /// w_in itself.
    Direction,
    /// The half vector h = (w_in + w_out)/|w_in + w_out|, with density
    /// pdf(w_in)·4 (w_out·h) (the reflection Jacobian, Walter et al. 2007, eq. 14).
    HalfVector,
}

/// The domains of a case at `w_out`:
/// - α > 0.05 and smooth plastic: the hemisphere of w_in;
/// - 0 < α < 0.3 below 80°: a cap of half-angle 8α (at most 1.5) around the mirror
///   direction, which resolves the lobe's core (for the Phong rows, n ≥ 37, too);
/// - α ≤ 0.05: caps of half-angle 3α and 12α around the normal in half-vector space.
///
/// At grazing angles a sharp reflected lobe is a thin crescent against the horizon that
/// equal-area cells around the mirror direction (or the hemisphere's, at normal
/// incidence around its pole) cannot resolve, while in half-vector space the same lobe
/// is a round bump of width ≈ α at the normal at every angle.
fn domains(case: &Case, degrees: f32) -> Vec<(String, Space, Domain)> {
    let w = w_out(degrees);
    let mirror = Vec3::new(-w.x, -w.y, w.z);
    let mut list = Vec::new();
    let a = case.alpha;
    if a == 0.0 || a >= 0.05 {
        list.push(("hemisphere".into(), Space::Direction, Domain::hemisphere()));
    }
    if a > 0.0 && a < 0.3 && degrees < 80.0 {
        let cap = Domain::cap(mirror, (8.0 * a).min(1.5).cos());
        list.push(("cap".into(), Space::Direction, cap));
    }
    if a > 0.0 && a <= 0.05 {
        for k in [3.0, 12.0] {
            let cap = Domain::cap(Vec3::Z, (k * a).cos());
            list.push((format!("h-cap-{k}a"), Space::HalfVector, cap));
        }
    }
    list
}

/// The half vector of w_in and w_out, or the marker when there is none (w_in = −w_out).
fn half_vector(w_in: Vec3, w_out: Vec3) -> Vec3 {
    (w_in + w_out).try_normalize().unwrap_or(MARKER)
}

/// The density of the half vector h: pdf(reflect(w_out, h))·4 (w_out·h).
fn half_vector_pdf(case: &Case, w_out: Vec3, h: Vec3) -> f32 {
    let cos = w_out.dot(h);
    if h == MARKER || cos <= 0.0 {
        return if h == MARKER { 1.0 } else { 0.0 };
    }
    case.material.pdf(2.0 * cos * h - w_out, w_out) * 4.0 * cos
}

#[test]
fn every_bsdf_passes_chi_square() {
    let table = cases(false);
    let rows: Vec<(&Case, f32, String, Space, Domain)> = table
        .iter()
        .filter(|c| c.name != "conductor")
        .flat_map(|c| {
            ANGLES.iter().flat_map(move |&angle| {
                domains(c, angle)
                    .into_iter()
                    .map(move |(d, space, domain)| (c, angle, d, space, domain))
            })
        })
        .collect();
    let alpha = sidak_alpha(rows.len());
    let verdicts = rows
        .par_iter()
        .enumerate()
        .map(|(i, (case, angle, domain_name, space, domain))| {
            let w = w_out(*angle);
            let name = format!("{}-{angle}-{domain_name}", case.name);
            let config = Chi2Config::new(domain, SAMPLES, SEED + i as u64);
            let mut draw = test_sample(case, w);
            let report = match space {
                Space::Direction => chi2_test(domain, &mut draw, &test_pdf(case, w), &config),
                Space::HalfVector => {
                    let mut sample = |rng: &mut Rng32| {
                        let (w_in, _) = draw(rng);
                        let h = if w_in == MARKER {
                            MARKER
                        } else {
                            half_vector(w_in, w)
                        };
                        (h, half_vector_pdf(case, w, h))
                    };
                    chi2_test(
                        domain,
                        &mut sample,
                        &|h| half_vector_pdf(case, w, h),
                        &config,
                    )
                }
            };
            verdict(&name, &report, alpha)
        })
        .collect();
    let failures = report_all(verdicts);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn harness_rejects_a_pdf_that_ignores_visible_normals() {
    // A classic bug: sampling GGX visible normals but claiming the D·cos density
    // D(h)·cos θ_h/(4 w_out·h), which drops G1(w_out, h)·(w_out·h)/(cos θ_out cos θ_h).
    let table = cases(false);
    let case = table
        .iter()
        .find(|c| c.name == "roughconductor-ggx-0.3")
        .expect("case");
    let mf = Microfacet::isotropic(MicrofacetType::Ggx, 0.3);
    let w = w_out(80.0);
    let wrong = |w_in: Vec3| match (w_in + w).try_normalize() {
        Some(h) if w_in.z > 0.0 && w.dot(h) > 0.0 => mf.d(h) * h.z / (4.0 * w.dot(h)),
        _ => 0.0,
    };
    let mut sample = |rng: &mut Rng32| {
        let (x, _) = test_sample(case, w)(rng);
        (x, if x == MARKER { 1.0 } else { wrong(x) })
    };
    let pdf = |x: Vec3| if x == MARKER { 1.0 } else { wrong(x) };
    let domain = Domain::hemisphere();
    let report = chi2_test(
        &domain,
        &mut sample,
        &pdf,
        &Chi2Config::new(&domain, SAMPLES, SEED),
    );
    println!(
        "visible normals under the D·cos pdf: p-value {:e}",
        report.p_value
    );
    assert!(report.failure.is_none(), "{:?}", report.failure);
    assert!(
        report.p_value < 1e-12,
        "the wrong pdf was accepted: p = {}",
        report.p_value
    );
}

#[test]
fn every_pdf_integrates_to_the_sampled_mass() {
    // ∫ pdf over the hemisphere = P(sample returns a non-Dirac direction), the latter
    // counted over 10⁵ draws: agreement within 4 standard errors + 2·10⁻³ quadrature.
    // The integral is taken over half vectors, where even the α = 0.005 lobe at 89° is
    // a round bump (see `integrate_over_half_vectors`).
    const DRAWS: usize = 100_000;
    let table = cases(false);
    let mut failures = Vec::new();
    for case in table.iter().filter(|c| c.name != "conductor") {
        for angle in ANGLES {
            let w = w_out(angle);
            let pdf = |w_in: Vec3| case.material.pdf(w_in, w) as f64;
            let total = integrate_over_half_vectors(case.alpha, w, pdf);
            let mut rng = Rng32::new(SEED);
            let kept = (0..DRAWS)
                .filter(|_| {
                    let u = Vec2::new(rng.next_f32(), rng.next_f32());
                    matches!(case.material.sample(w, u), Some(s) if !s.delta)
                })
                .count() as f64
                / DRAWS as f64;
            let sigma = (kept * (1.0 - kept) / DRAWS as f64).sqrt();
            println!(
                "{:28} {angle:4}°: integral {total:.5}, sampled mass {kept:.5}",
                case.name
            );
            if (total - kept).abs() > 4.0 * sigma + 2e-3 {
                failures.push(format!(
                    "{} at {angle}°: ∫pdf = {total}, sampled {kept}",
                    case.name
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn samples_carry_eval_and_pdf() {
    let top = 1.0 - f32::EPSILON / 2.0;
    for case in cases(false) {
        for angle in ANGLES {
            let w = w_out(angle);
            for i in 0..=32 {
                for j in 0..=32 {
                    let u = Vec2::new(i as f32 / 32.0, j as f32 / 32.0).min(Vec2::splat(top));
                    let Some(s) = case.material.sample(w, u) else {
                        continue;
                    };
                    let name = &case.name;
                    assert!(
                        s.w_in.is_finite() && s.f.is_finite() && s.pdf > 0.0,
                        "{name} {u}"
                    );
                    assert!(
                        (s.w_in.length() - 1.0).abs() < 1e-4,
                        "{name} {u}: {}",
                        s.w_in
                    );
                    if !s.delta {
                        assert_eq!(s.f, case.material.eval(s.w_in, w), "{name} {angle} {u}");
                        assert_eq!(s.pdf, case.material.pdf(s.w_in, w), "{name} {angle} {u}");
                    }
                }
            }
        }
    }
}
