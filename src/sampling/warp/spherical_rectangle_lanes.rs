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
//! scalar code takes.
//!
//! Dispatch at run time: AVX2 where the processor has it (`is_x86_feature_detected!`),
//! else the same code for the target's baseline (SSE2 on x86-64, NEON on aarch64). The
//! f32 `sin_cos` of u₀·S stays a per-lane call into the C library, as in the scalar
//! version, so the bits agree.

use glam::{DVec3, Vec2, Vec3};

use super::spherical_rectangle_fast::RectangleFrame;
use super::spherical_triangle::MIN_SOLID_ANGLE;
use crate::math::atan::atan_unit;

/// Shading points per call: eight chains hide each other's latency better than four
/// (43 → 34 ns a sample), and a staged chunk holds 64 samples.
pub const LANES: usize = 8;

type F = [f64; LANES];

#[inline(always)]
fn lanes(f: impl Fn(usize) -> f64) -> F {
    std::array::from_fn(f)
}

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
    let f = |l: usize| lane[l].frame;
    // The rectangle's frame seen from p (Local::from_frame).
    let d: [DVec3; LANES] =
        std::array::from_fn(|l| lane[l].corner.as_dvec3() - lane[l].p.as_dvec3());
    let z_signed = lanes(|l| d[l].dot(f(l).z));
    let flip: [bool; LANES] = std::array::from_fn(|l| z_signed[l] > 0.0);
    let z0 = lanes(|l| if flip[l] { -z_signed[l] } else { z_signed[l] });
    let x0 = lanes(|l| d[l].dot(f(l).x));
    let y0 = lanes(|l| d[l].dot(f(l).y));
    let x1 = lanes(|l| x0[l] + f(l).w);
    let y1 = lanes(|l| y0[l] + f(l).h);
    let z2 = lanes(|l| z0[l] * z0[l]);
    let len = |a: &F, b: &F| lanes(|l| (a[l] * a[l] + b[l] * b[l] + z2[l]).sqrt());
    let (l00, l10, l11, l01) = (len(&x0, &y0), len(&x1, &y0), len(&x1, &y1), len(&x0, &y1));
    // The solid angle: two Van Oosterom–Strackee triangles.
    let dot = |xa: &F, ya: &F, xb: &F, yb: &F| lanes(|l| xa[l] * xb[l] + ya[l] * yb[l] + z2[l]);
    let d00_10 = dot(&x0, &y0, &x1, &y0);
    let d00_11 = dot(&x0, &y0, &x1, &y1);
    let d10_11 = dot(&x1, &y0, &x1, &y1);
    let d00_01 = dot(&x0, &y0, &x0, &y1);
    let d11_01 = dot(&x1, &y1, &x0, &y1);
    let triple = lanes(|l| -z0[l] * (x1[l] - x0[l]) * (y1[l] - y0[l]));
    let den_a = lanes(|l| {
        l00[l] * l10[l] * l11[l] + d00_10[l] * l11[l] + d00_11[l] * l10[l] + d10_11[l] * l00[l]
    });
    let den_b = lanes(|l| {
        l00[l] * l11[l] * l01[l] + d00_11[l] * l01[l] + d00_01[l] * l11[l] + d11_01[l] * l00[l]
    });
    let (half_a, half_b) = (half_angles(&triple, &den_a), half_angles(&triple, &den_b));
    let s = lanes(|l| 2.0 * (half_a[l] + half_b[l]));
    // k = 2π − γ₂ − γ₃ by its sine and cosine (from_frame).
    let ry0 = lanes(|l| (z2[l] + y0[l] * y0[l]).sqrt());
    let ry1 = lanes(|l| (z2[l] + y1[l] * y1[l]).sqrt());
    let (c2, s2) = (lanes(|l| x0[l] * y1[l]), lanes(|l| -z0[l] * l01[l]));
    let (c3, s3) = (lanes(|l| -(x0[l] * y0[l])), lanes(|l| -z0[l] * l00[l]));
    let scale = lanes(|l| 1.0 / ((z2[l] + x0[l] * x0[l]) * ry0[l] * ry1[l]));
    let cos_k = lanes(|l| (c2[l] * c3[l] - s2[l] * s3[l]) * scale[l]);
    let sin_k = lanes(|l| -(s2[l] * c3[l] + c2[l] * s3[l]) * scale[l]);
    let b0 = lanes(|l| -y0[l] / ry0[l]);
    let b1 = lanes(|l| y1[l] / ry1[l]);
    let c = lanes(|l| z2[l] / (ry0[l] * ry0[l]));
    // The sample (sample): sin and cos of a_u = k + u₀S by angle addition.
    let mut su = [0.0; LANES];
    let mut cu = [0.0; LANES];
    for l in 0..LANES {
        let (a, b) = ((lane[l].u.x as f64 * s[l]) as f32).sin_cos();
        (su[l], cu[l]) = (a as f64, b as f64);
    }
    let one_minus_cu = lanes(|l| {
        if cu[l] > 0.0 {
            su[l] * su[l] / (1.0 + cu[l])
        } else {
            1.0 - cu[l]
        }
    });
    let sa = lanes(|l| sin_k[l] - sin_k[l] * one_minus_cu[l] + cos_k[l] * su[l]);
    let cos_au = lanes(|l| cos_k[l] - cos_k[l] * one_minus_cu[l] - sin_k[l] * su[l]);
    let n = lanes(|l| cos_au[l] * b0[l] - b1[l]);
    let den = lanes(|l| (n[l] * n[l] - c[l] * sa[l] * sa[l]).max(1e-300).sqrt());
    let xu = lanes(|l| {
        clamp(
            (-z0[l] * sa[l] / den[l]).copysign(-z0[l] * sa[l] * n[l]),
            x0[l],
            x1[l],
        )
    });
    let d2 = lanes(|l| xu[l] * xu[l] + z0[l] * z0[l]);
    let h0 = lanes(|l| y0[l] / (d2[l] + y0[l] * y0[l]).sqrt());
    let h1 = lanes(|l| y1[l] / (d2[l] + y1[l] * y1[l]).sqrt());
    let hv = lanes(|l| h0[l] + lane[l].u.y as f64 * (h1[l] - h0[l]));
    let hv2 = lanes(|l| hv[l] * hv[l]);
    let inside = lanes(|l| clamp(hv[l] * d2[l].sqrt() / (1.0 - hv2[l]).sqrt(), y0[l], y1[l]));
    let yv = lanes(|l| {
        if hv2[l] < 1.0 - 1e-12 {
            inside[l]
        } else if hv[l] > 0.0 {
            y1[l]
        } else {
            y0[l]
        }
    });
    std::array::from_fn(|l| {
        // from_frame's and solid_angle's `None`s, as one test.
        let finite = [x0[l], x1[l], y0[l], y1[l], z0[l]]
            .iter()
            .all(|v| v.is_finite());
        let valid = z0[l] < 0.0
            && finite
            && s[l] >= MIN_SOLID_ANGLE
            && s[l].is_finite()
            && cos_k[l].is_finite()
            && sin_k[l].is_finite();
        let z = if flip[l] { -f(l).z } else { f(l).z };
        let offset = xu[l] * f(l).x + yv[l] * f(l).y + z0[l] * z;
        valid.then(|| (offset.as_vec3(), 1.0 / s[l] as f32))
    })
}

