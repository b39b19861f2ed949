//! The bilinear warp of the square: density ∝ the bilinear interpolation of four corner
//! weights. Applied before a spherical rectangle or triangle map with the cosines at the
//! corners as weights, it approximates sampling ∝ cos θ over the light (Hart, Pharr,
//! Müller, Lopes, McGuire & Shirley 2020, "Practical Product Sampling by Fitting and
//! Composing Warps"; pbrt-v4 §6.5.2). Corner weights are `[w00, w10, w01, w11]`, the
//! weight at (0, 0), (1, 0), (0, 1) and (1, 1).

use glam::Vec2;

use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// x on [0, 1] with density ∝ (1 − x)·a + x·b (a, b ≥ 0, not both 0), by inverting its
/// CDF, written so it stays accurate when a ≈ b (the form pbrt-v4 uses).
#[inline]
fn square_to_linear(u: f32, a: f32, b: f32) -> f32 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + ((1.0 - u) * a * a + u * b * b).sqrt());
    x.min(ONE_MINUS_EPSILON)
}

/// The CDF of the density 2·((1 − x)·a + x·b)/(a + b): x·((2 − x)·a + x·b)/(a + b), the
/// inverse of [`square_to_linear`].
#[inline]
fn linear_to_square(x: f32, a: f32, b: f32) -> f32 {
    if a + b <= 0.0 {
        return x;
    }
    x * ((2.0 - x) * a + x * b) / (a + b)
}

/// A point of [0, 1]² with density ∝ the bilinear interpolation of `w` (see the module
/// docs), by the marginal in y then the conditional in x; returns it and its density per
/// unit area. Weights must be ≥ 0 and not all zero.
///
/// ```
/// use glam::Vec2;
/// use lightlab::sampling::warp::{bilinear_pdf, square_to_bilinear};
/// let w = [1.0, 2.0, 3.0, 4.0];
/// let (p, pdf) = square_to_bilinear(Vec2::new(0.3, 0.7), w);
/// assert!((pdf - bilinear_pdf(p, w)).abs() < 1e-5);
/// ```
#[inline]
pub fn square_to_bilinear(u: Vec2, w: [f32; 4]) -> (Vec2, f32) {
    let y = square_to_linear(u.y, w[0] + w[1], w[2] + w[3]);
    let x = square_to_linear(u.x, lerp(y, w[0], w[2]), lerp(y, w[1], w[3]));
    let p = Vec2::new(x, y);
    (p, bilinear_pdf(p, w))
}

/// Density per unit area of [`square_to_bilinear`], 4·bilinear(p)/(w00 + w10 + w01 + w11):
/// the marginal density of y times the conditional density of x.
/// (The product of the two linear densities collapses to this: the conditional's
/// normalisation is the marginal's numerator. One division instead of two.)
#[inline]
pub fn bilinear_pdf(p: Vec2, w: [f32; 4]) -> f32 {
    let sum = w[0] + w[1] + w[2] + w[3];
    if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) || sum <= 0.0 {
        return 0.0;
    }
    4.0 * lerp(p.y, lerp(p.x, w[0], w[1]), lerp(p.x, w[2], w[3])) / sum
}

/// The inverse of [`square_to_bilinear`]: the uniform point that maps to `p`.
#[inline]
pub fn bilinear_to_square(p: Vec2, w: [f32; 4]) -> Vec2 {
    let uy = linear_to_square(p.y, w[0] + w[1], w[2] + w[3]);
    let ux = linear_to_square(p.x, lerp(p.y, w[0], w[2]), lerp(p.y, w[1], w[3]));
    Vec2::new(ux, uy)
}

/// (1 − t)·a + t·b.
#[inline]
fn lerp(t: f32, a: f32, b: f32) -> f32 {
    (1.0 - t) * a + t * b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_round_trips_and_pdf_is_the_normalised_bilinear() {
        for w in [
            [1.0, 1.0, 1.0, 1.0],
            [0.01, 2.0, 0.5, 3.0],
            [0.0, 0.0, 1.0, 5.0],
        ] {
            for (a, b) in [(0.1, 0.2), (0.9, 0.05), (0.5, 0.5), (0.0, 0.99)] {
                let u = Vec2::new(a, b);
                let (p, pdf) = square_to_bilinear(u, w);
                let back = bilinear_to_square(p, w);
                assert!(
                    (back - u).abs().max_element() < 1e-4,
                    "{w:?} {u} -> {p} -> {back}"
                );
                let sum: f32 = w.iter().sum();
                let closed = 4.0 * lerp(p.y, lerp(p.x, w[0], w[1]), lerp(p.x, w[2], w[3])) / sum;
                assert!((pdf - closed).abs() < 1e-4 * pdf.max(1.0), "{w:?} {u}");
            }
        }
        // Equal weights: the identity.
        let (p, pdf) = square_to_bilinear(Vec2::new(0.25, 0.75), [2.0; 4]);
        assert!((p - Vec2::new(0.25, 0.75)).length() < 1e-6 && (pdf - 1.0).abs() < 1e-6);
    }
}
