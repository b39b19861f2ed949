//! The `solid-angle` sample of a sphere light ([`super::sphere`]: uniform in the cone the
//! sphere subtends, pbrt-v4 §6.2.4) for [`LANES`] shading points at once: the same
//! operations in the same order on each lane, so each lane's point, normal and density
//! are the scalar version's bit for bit (a test checks it; Rust never fuses a multiply
//! and an add, so the wide instructions round as the scalar ones do).
//!
//! Why: one sample is a chain of dependent square roots and divisions (the view of the
//! sphere, the cone's 1 − cos θmax, the frame around its axis, the hit on the sphere,
//! the normal), and a core spends most of it waiting on that chain: `Light::sample`
//! took 17.6 % of `gaussian_stratified`'s time for 10.9 % of its instructions
//! (BENCHMARKS.md session 37). Eight independent chains in one AVX2 register per step
//! keep the divider busy instead.
//!
//! Dispatch at run time: AVX2 where the processor has it (`is_x86_feature_detected!`),
//! else the same code for the target's baseline (SSE2 on x86-64, NEON on aarch64). The
//! `sin_cos` of 2πu₁ stays a per-lane call into the C library, as in the scalar
//! version, so the bits agree.

use glam::{Vec2, Vec3};

use super::LightPoint;
use super::sphere::CAP_SLACK;
use crate::geometry::shape::Sphere;
use crate::math::PI;
use crate::math::f32x8::{F32x8, V3, dot3 as dot, v3};
use crate::sampling::sampler::ONE_MINUS_EPSILON;
use crate::sampling::warp::LANES;

type F = F32x8;

/// One lane's sphere, shading point and two numbers.
#[derive(Clone, Copy, Debug)]
pub struct SphereLane {
    /// The sphere light's shape.
    pub sphere: Sphere,
    /// The shading point.
    pub p: Vec3,
    /// The sample's two uniform numbers.
    pub u: Vec2,
}

/// For each lane, what [`super::sphere::sample`] gives under `solid-angle` from outside
/// the sphere, or `None` from inside or on it (where the scalar version samples the
/// area instead).
#[inline]
pub fn sample_lanes(lane: &[SphereLane; LANES]) -> [Option<LightPoint>; LANES] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2, checked just above.
        return unsafe { sample_lanes_avx2(lane) };
    }
    kernel(lane)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn sample_lanes_avx2(lane: &[SphereLane; LANES]) -> [Option<LightPoint>; LANES] {
    kernel(lane)
}

