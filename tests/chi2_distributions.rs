//! Every tabulated and generic distribution of the registry against its pdf.

mod common;

use common::chi2::{chi2_all, edges_are_finite, integrates_to_one, inverses_round_trip};
use lightlab::sampling::registry::Family;

#[test]
fn every_distribution_passes_chi_square() {
    chi2_all(Family::Distribution);
}

#[test]
fn every_distribution_pdf_integrates_to_one() {
    integrates_to_one(Family::Distribution);
}

#[test]
fn every_distribution_inverse_round_trips() {
    inverses_round_trip(Family::Distribution);
}

#[test]
fn every_distribution_is_finite_at_the_edges() {
    edges_are_finite(Family::Distribution);
}