/// `v.clamp(lo, hi)` as selects: the same value wherever `clamp` is defined, and no
/// panic on lanes whose bounds are NaN (lanes the validity test drops, where the scalar
/// version returns before it clamps).
#[inline(always)]
fn clamp(v: f64, lo: f64, hi: f64) -> f64 {
    let v = if v < lo { lo } else { v };
    if v > hi { hi } else { v }
}

/// The scalar version's `half_angle` on every lane, its branches as selects.
#[inline(always)]
fn half_angles(t: &F, d: &F) -> F {
    use std::f64::consts::{FRAC_PI_2, PI};
    let x = lanes(|l| t[l] / d[l]);
    let x2 = lanes(|l| x[l] * x[l]);
    let series = lanes(|l| {
        x[l] * (1.0 - x2[l] * (1.0 / 3.0 - x2[l] * (0.2 - x2[l] * (1.0 / 7.0 - x2[l] / 9.0))))
    });
    let ad = lanes(|l| d[l].abs());
    let steep: [bool; LANES] = std::array::from_fn(|l| t[l] > ad[l]);
    let ratio: [f32; LANES] =
        std::array::from_fn(|l| (if steep[l] { ad[l] / t[l] } else { t[l] / ad[l] }) as f32);
    let a: [f32; LANES] = std::array::from_fn(|l| atan_unit(ratio[l]));
    let r = lanes(|l| {
        if steep[l] {
            FRAC_PI_2 - a[l] as f64
        } else {
            a[l] as f64
        }
    });
    let r = lanes(|l| if d[l] < 0.0 { PI - r[l] } else { r[l] });
    lanes(|l| if d[l] > 20.0 * t[l] { series[l] } else { r[l] })
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
