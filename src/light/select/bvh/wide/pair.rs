//! [`WideNode::importance`] of two nodes at two shading points in one pass over eight
//! AVX lanes: node `a`'s four children in lanes 0–3, node `b`'s in lanes 4–7. Two walks
//! of the light tree (`bvh::lanes`) then share every instruction of their importances,
//! and the divider, which the five square roots and three divisions of an importance
//! keep busy, does twice the work per instruction.
//!
//! Each lane computes what [`WideNode::importance`] computes with `glam::Vec4` on SSE,
//! step for step, with the same instructions' semantics (`maxps` keeps its second
//! operand where the first is not greater, `recip` is `1 / x`, a select is a bitwise
//! blend), so each lane's importance is the four-lane one bit for bit; the tests
//! (`wide/tests.rs`) check it. Written with the AVX intrinsics themselves: the same
//! steps over `[f32; 8]` arrays were compiled to 128-bit halves. Nodes of point lights
//! take the full formula here, which gives them the same bits as the short one
//! ([`WideNode::point_importance`]), unless both nodes are of point lights.

use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use super::{LANES, WideNode};
use crate::light::ShadingPoint;

/// Eight f32 lanes in one AVX register. Its operations are forced inline and meant for
/// functions compiled with AVX2 enabled (only [`importance_pair`] uses them).
#[derive(Clone, Copy)]
struct W(__m256);

/// Eight lane verdicts, all ones or all zeros.
#[derive(Clone, Copy)]
struct Mask(__m256);

macro_rules! lane_op {
    ($trait:ident, $f:ident, $intrinsic:ident) => {
        impl $trait for W {
            type Output = W;
            #[inline(always)]
            fn $f(self, o: W) -> W {
                // SAFETY: only reached from functions compiled for AVX2 (see `W`).
                W(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}
lane_op!(Add, add, _mm256_add_ps);
lane_op!(Sub, sub, _mm256_sub_ps);
lane_op!(Mul, mul, _mm256_mul_ps);
lane_op!(Div, div, _mm256_div_ps);

impl Neg for W {
    type Output = W;
    #[inline(always)]
    fn neg(self) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_xor_ps(_mm256_set1_ps(-0.0), self.0) })
    }
}

impl BitAnd for Mask {
    type Output = Mask;
    #[inline(always)]
    fn bitand(self, o: Mask) -> Mask {
        // SAFETY: as for the operators above.
        Mask(unsafe { _mm256_and_ps(self.0, o.0) })
    }
}

impl BitOr for Mask {
    type Output = Mask;
    #[inline(always)]
    fn bitor(self, o: Mask) -> Mask {
        // SAFETY: as for the operators above.
        Mask(unsafe { _mm256_or_ps(self.0, o.0) })
    }
}

impl Not for Mask {
    type Output = Mask;
    #[inline(always)]
    fn not(self) -> Mask {
        // SAFETY: as for the operators above.
        Mask(unsafe { _mm256_xor_ps(self.0, _mm256_castsi256_ps(_mm256_set1_epi32(-1))) })
    }
}

/// The comparisons `glam::Vec4` makes on SSE (ordered, but for `ne`), lane by lane.
macro_rules! comparisons {
    ($($f:ident => $predicate:ident),*) => {
        impl W {
            $(
                #[inline(always)]
                fn $f(self, o: W) -> Mask {
                    // SAFETY: as for the operators above.
                    Mask(unsafe { _mm256_cmp_ps::<$predicate>(self.0, o.0) })
                }
            )*
        }
    };
}
comparisons!(
    gt => _CMP_GT_OQ,
    le => _CMP_LE_OQ,
    lt => _CMP_LT_OQ,
    eq => _CMP_EQ_OQ,
    ne => _CMP_NEQ_UQ
);

/// The methods of `glam::Vec4` the importance uses, with its SSE semantics.
impl W {
    #[inline(always)]
    fn splat(x: f32) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_set1_ps(x) })
    }

    /// Lanes 0–3 from `a`, lanes 4–7 from `b`.
    #[inline(always)]
    fn both(a: &[f32; LANES], b: &[f32; LANES]) -> W {
        // SAFETY: as above; each array is four floats.
        W(unsafe { _mm256_set_m128(_mm_loadu_ps(b.as_ptr()), _mm_loadu_ps(a.as_ptr())) })
    }

    /// `x` in lanes 0–3, `y` in lanes 4–7.
    #[inline(always)]
    fn halves(x: f32, y: f32) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_set_m128(_mm_set1_ps(y), _mm_set1_ps(x)) })
    }

    #[inline(always)]
    fn sqrt(self) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_sqrt_ps(self.0) })
    }

    #[inline(always)]
    fn abs(self) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_and_ps(self.0, _mm256_castsi256_ps(_mm256_set1_epi32(i32::MAX))) })
    }

    /// `maxps`: `self` where `self > o`, else `o`.
    #[inline(always)]
    fn max(self, o: W) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_max_ps(self.0, o.0) })
    }

    /// glam's `is_finite_mask`: |x| < ∞.
    #[inline(always)]
    fn is_finite(self) -> Mask {
        self.abs().lt(W::splat(f32::INFINITY))
    }

    /// glam's `Vec4::select`: a bitwise blend.
    #[inline(always)]
    fn select(m: Mask, a: W, b: W) -> W {
        // SAFETY: as for the operators above.
        W(unsafe { _mm256_or_ps(_mm256_andnot_ps(m.0, b.0), _mm256_and_ps(a.0, m.0)) })
    }

    /// Lanes 0–3 and 4–7.
    #[inline(always)]
    fn split(self) -> ([f32; LANES], [f32; LANES]) {
        let mut out = [0.0f32; 2 * LANES];
        // SAFETY: as above; `out` holds eight floats.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) };
        let (lo, hi) = out.split_at(LANES);
        (lo.try_into().expect("four"), hi.try_into().expect("four"))
    }
}

