//! Error metrics of an image against a reference: MSE, relMSE, the relative bias of the
//! image sum with its standard error, and non-finite counts; plus a false-colour map.

use crate::math::Spectrum;

/// The ε in relMSE = mean((v − r)²/(r² + ε)), which keeps dark pixels from dominating.
pub const REL_MSE_EPSILON: f32 = 0.01;

/// How an image differs from a reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorReport {
    /// Mean squared error over pixels and channels.
    pub mse: f64,
    /// Mean of (v − r)²/(r² + 0.01) over pixels and channels.
    pub rel_mse: f64,
    /// (Σv − Σr)/Σr over pixels and channels; None (undefined) when Σr = 0.
    pub relative_bias: Option<f64>,
    /// Standard error of `relative_bias`, from the image's per-pixel variance (and the
    /// reference's, when it has one).
    pub bias_std_error: Option<f64>,
    /// Pixels (of the image) with a NaN channel.
    pub nan_pixels: usize,
    /// Pixels (of the image) with an infinite channel.
    pub inf_pixels: usize,
}

impl ErrorReport {
    /// The bias in standard errors (None without variance).
    pub fn bias_z(&self) -> Option<f64> {
        let se = self.bias_std_error.filter(|s| *s > 0.0)?;
        Some(self.relative_bias? / se)
    }

    /// The relative bias in percent (`+1.23%`), or `undefined` against an all-zero
    /// reference.
    pub fn relative_bias_percent(&self) -> String {
        self.relative_bias
            .map_or("undefined".into(), |b| format!("{:+.2}%", 100.0 * b))
    }
}

/// Per-pixel relative squared error, averaged over channels.
#[inline]
pub fn pixel_rel_mse(v: Spectrum, r: Spectrum) -> f32 {
    let d = v - r;
    ((d * d) / (r * r + Spectrum::splat(REL_MSE_EPSILON))).element_sum() / 3.0
}

/// Compares `image` (with optional variance of each pixel's mean) to `reference`.
/// Non-finite pixels are counted and left out of the sums. Slices must have equal length.
pub fn compare(
    image: &[Spectrum],
    variance: Option<&[Spectrum]>,
    reference: &[Spectrum],
    reference_variance: Option<&[Spectrum]>,
) -> ErrorReport {
    let (mut se, mut rel, mut sum_v, mut sum_r, mut var) = (0f64, 0f64, 0f64, 0f64, 0f64);
    let (mut nan, mut inf, mut n) = (0, 0, 0usize);
    for (i, (&v, &r)) in image.iter().zip(reference).enumerate() {
        if v.is_nan() {
            nan += 1;
            continue;
        }
        if !v.is_finite() {
            inf += 1;
            continue;
        }
        let d = v - r;
        se += (d * d).element_sum() as f64;
        rel += pixel_rel_mse(v, r) as f64 * 3.0;
        sum_v += v.element_sum() as f64;
        sum_r += r.element_sum() as f64;
        if let Some(vv) = variance {
            var += vv[i].element_sum() as f64;
        }
        if let Some(rv) = reference_variance {
            var += rv[i].element_sum() as f64;
        }
        n += 3;
    }
    let n = n.max(1) as f64;
    let has_var = variance.is_some() || reference_variance.is_some();
    ErrorReport {
        mse: se / n,
        rel_mse: rel / n,
        relative_bias: (sum_r != 0.0).then(|| (sum_v - sum_r) / sum_r),
        bias_std_error: (has_var && sum_r != 0.0).then(|| var.sqrt() / sum_r.abs()),
        nan_pixels: nan,
        inf_pixels: inf,
    }
}

/// A colour for t in [0, 1] on a perceptually ordered dark-blue → yellow ramp (five
/// stops sampled from matplotlib's viridis).
pub fn ramp(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let x = t * 4.0;
    let i = (x as usize).min(3);
    let f = x - i as f32;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    [0, 1, 2].map(|c| (a[c] + (b[c] - a[c]) * f + 0.5) as u8)
}

/// False-colour bytes (RGB8) of per-pixel relMSE on a log scale from 10⁻⁴ (dark) to
/// 10 (bright); non-finite pixels are magenta.
pub fn false_color(image: &[Spectrum], reference: &[Spectrum]) -> Vec<u8> {
    image
        .iter()
        .zip(reference)
        .flat_map(|(&v, &r)| {
            if !v.is_finite() {
                return [255, 0, 255];
            }
            let e = pixel_rel_mse(v, r).max(1e-12).log10();
            ramp((e + 4.0) / 5.0)
        })
        .collect()
}

/// Side of the blocks [`signed_difference`] averages over.
pub const DIFFERENCE_BLOCK: u32 = 8;

/// The signed relative difference (image − reference)/reference of luminance averaged
/// over [`DIFFERENCE_BLOCK`]² blocks (so bias shows through the noise), as RGB8: white
/// for none, red where the image is brighter, blue where it is darker, saturated at
/// ±50 %. Blocks where the reference is black are grey.
pub fn signed_difference(
    image: &[Spectrum],
    reference: &[Spectrum],
    width: u32,
    height: u32,
) -> Vec<u8> {
    let b = DIFFERENCE_BLOCK;
    let (bw, bh) = (width.div_ceil(b), height.div_ceil(b));
    let mut sums = vec![(0.0f64, 0.0f64); (bw * bh) as usize];
    for (i, (&v, &r)) in image.iter().zip(reference).enumerate() {
        let (x, y) = (i as u32 % width, i as u32 / width);
        let cell = &mut sums[((y / b) * bw + x / b) as usize];
        cell.0 += crate::math::spectrum::luminance(v) as f64;
        cell.1 += crate::math::spectrum::luminance(r) as f64;
    }
    (0..width * height)
        .flat_map(|i| {
            let (x, y) = (i % width, i / width);
            let (v, r) = sums[((y / b) * bw + x / b) as usize];
            if r.is_nan() || r <= 0.0 || !v.is_finite() {
                return [128, 128, 128];
            }
            let d = ((v - r) / r / 0.5).clamp(-1.0, 1.0) as f32;
            let fade = (255.0 * (1.0 - d.abs())) as u8;
            if d >= 0.0 {
                [255, fade, fade]
            } else {
                [fade, fade, 255]
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_values() {
        let r = [Spectrum::splat(1.0), Spectrum::splat(0.0)];
        let v = [Spectrum::splat(2.0), Spectrum::splat(0.1)];
        let e = compare(&v, None, &r, None);
        assert!((e.mse - (1.0 + 0.01) / 2.0).abs() < 1e-6);
        assert!((e.rel_mse - (1.0 / 1.01 + 0.01 / 0.01) / 2.0).abs() < 1e-5);
        assert!((e.relative_bias.unwrap() - (6.3 - 3.0) / 3.0).abs() < 1e-5);
        let same = compare(&r, None, &r, None);
        assert_eq!(
            (same.mse, same.rel_mse, same.relative_bias),
            (0.0, 0.0, Some(0.0))
        );
        // Against an all-zero reference the relative bias is undefined, not 0.
        let zero = [Spectrum::ZERO; 2];
        let undefined = compare(&v, None, &zero, None);
        assert_eq!(undefined.relative_bias, None);
        assert_eq!(undefined.relative_bias_percent(), "undefined");
        let nan = compare(
            &[Spectrum::splat(f32::NAN), Spectrum::splat(f32::INFINITY)],
            None,
            &r,
            None,
        );
        assert_eq!((nan.nan_pixels, nan.inf_pixels), (1, 1));
    }
}
