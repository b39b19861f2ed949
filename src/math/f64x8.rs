//! Eight f64 lanes as one value, for kernels that run one scalar computation on eight
//! independent inputs (the spherical-rectangle lanes, `sampling::warp::
//! spherical_rectangle_lanes`).
//!
//! Every operation is the scalar operation in a loop over the lanes, forced inline, so
//! that a kernel written with these types is one straight run of vector instructions:
//! two 256-bit instructions per operation inside a function compiled for AVX2, four
//! SSE2 ones in the baseline build. Each lane rounds exactly as the scalar operation does
//! (Rust never fuses a multiply and an add). Written as closures over `[f64; 8]`
//! (`std::array::from_fn`), the same kernel left five steps as calls to SSE2-compiled
//! helpers, its lanes in memory between steps: 54.7 ns a sample against 47.0 ns with
//! these types (`examples/rectangle_lanes.rs`, medians of 5; BENCHMARKS.md session 34).

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Lanes per value.
pub const N: usize = 8;

/// Eight f64 lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct F64x8(pub [f64; N]);

/// Eight lane verdicts, as all-ones or all-zero 64-bit words (the form the wide
/// comparisons produce, so that a select needs no conversion).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mask8([u64; N]);

/// `[f(0), …, f(7)]` as a plain loop (forced inline, unlike `std::array::from_fn`).
#[inline(always)]
fn each<T: Copy + Default>(f: impl Fn(usize) -> T) -> [T; N] {
    let mut out = [T::default(); N];
    for (l, o) in out.iter_mut().enumerate() {
        *o = f(l);
    }
    out
}

impl F64x8 {
    /// Lane `l` is `f(l)`.
    #[inline(always)]
    pub fn from_fn(f: impl Fn(usize) -> f64) -> F64x8 {
        F64x8(each(f))
    }

    /// Every lane `v`.
    #[inline(always)]
    pub fn splat(v: f64) -> F64x8 {
        F64x8([v; N])
    }

    /// `f64::sqrt` in every lane.
    #[inline(always)]
    pub fn sqrt(self) -> F64x8 {
        F64x8::from_fn(|l| self.0[l].sqrt())
    }

    /// `f64::abs` in every lane.
    #[inline(always)]
    pub fn abs(self) -> F64x8 {
        F64x8::from_fn(|l| self.0[l].abs())
    }

    /// `f64::max(self, v)` in every lane (`v` where a lane is NaN).
    #[inline(always)]
    pub fn max(self, v: f64) -> F64x8 {
        F64x8::from_fn(|l| self.0[l].max(v))
    }

    /// `f64::copysign` in every lane.
    #[inline(always)]
    pub fn copysign(self, sign: F64x8) -> F64x8 {
        F64x8::from_fn(|l| self.0[l].copysign(sign.0[l]))
    }

    /// Lanes where `self < o`.
    #[inline(always)]
    pub fn lt(self, o: F64x8) -> Mask8 {
        Mask8::from_fn(|l| self.0[l] < o.0[l])
    }

    /// Lanes where `self > o`.
    #[inline(always)]
    pub fn gt(self, o: F64x8) -> Mask8 {
        o.lt(self)
    }

    /// Lanes where `self ≥ o`.
    #[inline(always)]
    pub fn ge(self, o: F64x8) -> Mask8 {
        Mask8::from_fn(|l| self.0[l] >= o.0[l])
    }

    /// Lanes that are finite.
    #[inline(always)]
    pub fn is_finite(self) -> Mask8 {
        Mask8::from_fn(|l| self.0[l].is_finite())
    }

    /// `if self { a } else { b }` where the mask is `m`, lane by lane.
    #[inline(always)]
    pub fn select(m: Mask8, a: F64x8, b: F64x8) -> F64x8 {
        F64x8::from_fn(|l| if m.0[l] != 0 { a.0[l] } else { b.0[l] })
    }
}

impl Mask8 {
    /// Lane `l` set where `f(l)`.
    #[inline(always)]
    pub fn from_fn(f: impl Fn(usize) -> bool) -> Mask8 {
        Mask8(each(|l| if f(l) { u64::MAX } else { 0 }))
    }

    /// Whether lane `l` is set.
    #[inline(always)]
    pub fn get(self, l: usize) -> bool {
        self.0[l] != 0
    }
}

