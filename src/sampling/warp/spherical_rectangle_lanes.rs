//! [`FastSphericalRectangle`](super::FastSphericalRectangle) for [`LANES`] shading points at once: the same map, the
//! same operations in the same order on each lane, so each lane's point and density are
//! the scalar version's bit for bit (a test checks it; Rust never fuses a multiply and
//! an add, so the wide instructions round as the scalar ones do).
//!
//! Why: one solid-angle sample of a rectangle is a chain of about 30 dependent f64
//! square roots, divisions and products (Ureña et al. 2013, Algorithm 1), and a core
//! spends most of its ≈ 110 ns waiting on that chain. Eight independent chains side by
//! side, in two AVX2 registers of four f64 lanes each, keep the core busy: 3.2–3.4× the
//! throughput of one chain (four lanes gave 2.5–2.6×), measured on the renderer's
//! placement of a ceiling light (`examples/rectangle_lanes.rs`). An AVX-512 build of the
//! same kernel (one register per step) was 4–10 % faster in that example and no faster
//! in a render, so it is not dispatched. Branches of the scalar
//! version become per-lane selects: both sides are computed, each lane keeps the one the
//! scalar code takes. The steps are written with [`F64x8`], whose every operation is
//! forced inline, so the kernel is one straight run of vector instructions (54.7 → 47.0
//! ns a sample in that example, session 34); it now waits mostly on its 15 divisions and
//! 11 square roots per lane, which the divider takes one at a time.
//!
//! Dispatch at run time: AVX2 where the processor has it (`is_x86_feature_detected!`),
//! else the same code for the target's baseline (SSE2 on x86-64, NEON on aarch64). The
//! f32 `sin_cos` of u₀·S stays a per-lane call into the C library, as in the scalar
//! version, so the bits agree.

use glam::{Vec2, Vec3};

use super::spherical_rectangle_fast::RectangleFrame;
use super::spherical_triangle::MIN_SOLID_ANGLE;
use crate::math::atan::atan_unit;
use crate::math::f64x8::{F64x8, dot3 as dot, v3};

/// Shading points per call: eight chains hide each other's latency better than four
/// (43 → 34 ns a sample), and a staged chunk holds 64 samples.
pub const LANES: usize = 8;

type F = F64x8;

/// One lane's rectangle and shading point: the rectangle's frame, its corner (the
/// origin of its edges), the shading point and the sample's two numbers.
#[derive(Clone, Copy, Debug)]
pub struct RectangleLane<'a> {
    /// The rectangle's edge frame.
    pub frame: &'a RectangleFrame,
    /// The corner its edges start from.
    pub corner: Vec3,
    /// The shading point.
    pub p: Vec3,
    /// The sample's two uniform numbers.
    pub u: Vec2,
}

/// For each lane, what [`FastSphericalRectangle::from_frame`] followed by
/// [`FastSphericalRectangle::sample`] gives: `Some((offset from p to the rectangle's
/// point, density 1/S))`, or `None` where `from_frame` is `None`.
///
/// [`FastSphericalRectangle::from_frame`]: super::FastSphericalRectangle::from_frame
/// [`FastSphericalRectangle::sample`]: super::FastSphericalRectangle::sample
#[inline]
pub fn sample_lanes(lane: &[RectangleLane; LANES]) -> [Option<(Vec3, f32)>; LANES] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2, checked just above.
        return unsafe { sample_lanes_avx2(lane) };
    }
    sample_lanes_baseline(lane)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn sample_lanes_avx2(lane: &[RectangleLane; LANES]) -> [Option<(Vec3, f32)>; LANES] {
    kernel(lane)
}

fn sample_lanes_baseline(lane: &[RectangleLane; LANES]) -> [Option<(Vec3, f32)>; LANES] {
    kernel(lane)
}

