//! eˣ on four lanes at once, for the Gaussian reconstruction filter's weights (each
//! splat evaluates the filter at four pixel offsets per axis; glibc's `expf`, 45
//! instructions a call, twice per weight, was 16 % of a Gaussian-filtered render's
//! instructions).
//!
//! Cephes' `expf` (Moshier 1989, "Methods and Programs for Mathematical Functions"):
//! n = round(x·log₂e), r = x − n·ln 2 with ln 2 split in two so that r is exact,
//! eʳ = 1 + r + r²·P(r) with P of degree 5 on |r| ≤ ln 2 / 2, and 2ⁿ built in the
//! exponent bits. Relative error at most 7.9·10⁻⁸ on [−87, 88] (test below, against f64).

use glam::Vec4;

/// ln 2 = LN2_HI + LN2_LO, LN2_HI with few mantissa bits so that n·LN2_HI is exact.
const LN2_HI: f32 = 0.693_359_4;
const LN2_LO: f32 = -2.121_944_4e-4;
/// P's coefficients, highest degree first.
const P: [f32; 6] = [
    1.987_569_1e-4,
    1.398_2e-3,
    8.333_452e-3,
    4.166_579_6e-2,
    0.166_666_65,
    0.5,
];
/// 1.5·2²³: adding and subtracting it rounds |t| < 2²² to the nearest integer.
const ROUND: f32 = 12_582_912.0;

/// eˣ per lane, for finite x; arguments are clamped to [−87, 88], where eˣ is a normal
/// f32 (so below −87 the result is e⁻⁸⁷ ≈ 1.6·10⁻³⁸, not a subnormal or zero).
#[inline]
pub fn exp4(x: Vec4) -> Vec4 {
    let x = x.clamp(Vec4::splat(-87.0), Vec4::splat(88.0));
    let n = (x * std::f32::consts::LOG2_E + ROUND) - ROUND;
    let r = x - n * LN2_HI - n * LN2_LO;
    let mut p = Vec4::splat(P[0]);
    for &c in &P[1..] {
        p = p * r + c;
    }
    (p * (r * r) + r + 1.0) * pow2(n)
}

/// 2ⁿ for integral n in [−126, 127], from the exponent bits.
#[inline(always)]
fn pow2(n: Vec4) -> Vec4 {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{
            _mm_add_epi32, _mm_castsi128_ps, _mm_cvttps_epi32, _mm_set1_epi32, _mm_slli_epi32,
        };
        // SAFETY: SSE2 is part of the x86-64 baseline, so these instructions always exist.
        unsafe {
            let i = _mm_add_epi32(_mm_cvttps_epi32(n.into()), _mm_set1_epi32(127));
            Vec4::from(_mm_castsi128_ps(_mm_slli_epi32::<23>(i)))
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        Vec4::from_array(
            n.to_array()
                .map(|n| f32::from_bits(((n as i32 + 127) as u32) << 23)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_f64_exp_to_a_tenth_of_a_millionth() {
        let mut worst = 0.0f64;
        let (lo, hi, steps) = (-87.0f32, 88.0f32, 400_000);
        for i in (0..steps).step_by(4) {
            let x = Vec4::from_array(
                [0, 1, 2, 3].map(|k| lo + (hi - lo) * (i + k) as f32 / steps as f32),
            );
            let y = exp4(x);
            for k in 0..4 {
                let exact = (x[k] as f64).exp();
                worst = worst.max(((y[k] as f64 - exact) / exact).abs());
            }
        }
        assert!(worst < 1e-7, "worst relative error {worst:e}");
        // Exact where it must be, and clamped outside the range.
        assert_eq!(exp4(Vec4::ZERO), Vec4::ONE);
        let far = exp4(Vec4::new(-1e4, -87.0, 88.0, 1e4));
        assert!(far.x > 0.0 && far.x == far.y && far.z == far.w && far.w.is_finite());
    }
}
