//! Small numerics shared by every module: shading frames, RGB spectra, bitmap texture
//! lookups.
//! Vectors themselves come from `glam`.

pub mod atan;
pub mod elliptic;
pub mod exp;
pub mod f32x8;
pub mod f64x8;
pub mod frame;
pub mod spectrum;
pub mod texture;
pub mod wide;

pub use frame::Frame;
pub use spectrum::Spectrum;

/// π as `f32`.
pub const PI: f32 = std::f32::consts::PI;
/// 1/π.
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;
/// 1/(2π).
pub const INV_TWO_PI: f32 = 0.5 * std::f32::consts::FRAC_1_PI;
/// 1/(4π).
pub const INV_FOUR_PI: f32 = 0.25 * std::f32::consts::FRAC_1_PI;

/// Largest |x| below which [`floor`] and [`ceil`] round through an `i32`.
const I32_RANGE: f32 = 2_147_483_648.0;

/// `x.floor()`, bit for bit (signed zeros, NaN and infinities included), without the
/// call to libm's `floorf` that baseline x86-64 needs for it (SSE2 has no rounding
/// instruction; `roundss` is SSE4.1): truncate through an `i32`, one less for negative
/// non-integers. Pixel footprints, environment-map and texture lookups round per sample.
#[inline]
pub fn floor(x: f32) -> f32 {
    if x.abs() < I32_RANGE {
        let t = x as i32 as f32;
        if t > x { t - 1.0 } else { t.copysign(x) }
    } else {
        x.floor()
    }
}

/// `x.ceil()`, bit for bit, without a libm call (see [`floor`]).
#[inline]
pub fn ceil(x: f32) -> f32 {
    if x.abs() < I32_RANGE {
        let t = x as i32 as f32;
        if t < x { t + 1.0 } else { t.copysign(x) }
    } else {
        x.ceil()
    }
}

/// `i.rem_euclid(n)` for `n > 0`, without the division where `i` lies in [−n, n): the
/// texel indices of lookups inside an image or one texel off its edge. A 64-bit division
/// costs tens of cycles, on the critical path of every environment-map and bitmap lookup.
#[inline]
pub fn rem_euclid_near(i: i64, n: i64) -> i64 {
    debug_assert!(n > 0, "modulus {n}");
    if (0..n).contains(&i) {
        i
    } else if (-n..0).contains(&i) {
        i + n
    } else {
        i.rem_euclid(n)
    }
}

/// `sqrt(max(x, 0))`: a square root that never produces NaN from rounding below zero.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_and_ceil_equal_the_standard_ones_bit_for_bit() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            1e-30,
            -1e-30,
            8_388_607.5,
            -8_388_607.5,
            16_777_217.0,
            2_147_483_520.0,
            -2_147_483_648.0,
            2_147_483_648.0,
            1e20,
            -1e20,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
        ];
        let mut state = 0x853c_49e6_748f_ea9bu64;
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            // Random bit patterns: every exponent, sign and fraction.
            values.push(f32::from_bits((state >> 32) as u32));
        }
        for x in values {
            assert_eq!(floor(x).to_bits(), x.floor().to_bits(), "floor({x:e})");
            assert_eq!(ceil(x).to_bits(), x.ceil().to_bits(), "ceil({x:e})");
        }
    }

    #[test]
    fn rem_euclid_near_is_rem_euclid() {
        for n in [1i64, 2, 3, 7, 64, 1 << 40, i64::MAX] {
            let (up, down) = (n.saturating_mul(3), n.saturating_mul(-3).saturating_sub(2));
            let edges = [
                0,
                1,
                n - 1,
                n,
                n.saturating_add(1),
                -1,
                -n,
                -n - 1,
                up,
                down,
            ];
            let far = [i64::MIN, i64::MIN + 1, i64::MAX, i64::MAX - 1];
            for i in edges.into_iter().chain(far).chain(-70..70) {
                assert_eq!(rem_euclid_near(i, n), i.rem_euclid(n), "{i} mod {n}");
            }
        }
    }
}
