//! The lecture's first non-uniform example: x = ξ², whose density 1/(2√x) has an
//! integrable singularity at 0.

/// x = u² on [0, 1). pdf = 1/(2√x) per unit length (lecture: P(ξ² < x) = P(ξ < √x) = √x).
///
/// ```
/// use lightlab::sampling::warp::uniform_to_xi_squared;
/// let (x, pdf) = uniform_to_xi_squared(0.5);
/// assert!((x - 0.25).abs() < 1e-6 && (pdf - 1.0).abs() < 1e-6);
/// ```
#[inline]
pub fn uniform_to_xi_squared(u: f32) -> (f32, f32) {
    let x = u * u;
    (x, xi_squared_pdf(x))
}

/// Density of [`uniform_to_xi_squared`]: 1/(2√x) on (0, 1], 0 elsewhere. At x = 0 the
/// density is infinite; this returns `f32::INFINITY` there (never NaN).
#[inline]
pub fn xi_squared_pdf(x: f32) -> f32 {
    if !(0.0..=1.0).contains(&x) {
        return 0.0;
    }
    if x == 0.0 {
        f32::INFINITY
    } else {
        0.5 / x.sqrt()
    }
}

/// Inverse of [`uniform_to_xi_squared`]: u = √x.
#[inline]
pub fn xi_squared_to_uniform(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_and_round_trip() {
        for u in [0.0, 0.1, 0.5, 0.999_999] {
            let (x, pdf) = uniform_to_xi_squared(u);
            assert!(!pdf.is_nan());
            assert!((xi_squared_to_uniform(x) - u).abs() < 1e-6);
        }
        assert_eq!(xi_squared_pdf(-0.1), 0.0);
        assert_eq!(xi_squared_pdf(1.5), 0.0);
    }
}