/// `a − b`, coordinate by coordinate.
#[inline(always)]
fn sub(a: &V3, b: &V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a + t·w`, coordinate by coordinate (glam's `a + t * w`).
#[inline(always)]
fn along(a: &V3, t: F, w: &V3) -> V3 {
    [a[0] + t * w[0], a[1] + t * w[1], a[2] + t * w[2]]
}

/// The scalar version's steps (`View::new`, `View::one_minus_cos_max`,
/// `square_to_uniform_cone`, `Frame::from_normal`, `Frame::to_world`, `cone_hit`, then
/// the density `pdf` gives the point), each over all lanes.
#[inline(always)]
fn kernel(lane: &[SphereLane; LANES]) -> [Option<LightPoint>; LANES] {
    let c = v3(|l| lane[l].sphere.center.to_array());
    let r = F::from_fn(|l| lane[l].sphere.radius);
    let p = v3(|l| lane[l].p.to_array());
    // The view from p: the cap's axis b and r/D = sin θmax (View::new).
    let d = sub(&p, &c);
    let distance = dot(&d, &d).sqrt();
    let ratio = r / distance;
    let outside = ratio.lt(F::splat(1.0 - 1e-5)) & ratio.is_finite();
    let b = [d[0] / distance, d[1] / distance, d[2] / distance];
    // 1 − cos θmax = (r/D)²/(1 + cos θmax) (View::one_minus_cos_max).
    let sin2 = ratio * ratio;
    let cos_max = 1.0 - sin2 / (1.0 + (1.0 - sin2).sqrt());
    // The direction in the cone around +z (square_to_uniform_cone).
    let one_minus_cos = 1.0 - cos_max.clamp(-1.0, ONE_MINUS_EPSILON);
    let one_minus_z = F::from_fn(|l| lane[l].u.x) * one_minus_cos;
    let z = 1.0 - one_minus_z;
    let sin_theta = (one_minus_z * (2.0 - one_minus_z)).max(0.0).sqrt();
    let (mut sin_phi, mut cos_phi) = (F::splat(0.0), F::splat(0.0));
    for (l, job) in lane.iter().enumerate() {
        (sin_phi.0[l], cos_phi.0[l]) = (2.0 * PI * job.u.y).sin_cos();
    }
    let local = [sin_theta * cos_phi, sin_theta * sin_phi, z];
    // The frame around −b (Frame::from_normal, Duff et al. 2017) and the world
    // direction (Frame::to_world).
    let n = [-b[0], -b[1], -b[2]];
    let sign = F::splat(1.0).copysign(n[2]);
    let a = -1.0 / (sign + n[2]);
    let bn = n[0] * n[1] * a;
    let s = [1.0 + sign * n[0] * n[0] * a, sign * bn, -sign * n[0]];
    let t = [bn, sign + n[1] * n[1] * a, -n[1]];
    let w: V3 = std::array::from_fn(|k| s[k] * local[0] + t[k] * local[1] + n[k] * local[2]);
    // The first hit of p + t·w on the sphere, clamped to the tangent point (cone_hit).
    let to_center = sub(&c, &p);
    let along_w = dot(&w, &to_center);
    let perp = [
        to_center[0] - along_w * w[0],
        to_center[1] - along_w * w[1],
        to_center[2] - along_w * w[2],
    ];
    let t_hit = along_w - (r * r - dot(&perp, &perp)).max(0.0).sqrt();
    let y = along(&p, t_hit, &w);
    let q = sub(&y, &c);
    let q = [q[0] / r, q[1] / r, q[2] / r];
    // glam's normalize_or_zero: q times 1/|q| when that is finite and positive.
    let rcp = 1.0 / dot(&q, &q).sqrt();
    let unit = rcp.is_finite() & rcp.gt(F::splat(0.0));
    let ny = [q[0] * rcp, q[1] * rcp, q[2] * rcp].map(|x| F::select(unit, x, F::splat(0.0)));
    let point: V3 = std::array::from_fn(|k| c[k] + r * ny[k]);
    // The density `pdf` gives the point: the cone's 1/(2π(1 − cos θmax)) on the visible
    // cap (View::sees), as uniform_cone_pdf computes it along +z.
    let sees = dot(&ny, &b).ge(ratio - CAP_SLACK);
    let in_cone = F::splat(1.0).ge(1.0 - one_minus_cos);
    let cone_pdf = F::select(in_cone, 1.0 / (2.0 * PI * one_minus_cos), F::splat(0.0));
    let pdf = F::select(sees, cone_pdf, F::splat(0.0));
    std::array::from_fn(|l| {
        outside.get(l).then(|| LightPoint {
            y: Vec3::new(point[0].0[l], point[1].0[l], point[2].0[l]),
            ny: Vec3::new(ny[0].0[l], ny[1].0[l], ny[2].0[l]),
            pdf: pdf.0[l],
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::ShadingPoint;
    use crate::light::area::LightSampling;
    use crate::math::Frame;
    use crate::sampling::{Rng32, Uniform};

    /// Every lane gives the scalar `solid-angle` sample's point, normal and density bit
    /// for bit, and `None` exactly where the shading point is inside or on the sphere
    /// (where the scalar version samples the area), through both the dispatched and the
    /// baseline kernel, with a different sphere in every lane: far and near (0.5 to 20
    /// radii from the centre), inside (lane 7), within a few units in the last place of
    /// the view's threshold r/D = 1 − 10⁻⁵ on either side (lane 6), and sampled at the
    /// cone's rim, u₀ = 1 − ε/2, where the hit is clamped to the silhouette (lane 5).
    #[test]
    fn every_lane_is_the_scalar_sample_bit_for_bit() {
        let mut rng = Rng32::new(5);
        // Lanes outside and inside as the view decides, and lane 6 on each side.
        let (mut outside, mut inside, mut near_out, mut near_in) = (0, 0, 0, 0);
        for _ in 0..2000 {
            let mut next = || rng.next_1d();
            let lane: [SphereLane; LANES] = std::array::from_fn(|l| {
                let center = Vec3::new(next(), next(), next()) * 4.0 - 2.0;
                let radius = 0.01 + next() * next();
                // From 0.5 to 20 radii away from the centre, every eighth lane inside.
                let dir = (Vec3::new(next(), next(), next()) - 0.5).normalize_or(Vec3::Z);
                let distance = match l {
                    7 => radius * next(),
                    6 => {
                        let threshold = radius / (1.0 - 1e-5);
                        let ulps = (next() * 9.0) as u32;
                        f32::from_bits(threshold.to_bits() + ulps - 4)
                    }
                    _ => radius * (0.5 + 19.5 * next()),
                };
                let sphere = Sphere {
                    center,
                    radius,
                    axes: Frame::from_normal(Vec3::Z),
                };
                let p = center + dir * distance;
                let u0 = if l == 5 { ONE_MINUS_EPSILON } else { next() };
                SphereLane {
                    sphere,
                    p,
                    u: Vec2::new(u0, next()),
                }
            });
            let bits = |x: &Option<LightPoint>| {
                x.map(|x| {
                    (
                        x.y.to_array().map(f32::to_bits),
                        x.ny.to_array().map(f32::to_bits),
                        x.pdf.to_bits(),
                    )
                })
            };
            let (wide, baseline) = (sample_lanes(&lane), kernel(&lane));
            for (l, job) in lane.iter().enumerate() {
                let at = ShadingPoint {
                    p: job.p,
                    ng: Vec3::Y,
                    n: Vec3::Y,
                };
                let s = &job.sphere;
                let scalar = super::super::sphere::sample(s, LightSampling::SolidAngle, &at, job.u);
                // Outside as the scalar version's view decides it.
                let ratio = s.radius / (job.p - s.center).length();
                let seen = ratio < 1.0 - 1e-5 && ratio.is_finite();
                let expected = if seen {
                    outside += 1;
                    bits(&scalar)
                } else {
                    inside += 1;
                    None
                };
                if l == 6 {
                    (near_out, near_in) = (near_out + seen as u32, near_in + !seen as u32);
                }
                assert_eq!(bits(&wide[l]), expected, "lane {l}: {job:?}");
                assert_eq!(bits(&baseline[l]), bits(&wide[l]), "lane {l}");
            }
        }
        assert!(outside > 10_000 && inside > 1000, "{outside} / {inside}");
        assert!(near_out > 300 && near_in > 300, "{near_out} / {near_in}");
    }
}
