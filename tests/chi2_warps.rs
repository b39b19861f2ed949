//! Every warp of the registry against its pdf: chi-square, normalisation, inverses and
//! edge values; and one test showing the harness rejects a wrong pdf.

mod common;

use common::chi2::{SEED, chi2_all, edges_are_finite, integrates_to_one, inverses_round_trip};
use lightlab::sampling::chi2::{Chi2Config, Domain, chi2_test};
use lightlab::sampling::registry::Family;
use lightlab::sampling::warp::{square_to_cosine_hemisphere, uniform_hemisphere_pdf};

#[test]
fn every_warp_passes_chi_square() {
    chi2_all(Family::Warp);
}

#[test]
fn every_warp_pdf_integrates_to_one() {
    integrates_to_one(Family::Warp);
}

#[test]
fn every_warp_inverse_round_trips() {
    inverses_round_trip(Family::Warp);
}

#[test]
fn every_warp_is_finite_at_the_edges() {
    edges_are_finite(Family::Warp);
}

#[test]
fn harness_rejects_cosine_samples_under_the_uniform_pdf() {
    let domain = Domain::hemisphere();
    // The sampler claims the uniform pdf too, so only the histogram can tell.
    let mut sample = |rng: &mut lightlab::sampling::Rng32| {
        let (w, _) = square_to_cosine_hemisphere(glam::Vec2::new(rng.next_f32(), rng.next_f32()));
        (w, uniform_hemisphere_pdf(w))
    };
    let report = chi2_test(
        &domain,
        &mut sample,
        &uniform_hemisphere_pdf,
        &Chi2Config::new(&domain, 100_000, SEED),
    );
    println!("cosine vs uniform pdf: p-value: {:e}", report.p_value);
    assert!(report.failure.is_none(), "{:?}", report.failure);
    assert!(
        report.p_value < 1e-12,
        "the wrong pdf was accepted: p = {}",
        report.p_value
    );
}