/// The importances of `a`'s children at `at_a` and of `b`'s at `at_b`.
#[inline]
#[target_feature(enable = "avx2")]
pub(in super::super) fn importance_pair(
    a: &WideNode,
    at_a: &ShadingPoint,
    b: &WideNode,
    at_b: &ShadingPoint,
) -> ([f32; LANES], [f32; LANES]) {
    let both = W::both;
    let (zero, one) = (W::splat(0.0), W::splat(1.0));
    let safe_sqrt = |x: W| x.max(zero).sqrt();
    let sight = Sight::new(a, at_a, b, at_b);
    let d2 = sight.dist2.max(both(&a.d2_floor, &b.d2_floor));
    let phi = both(&a.phi, &b.phi);
    let importance = if a.points && b.points {
        // WideNode::point_importance.
        let cos_pi = W::select(sight.cos_i.gt(one), one, sight.cos_i);
        let importance = phi / d2 * cos_pi;
        kept(phi, importance, one.eq(one), d2, cos_pi, sight.above)
    } else {
        let [wx, wy, wz] = sight.w;
        let cos_w_signed =
            both(&a.w[0], &b.w[0]) * wx + both(&a.w[1], &b.w[1]) * wy + both(&a.w[2], &b.w[2]) * wz;
        let two_sided = both(&a.two_sided, &b.two_sided).ne(zero);
        let cos_w = W::select(two_sided, cos_w_signed.abs(), cos_w_signed);
        let sin_w = safe_sqrt(one - cos_w * cos_w);
        // The cone the bounding sphere subtends.
        let dist2 = sight.dist2;
        let r2 = both(&a.radius2, &b.radius2);
        let around = dist2.le(r2) | dist2.eq(zero);
        let cos_b = W::select(around, W::splat(-1.0), safe_sqrt(one - r2 / dist2));
        let sin_b = safe_sqrt(one - cos_b * cos_b);
        // θ' = max(0, θ_w − θ_o − θ_b).
        let (cos_o, sin_o) = (both(&a.cos_o, &b.cos_o), both(&a.sin_o, &b.sin_o));
        let inside_cone = cos_w.gt(cos_o);
        let cos_x = W::select(inside_cone, one, cos_w * cos_o + sin_w * sin_o);
        let sin_x = W::select(inside_cone, zero, sin_w * cos_o - cos_w * sin_o);
        let cos_p = W::select(cos_x.gt(cos_b), one, cos_x * cos_b + sin_x * sin_b);
        // θ'_i = max(0, θ_i − θ_b).
        let cos_i = sight.cos_i;
        let sin_i = safe_sqrt(one - cos_i * cos_i);
        let cos_pi = W::select(cos_i.gt(cos_b), one, cos_i * cos_b + sin_i * sin_b);
        // The box's highest point above the shading point's tangent plane.
        let (na, nb) = (at_a.n.abs(), at_b.n.abs());
        let highest = sight.above
            + (W::halves(na.x, nb.x) * both(&a.half[0], &b.half[0])
                + W::halves(na.y, nb.y) * both(&a.half[1], &b.half[1])
                + W::halves(na.z, nb.z) * both(&a.half[2], &b.half[2]));
        let importance = phi * cos_p / d2 * cos_pi;
        let lit = !cos_p.le(both(&a.cos_e, &b.cos_e));
        kept(phi, importance, lit, d2, cos_pi, highest)
    };
    importance.split()
}

