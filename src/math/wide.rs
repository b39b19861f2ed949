//! Eight float lanes as one value ([`super::f64x8::F64x8`], [`super::f32x8::F32x8`]), for
//! kernels that run one scalar computation on eight independent inputs (the light
//! samples of eight shading points at once, `light::LightLanes`).
//!
//! Every operation is the scalar operation in a loop over the lanes, forced inline, so
//! that a kernel written with these types is one straight run of vector instructions
//! inside a function compiled for AVX2 (one or two 256-bit instructions per operation),
//! and the target's baseline SIMD elsewhere. Each lane rounds exactly as the scalar
//! operation does (Rust never fuses a multiply and an add). Written as closures over
//! plain arrays (`std::array::from_fn`), the same kernel left steps as calls to
//! SSE2-compiled helpers, its lanes in memory between steps: 54.7 ns a sample against
//! 47.0 ns with these types (`examples/rectangle_lanes.rs`, medians of 5; BENCHMARKS.md
//! session 34).

/// Lanes per value.
pub const N: usize = 8;

/// `[f(0), …, f(7)]` as a plain loop (forced inline, unlike `std::array::from_fn`).
#[inline(always)]
pub(super) fn each<T: Copy + Default>(f: impl Fn(usize) -> T) -> [T; N] {
    let mut out = [T::default(); N];
    for (l, o) in out.iter_mut().enumerate() {
        *o = f(l);
    }
    out
}

/// Defines `$wide`, eight `$float` lanes, and `$mask`, eight lane verdicts as all-ones
/// or all-zero `$bits` words (the form the wide comparisons produce, so that a select
/// needs no conversion), with the operations the lane kernels use.
macro_rules! float_lanes {
    ($wide:ident, $mask:ident, $float:ty, $bits:ty) => {
        use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

        use $crate::math::wide::{N, each};

        #[doc = concat!("Eight `", stringify!($float), "` lanes.")]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $wide(pub [$float; N]);

        #[doc = concat!("Eight lane verdicts of [`", stringify!($wide), "`].")]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub struct $mask([$bits; N]);

        impl $wide {
            /// Lane `l` is `f(l)`.
            #[inline(always)]
            pub fn from_fn(f: impl Fn(usize) -> $float) -> $wide {
                $wide(each(f))
            }

            /// Every lane `v`.
            #[inline(always)]
            pub fn splat(v: $float) -> $wide {
                $wide([v; N])
            }

            /// `sqrt` in every lane.
            #[inline(always)]
            pub fn sqrt(self) -> $wide {
                $wide::from_fn(|l| self.0[l].sqrt())
            }

            /// `abs` in every lane.
            #[inline(always)]
            pub fn abs(self) -> $wide {
                $wide::from_fn(|l| self.0[l].abs())
            }

            /// `max(self, v)` in every lane (`v` where a lane is NaN).
            #[inline(always)]
            pub fn max(self, v: $float) -> $wide {
                $wide::from_fn(|l| self.0[l].max(v))
            }

            /// `clamp(self, lo, hi)` in every lane (NaN stays NaN), for `lo ≤ hi`.
            #[inline(always)]
            pub fn clamp(self, lo: $float, hi: $float) -> $wide {
                debug_assert!(lo <= hi);
                $wide::from_fn(|l| self.0[l].clamp(lo, hi))
            }

            /// `copysign` in every lane.
            #[inline(always)]
            pub fn copysign(self, sign: $wide) -> $wide {
                $wide::from_fn(|l| self.0[l].copysign(sign.0[l]))
            }

            /// Lanes where `self < o`.
            #[inline(always)]
            pub fn lt(self, o: $wide) -> $mask {
                $mask::from_fn(|l| self.0[l] < o.0[l])
            }

            /// Lanes where `self > o`.
            #[inline(always)]
            pub fn gt(self, o: $wide) -> $mask {
                o.lt(self)
            }

            /// Lanes where `self ≥ o`.
            #[inline(always)]
            pub fn ge(self, o: $wide) -> $mask {
                $mask::from_fn(|l| self.0[l] >= o.0[l])
            }

            /// Lanes that are finite.
            #[inline(always)]
            pub fn is_finite(self) -> $mask {
                $mask::from_fn(|l| self.0[l].is_finite())
            }

            /// `if m { a } else { b }`, lane by lane.
            #[inline(always)]
            pub fn select(m: $mask, a: $wide, b: $wide) -> $wide {
                $wide::from_fn(|l| if m.0[l] != 0 { a.0[l] } else { b.0[l] })
            }
        }

        /// A vector's three coordinates over the lanes (structure of arrays).
        pub type V3 = [$wide; 3];

        /// The vectors `f(l)` of the lanes `l`, as [`V3`].
        #[inline(always)]
        pub fn v3(f: impl Fn(usize) -> [$float; 3]) -> V3 {
            [
                $wide::from_fn(|l| f(l)[0]),
                $wide::from_fn(|l| f(l)[1]),
                $wide::from_fn(|l| f(l)[2]),
            ]
        }

        /// `a · b` summed as glam's `dot` sums it: (a₀b₀ + a₁b₁) + a₂b₂.
        #[inline(always)]
        pub fn dot3(a: &V3, b: &V3) -> $wide {
            a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
        }

        impl $mask {
            /// Lane `l` set where `f(l)`.
            #[inline(always)]
            pub fn from_fn(f: impl Fn(usize) -> bool) -> $mask {
                $mask(each(|l| if f(l) { <$bits>::MAX } else { 0 }))
            }

            /// Whether lane `l` is set.
            #[inline(always)]
            pub fn get(self, l: usize) -> bool {
                self.0[l] != 0
            }
        }

        /// The binary operator `$op` (method `$f`) lane by lane, also with a scalar on
        /// either side.
        macro_rules! binary {
            ($op:ident, $f:ident) => {
                impl $op for $wide {
                    type Output = $wide;
                    #[inline(always)]
                    fn $f(self, o: $wide) -> $wide {
                        $wide::from_fn(|l| self.0[l].$f(o.0[l]))
                    }
                }
                impl $op<$float> for $wide {
                    type Output = $wide;
                    #[inline(always)]
                    fn $f(self, o: $float) -> $wide {
                        $wide::from_fn(|l| self.0[l].$f(o))
                    }
                }
                impl $op<$wide> for $float {
                    type Output = $wide;
                    #[inline(always)]
                    fn $f(self, o: $wide) -> $wide {
                        $wide::from_fn(|l| self.$f(o.0[l]))
                    }
                }
            };
        }

        binary!(Add, add);
        binary!(Sub, sub);
        binary!(Mul, mul);
        binary!(Div, div);

        impl Neg for $wide {
            type Output = $wide;
            #[inline(always)]
            fn neg(self) -> $wide {
                $wide::from_fn(|l| -self.0[l])
            }
        }

        impl BitAnd for $mask {
            type Output = $mask;
            #[inline(always)]
            fn bitand(self, o: $mask) -> $mask {
                $mask(each(|l| self.0[l] & o.0[l]))
            }
        }

        impl BitOr for $mask {
            type Output = $mask;
            #[inline(always)]
            fn bitor(self, o: $mask) -> $mask {
                $mask(each(|l| self.0[l] | o.0[l]))
            }
        }

        impl Not for $mask {
            type Output = $mask;
            #[inline(always)]
            fn not(self) -> $mask {
                $mask(each(|l| !self.0[l]))
            }
        }
    };
}