/// The binary operator `$op` (method `$f`) lane by lane, also with an f64 on either side.
macro_rules! binary {
    ($op:ident, $f:ident) => {
        impl $op for F64x8 {
            type Output = F64x8;
            #[inline(always)]
            fn $f(self, o: F64x8) -> F64x8 {
                F64x8::from_fn(|l| self.0[l].$f(o.0[l]))
            }
        }
        impl $op<f64> for F64x8 {
            type Output = F64x8;
            #[inline(always)]
            fn $f(self, o: f64) -> F64x8 {
                F64x8::from_fn(|l| self.0[l].$f(o))
            }
        }
        impl $op<F64x8> for f64 {
            type Output = F64x8;
            #[inline(always)]
            fn $f(self, o: F64x8) -> F64x8 {
                F64x8::from_fn(|l| self.$f(o.0[l]))
            }
        }
    };
}

binary!(Add, add);
binary!(Sub, sub);
binary!(Mul, mul);
binary!(Div, div);

impl Neg for F64x8 {
    type Output = F64x8;
    #[inline(always)]
    fn neg(self) -> F64x8 {
        F64x8::from_fn(|l| -self.0[l])
    }
}

impl BitAnd for Mask8 {
    type Output = Mask8;
    #[inline(always)]
    fn bitand(self, o: Mask8) -> Mask8 {
        Mask8(each(|l| self.0[l] & o.0[l]))
    }
}

impl BitOr for Mask8 {
    type Output = Mask8;
    #[inline(always)]
    fn bitor(self, o: Mask8) -> Mask8 {
        Mask8(each(|l| self.0[l] | o.0[l]))
    }
}

impl Not for Mask8 {
    type Output = Mask8;
    #[inline(always)]
    fn not(self) -> Mask8 {
        Mask8(each(|l| !self.0[l]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation is the scalar one lane by lane, bit for bit, on values that
    /// include zeros of both signs, subnormals, infinities and NaN.
    #[test]
    fn every_lane_is_the_scalar_operation() {
        let v = [
            0.0,
            -0.0,
            1.5,
            -2.25,
            5e-324,
            f64::INFINITY,
            f64::NAN,
            -7e300,
        ];
        let w = [3.0, -0.0, 1.5, 0.0, -1.0, f64::INFINITY, 2.0, 1e-300];
        let (a, b) = (F64x8(v), F64x8(w));
        let bits = |x: F64x8| x.0.map(f64::to_bits);
        // Expected lanes built apart from the type's own loops.
        let lanes = |f: &dyn Fn(usize) -> f64| F64x8(std::array::from_fn(f));
        let each2 = |f: fn(f64, f64) -> f64| bits(lanes(&|l| f(v[l], w[l])));
        assert_eq!(bits(a + b), each2(|x, y| x + y));
        assert_eq!(bits(a - b), each2(|x, y| x - y));
        assert_eq!(bits(a * b), each2(|x, y| x * y));
        assert_eq!(bits(a / b), each2(|x, y| x / y));
        assert_eq!(bits(a.copysign(b)), each2(f64::copysign));
        assert_eq!(bits(2.0 - a), bits(lanes(&|l| 2.0 - v[l])));
        assert_eq!(bits(a / 9.0), bits(lanes(&|l| v[l] / 9.0)));
        assert_eq!(bits(-a), bits(lanes(&|l| -v[l])));
        assert_eq!(bits(a.sqrt()), bits(lanes(&|l| v[l].sqrt())));
        assert_eq!(bits(a.abs()), bits(lanes(&|l| v[l].abs())));
        assert_eq!(bits(a.max(1.0)), bits(lanes(&|l| v[l].max(1.0))));
        for l in 0..N {
            assert_eq!(a.lt(b).get(l), v[l] < w[l], "lane {l}");
            assert_eq!(a.gt(b).get(l), v[l] > w[l], "lane {l}");
            assert_eq!(a.ge(b).get(l), v[l] >= w[l], "lane {l}");
            assert_eq!(a.is_finite().get(l), v[l].is_finite(), "lane {l}");
            let (lt, ge) = (a.lt(b), a.ge(b));
            assert!(!(lt & ge).get(l), "lane {l}");
            assert_eq!(
                (lt | ge).get(l),
                !(v[l].is_nan() || w[l].is_nan()),
                "lane {l}"
            );
            assert_eq!((!lt).get(l), !lt.get(l), "lane {l}");
            let s = F64x8::select(lt, a, b).0[l].to_bits();
            assert_eq!(
                s,
                if v[l] < w[l] { v[l] } else { w[l] }.to_bits(),
                "lane {l}"
            );
        }
    }
}
