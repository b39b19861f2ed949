//! Prints the lecture's 1D variance table: uniform against importance sampling of
//! cos x and 4cos¹⁶x on [0, π/2].

use lightlab::lab::variance_1d::variance_table;

fn main() {
    let samples = 1_000_000;
    println!(
        "{:12} {:22} {:>12} {:>14} {:>12} {:>12}",
        "integrand", "strategy", "estimate", "variance", "std. error", "exact"
    );
    for row in variance_table(samples, 1) {
        println!(
            "{:12} {:22} {:>12.6} {:>14.6e} {:>12.2e} {:>12.6}",
            row.integrand,
            row.strategy,
            row.estimate,
            row.variance,
            row.standard_error(),
            row.exact
        );
    }
}