/// A test that every operation of `$wide` (mask `$mask`) is the scalar one lane by lane,
/// bit for bit, on the lanes `$v` and `$w` (which should hold zeros of both signs,
/// subnormals, infinities and NaN).
#[cfg(test)]
macro_rules! float_lanes_test {
    ($wide:ident, $float:ty, $v:expr, $w:expr) => {
        #[test]
        fn every_lane_is_the_scalar_operation() {
            let v: [$float; N] = $v;
            let w: [$float; N] = $w;
            let (a, b) = ($wide(v), $wide(w));
            let bits = |x: $wide| x.0.map(<$float>::to_bits);
            // Expected lanes built apart from the type's own loops.
            let lanes = |f: &dyn Fn(usize) -> $float| $wide(std::array::from_fn(f));
            let each2 = |f: fn($float, $float) -> $float| bits(lanes(&|l| f(v[l], w[l])));
            assert_eq!(bits(a + b), each2(|x, y| x + y));
            assert_eq!(bits(a - b), each2(|x, y| x - y));
            assert_eq!(bits(a * b), each2(|x, y| x * y));
            assert_eq!(bits(a / b), each2(|x, y| x / y));
            assert_eq!(bits(a.copysign(b)), each2(<$float>::copysign));
            assert_eq!(bits(2.0 - a), bits(lanes(&|l| 2.0 - v[l])));
            assert_eq!(bits(a / 9.0), bits(lanes(&|l| v[l] / 9.0)));
            assert_eq!(bits(-a), bits(lanes(&|l| -v[l])));
            assert_eq!(bits(a.sqrt()), bits(lanes(&|l| v[l].sqrt())));
            assert_eq!(bits(a.abs()), bits(lanes(&|l| v[l].abs())));
            assert_eq!(bits(a.max(1.0)), bits(lanes(&|l| v[l].max(1.0))));
            let clamped = bits(lanes(&|l| v[l].clamp(-1.0, 2.0)));
            assert_eq!(bits(a.clamp(-1.0, 2.0)), clamped);
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
                let s = $wide::select(lt, a, b).0[l].to_bits();
                assert_eq!(
                    s,
                    if v[l] < w[l] { v[l] } else { w[l] }.to_bits(),
                    "lane {l}"
                );
            }
        }
    };
}

pub(crate) use float_lanes;
#[cfg(test)]
pub(crate) use float_lanes_test;
