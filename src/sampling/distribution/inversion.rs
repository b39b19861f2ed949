//! Numerical inversion of a monotone CDF for densities whose inverse CDF has no closed
//! form: safeguarded Newton iteration with a bisection fallback (Press et al.,
//! Numerical Recipes, 3rd ed., §9.4 `rtsafe`).

/// x in [min, max] with P(x) = u, found by Newton steps x ← x − (P(x) − u)/p(x) kept
/// inside a shrinking bracket; a step that would leave the bracket (or a zero density)
/// is replaced by bisection, so it always converges. `cdf` must increase from 0 at
/// `min` to 1 at `max`, and `pdf` is its derivative. Works in f64; returns x as f32.
///
/// ```
/// use lightlab::sampling::distribution::sample_by_inversion;
/// // p(x) = 2x on [0, 1]: P(x) = x², so P⁻¹(0.25) = 0.5.
/// let x = sample_by_inversion(|x| x * x, |x| 2.0 * x, 0.0, 1.0, 0.25);
/// assert!((x - 0.5).abs() < 1e-6);
/// ```
pub fn sample_by_inversion(
    cdf: impl Fn(f64) -> f64,
    pdf: impl Fn(f64) -> f64,
    min: f64,
    max: f64,
    u: f32,
) -> f32 {
    let u = (u as f64).clamp(0.0, 1.0);
    let (mut lo, mut hi) = (min, max);
    let mut x = min + u * (max - min);
    for _ in 0..100 {
        let residual = cdf(x) - u;
        if residual.abs() < 1e-12 {
            break;
        }
        if residual < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let slope = pdf(x);
        let newton = x - residual / slope;
        x = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo < 1e-12 * (max - min) {
            break;
        }
    }
    x.clamp(min, max) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverts_a_cdf_with_a_flat_stretch_and_the_ends() {
        // p = 2 on [0, 0.25) ∪ [0.75, 1), 0 between: Newton must fall back to bisection.
        let cdf = |x: f64| (2.0 * x.min(0.25)) + 2.0 * (x - 0.75).max(0.0);
        let pdf = |x: f64| if (0.25..0.75).contains(&x) { 0.0 } else { 2.0 };
        for u in [0.0f32, 0.1, 0.5, 0.7, 1.0] {
            let x = sample_by_inversion(cdf, pdf, 0.0, 1.0, u) as f64;
            assert!((cdf(x) - u as f64).abs() < 1e-6, "u = {u}: x = {x}");
        }
    }
}
