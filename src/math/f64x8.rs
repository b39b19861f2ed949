//! Eight f64 lanes as one value ([`crate::math::wide`]), for kernels that run one scalar
//! f64 computation on eight independent inputs (the spherical-rectangle lanes,
//! `sampling::warp::spherical_rectangle_lanes`): two 256-bit instructions per operation
//! inside a function compiled for AVX2, four SSE2 ones in the baseline build.

crate::math::wide::float_lanes!(F64x8, Mask8, f64, u64);

#[cfg(test)]
mod tests {
    use super::*;

    crate::math::wide::float_lanes_test!(
        F64x8,
        f64,
        [
            0.0,
            -0.0,
            1.5,
            -2.25,
            5e-324,
            f64::INFINITY,
            f64::NAN,
            -7e300
        ],
        [3.0, -0.0, 1.5, 0.0, -1.0, f64::INFINITY, 2.0, 1e-300]
    );
}
