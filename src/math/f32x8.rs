//! Eight f32 lanes as one value ([`crate::math::wide`]), for kernels that run one scalar
//! f32 computation on eight independent inputs (the sphere lights' solid-angle samples,
//! `light::area::sphere_lanes`): one 256-bit instruction per operation inside a function
//! compiled for AVX2, two SSE2 ones in the baseline build.

crate::math::wide::float_lanes!(F32x8, Mask32x8, f32, u32);

#[cfg(test)]
mod tests {
    use super::*;

    crate::math::wide::float_lanes_test!(
        F32x8,
        f32,
        [0.0, -0.0, 1.5, -2.25, 1e-45, f32::INFINITY, f32::NAN, -7e37],
        [3.0, -0.0, 1.5, 0.0, -1.0, f32::INFINITY, 2.0, 1e-38]
    );
}
