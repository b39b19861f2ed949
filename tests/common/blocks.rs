//! Per-pixel-block comparison of two renders: the sum of the pixel means in each 16×16
//! block with the variance of that sum (from the films' per-pixel Welford variances), and
//! the z-score of the worst block. Blocks average out pixel noise while keeping bias that
//! is local to a region visible.

use lightlab::image::Film;

/// Per 16×16 block: the sum of the pixel means (RGB summed) and the variance of that sum.
pub fn blocks(film: &Film) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for by in (0..film.height).step_by(16) {
        for bx in (0..film.width).step_by(16) {
            let (mut m, mut v) = (0f64, 0f64);
            for y in by..(by + 16).min(film.height) {
                for x in bx..(bx + 16).min(film.width) {
                    let p = film.pixel(x, y);
                    m += p.mean.element_sum() as f64;
                    v += p.variance_of_mean().element_sum() as f64;
                }
            }
            out.push((m, v));
        }
    }
    out
}

/// z-scores of `test` against `reference`, block by block.
pub fn block_z(test: &[(f64, f64)], reference: &[(f64, f64)]) -> Vec<f64> {
    test.iter()
        .zip(reference)
        .map(|(a, r)| (a.0 - r.0) / (a.1 + r.1).sqrt().max(1e-9))
        .collect()
}

/// The z-score of largest magnitude (0 for no blocks).
pub fn worst(z: &[f64]) -> f64 {
    z.iter()
        .copied()
        .fold(0f64, |w, z| if z.abs() > w.abs() { z } else { w })
}