/// The scalar version's steps (its `Local::from_frame`, `solid_angle`, `from_frame`
/// and `sample`), each over all lanes.
#[inline(always)]
fn kernel(lane: &[RectangleLane; LANES]) -> [Option<(Vec3, f32)>; LANES] {
    let fx = v3(|l| lane[l].frame.x.to_array());
    let fy = v3(|l| lane[l].frame.y.to_array());
    let fz = v3(|l| lane[l].frame.z.to_array());
    // The rectangle's frame seen from p (Local::from_frame).
    let d = v3(|l| (lane[l].corner.as_dvec3() - lane[l].p.as_dvec3()).to_array());
    let z_signed = dot(&d, &fz);
    let flip = z_signed.gt(F::splat(0.0));
    let z0 = F::select(flip, -z_signed, z_signed);
    let x0 = dot(&d, &fx);
    let y0 = dot(&d, &fy);
    let x1 = x0 + F::from_fn(|l| lane[l].frame.w);
    let y1 = y0 + F::from_fn(|l| lane[l].frame.h);
    let z2 = z0 * z0;
    let len = |a: F, b: F| (a * a + b * b + z2).sqrt();
    let (l00, l10, l11, l01) = (len(x0, y0), len(x1, y0), len(x1, y1), len(x0, y1));
    // The solid angle: two Van Oosterom–Strackee triangles.
    let dot2 = |xa: F, ya: F, xb: F, yb: F| xa * xb + ya * yb + z2;
    let d00_10 = dot2(x0, y0, x1, y0);
    let d00_11 = dot2(x0, y0, x1, y1);
    let d10_11 = dot2(x1, y0, x1, y1);
    let d00_01 = dot2(x0, y0, x0, y1);
    let d11_01 = dot2(x1, y1, x0, y1);
    let triple = -z0 * (x1 - x0) * (y1 - y0);
    let den_a = l00 * l10 * l11 + d00_10 * l11 + d00_11 * l10 + d10_11 * l00;
    let den_b = l00 * l11 * l01 + d00_11 * l01 + d00_01 * l11 + d11_01 * l00;
    let s = 2.0 * (half_angles(triple, den_a) + half_angles(triple, den_b));
    // k = 2π − γ₂ − γ₃ by its sine and cosine (from_frame).
    let ry0 = (z2 + y0 * y0).sqrt();
    let ry1 = (z2 + y1 * y1).sqrt();
    let (c2, s2) = (x0 * y1, -z0 * l01);
    let (c3, s3) = (-(x0 * y0), -z0 * l00);
    let scale = 1.0 / ((z2 + x0 * x0) * ry0 * ry1);
    let cos_k = (c2 * c3 - s2 * s3) * scale;
    let sin_k = -(s2 * c3 + c2 * s3) * scale;
    let b0 = -y0 / ry0;
    let b1 = y1 / ry1;
    let c = z2 / (ry0 * ry0);
    // The sample (sample): sin and cos of a_u = k + u₀S by angle addition.
    let mut su = F::splat(0.0);
    let mut cu = F::splat(0.0);
    for (l, job) in lane.iter().enumerate() {
        let (a, b) = ((job.u.x as f64 * s.0[l]) as f32).sin_cos();
        (su.0[l], cu.0[l]) = (a as f64, b as f64);
    }
    let one_minus_cu = F::select(cu.gt(F::splat(0.0)), su * su / (1.0 + cu), 1.0 - cu);
    let sa = sin_k - sin_k * one_minus_cu + cos_k * su;
    let cos_au = cos_k - cos_k * one_minus_cu - sin_k * su;
    let n = cos_au * b0 - b1;
    let den = (n * n - c * sa * sa).max(1e-300).sqrt();
    let xu = clamp((-z0 * sa / den).copysign(-z0 * sa * n), x0, x1);
    let d2 = xu * xu + z0 * z0;
    let h0 = y0 / (d2 + y0 * y0).sqrt();
    let h1 = y1 / (d2 + y1 * y1).sqrt();
    let hv = h0 + F::from_fn(|l| lane[l].u.y as f64) * (h1 - h0);
    let hv2 = hv * hv;
    let inside = clamp(hv * d2.sqrt() / (1.0 - hv2).sqrt(), y0, y1);
    let edge = F::select(hv.gt(F::splat(0.0)), y1, y0);
    let yv = F::select(hv2.lt(F::splat(1.0 - 1e-12)), inside, edge);
    // from_frame's and solid_angle's `None`s, as one test.
    let finite = x0.is_finite() & x1.is_finite() & y0.is_finite() & y1.is_finite();
    let valid = z0.lt(F::splat(0.0))
        & finite
        & z0.is_finite()
        & s.ge(F::splat(MIN_SOLID_ANGLE))
        & s.is_finite()
        & cos_k.is_finite()
        & sin_k.is_finite();
    let offset = |i: usize| xu * fx[i] + yv * fy[i] + z0 * F::select(flip, -fz[i], fz[i]);
    let (ox, oy, oz) = (offset(0), offset(1), offset(2));
    std::array::from_fn(|l| {
        let o = Vec3::new(ox.0[l] as f32, oy.0[l] as f32, oz.0[l] as f32);
        valid.get(l).then(|| (o, 1.0 / s.0[l] as f32))
    })
}

/// `v.clamp(lo, hi)` as selects: the same value wherever `clamp` is defined, and no
/// panic on lanes whose bounds are NaN (lanes the validity test drops, where the scalar
/// version returns before it clamps).
#[inline(always)]
fn clamp(v: F, lo: F, hi: F) -> F {
    let v = F::select(v.lt(lo), lo, v);
    F::select(v.gt(hi), hi, v)
}