/// What both formulas derive from the shading points and the lanes' centres
/// (`WideNode::sight`).
struct Sight {
    dist2: W,
    w: [W; 3],
    cos_i: W,
    above: W,
}

impl Sight {
    #[inline(always)]
    fn new(a: &WideNode, at_a: &ShadingPoint, b: &WideNode, at_b: &ShadingPoint) -> Sight {
        let zero = W::splat(0.0);
        let halves = W::halves;
        let (p, q) = (at_a.p, at_b.p);
        let (m, n) = (at_a.n, at_b.n);
        let (px, py, pz) = (halves(p.x, q.x), halves(p.y, q.y), halves(p.z, q.z));
        let (nx, ny, nz) = (halves(m.x, n.x), halves(m.y, n.y), halves(m.z, n.z));
        let cx = W::both(&a.centre[0], &b.centre[0]);
        let cy = W::both(&a.centre[1], &b.centre[1]);
        let cz = W::both(&a.centre[2], &b.centre[2]);
        let (vx, vy, vz) = (px - cx, py - cy, pz - cz);
        let dist2 = vx * vx + vy * vy + vz * vz;
        let rcp = one_over(dist2.sqrt());
        // wi: from the cluster towards the shading point, zero where it has no length.
        let unit = rcp.is_finite() & rcp.gt(zero);
        let w = [vx * rcp, vy * rcp, vz * rcp].map(|x| W::select(unit, x, zero));
        Sight {
            dist2,
            cos_i: nx * -w[0] + ny * -w[1] + nz * -w[2],
            above: nx * (cx - px) + ny * (cy - py) + nz * (cz - pz),
            w,
        }
    }
}

/// glam's `recip`: `1 / x`.
#[inline(always)]
fn one_over(x: W) -> W {
    W::splat(1.0) / x
}

/// `importance` in the lanes that pass every test, 0 elsewhere (`WideNode::kept`).
#[inline(always)]
fn kept(phi: W, importance: W, lit: Mask, d2: W, cos_pi: W, highest: W) -> W {
    let zero = W::splat(0.0);
    let contributes = phi.gt(zero)
        & !d2.le(zero)
        & lit
        & !cos_pi.le(zero)
        & !highest.le(zero)
        & importance.is_finite();
    W::select(contributes, importance.max(zero), zero)
}