/// The scalar version's `half_angle` on every lane, its branches as selects.
#[inline(always)]
fn half_angles(t: F, d: F) -> F {
    use std::f64::consts::{FRAC_PI_2, PI};
    let x = t / d;
    let x2 = x * x;
    let series = x * (1.0 - x2 * (1.0 / 3.0 - x2 * (0.2 - x2 * (1.0 / 7.0 - x2 / 9.0))));
    let ad = d.abs();
    let steep = t.gt(ad);
    // The smaller over the larger: the scalar version's quotient, one division.
    let ratio = F::select(steep, ad, t) / F::select(steep, t, ad);
    let mut a = [0.0f32; LANES];
    for (l, a) in a.iter_mut().enumerate() {
        *a = atan_unit(ratio.0[l] as f32);
    }
    let a = F::from_fn(|l| a[l] as f64);
    let r = F::select(steep, FRAC_PI_2 - a, a);
    let r = F::select(d.lt(F::splat(0.0)), PI - r, r);
    F::select(d.gt(20.0 * t), series, r)
}

#[cfg(test)]
mod tests {
    use super::super::FastSphericalRectangle;
    use super::*;
    use crate::sampling::{Rng32, Uniform};

    /// Every lane gives the scalar version's point and density bit for bit, and its
    /// `None`s, on near, far, grazing, in-plane and behind placements, through both the
    /// dispatched and the baseline kernel, with a different rectangle in every lane.
    #[test]
    fn every_lane_is_the_scalar_sample_bit_for_bit() {
        let mut rng = Rng32::new(11);
        let mut next = || rng.next_1d();
        let rects: Vec<(RectangleFrame, Vec3, Vec3, Vec3)> = (0..8)
            .map(|i| {
                let a = i as f32 * 0.7;
                let ex = Vec3::new(a.cos(), 0.0, a.sin()) * (0.05 + i as f32 * 0.4);
                let ey = Vec3::new(-a.sin() * 0.3, 0.9, a.cos() * 0.3).normalize()
                    * (0.1 + i as f32 * 0.2);
                let ey = ey - ex * (ex.dot(ey) / ex.length_squared());
                let corner = Vec3::new(i as f32 - 4.0, 2.0, -1.0);
                (
                    RectangleFrame::new(ex, ey).expect("perpendicular"),
                    corner,
                    ex,
                    ey,
                )
            })
            .collect();
        let (mut some, mut none) = (0, 0);
        for i in 0..20_000 {
            let lane: [RectangleLane; LANES] = std::array::from_fn(|l| {
                let (frame, corner, ex, ey) = &rects[(i + 3 * l) % rects.len()];
                let scale = [1e-3f32, 0.1, 1.0, 30.0, 1e4][(i / 7 + l) % 5];
                let mut p = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 6.0 * scale;
                if i % 11 == 0 {
                    // In the rectangle's plane, or a hair above it.
                    p = *corner + *ex * next() * 2.0 + *ey * (next() - 0.5) * 2.0;
                    p += ex.cross(*ey).normalize() * [0.0, 1e-6, 1e-3][l % 3];
                }
                if i % 97 == 0 && l == 1 {
                    // Not a point: None, as the scalar version, and no panic.
                    let bad = [
                        Vec3::NAN,
                        Vec3::INFINITY,
                        Vec3::new(0.0, f32::INFINITY, 1.0),
                    ];
                    p = bad[(i / 97) % 3];
                }
                RectangleLane {
                    frame,
                    corner: *corner,
                    p,
                    u: Vec2::new(next(), next()),
                }
            });
            let wide = sample_lanes(&lane);
            let baseline = sample_lanes_baseline(&lane);
            for (l, got) in wide.into_iter().enumerate() {
                let RectangleLane {
                    frame,
                    corner,
                    p,
                    u,
                } = lane[l];
                let scalar = FastSphericalRectangle::from_frame(frame, p, corner)
                    .map(|r| r.sample(u))
                    .map(|(_, offset, pdf)| (offset, pdf));
                let bits = |s: Option<(Vec3, f32)>| {
                    s.map(|(o, p)| (o.to_array().map(f32::to_bits), p.to_bits()))
                };
                assert_eq!(bits(got), bits(scalar), "lane {l} at {p}");
                assert_eq!(bits(baseline[l]), bits(scalar), "baseline lane {l} at {p}");
                if got.is_some() {
                    some += 1;
                } else {
                    none += 1;
                }
            }
        }
        // Both outcomes are exercised.
        assert!(some > 50_000 && none > 1_000, "{some} samples, {none} None");
    }
}
