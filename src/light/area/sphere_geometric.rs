//! The sphere's `geometric` strategy (lecture p₄ ∝ cos θx·cos θy/d²). Since
//! dω = cos θy·dA/d², a density ∝ cos θx·cos θy/d² per unit area is a density ∝ cos θx
//! per steradian over the cone the sphere subtends: projected-solid-angle sampling of
//! the cone, clipped at the horizon of the shading point.
//!
//! In the cone's frame (axis a towards the centre, e₁ towards the normal n), a direction
//! at (θ, φ) has cos θx = w·n = A + B·cos φ with A = cos θ·cos β, B = sin θ·sin β
//! (cos β = a·n). With s = 1 − cos θ, dω = ds·dφ and the density factors as
//! p(s)·p(φ | s):
//! - the marginal m(s) = Z(s) = ∫ max(0, A + B cos φ) dφ is tabulated at [`BINS`] + 1
//!   points and sampled as a piecewise-linear density (exact when the cone lies above the
//!   horizon, where Z = 2π·cos θ·cos β is linear in s);
//! - the conditional ∝ max(0, A + B cos φ) has the CDF A(φ + φm) + B(sin φ + sin φm) on
//!   [−φm, φm], inverted numerically (Newton's method safeguarded by bisection).

use std::f64::consts::PI;

use glam::{DVec3, Vec2, Vec3};

/// Points of the tabulated marginal are `BINS + 1`.
pub const BINS: usize = 32;

/// A cone of directions seen from a shading point with normal `n`, ready for sampling
/// ∝ max(0, w·n).
#[derive(Clone, Debug)]
pub struct ProjectedCone {
    a: DVec3,
    e1: DVec3,
    e2: DVec3,
    n: DVec3,
    cos_beta: f64,
    sin_beta: f64,
    /// s_max = 1 − cos θmax.
    s_max: f64,
    /// Z(s) at s = i·s_max/BINS.
    z: [f64; BINS + 1],
    /// ∫ Z ds over [0, s_max] (trapezoids).
    total: f64,
}

/// Z(A, B) = ∫_{−π}^{π} max(0, A + B cos φ) dφ for B ≥ 0, and the half-width φm of its
/// support.
fn clipped_integral(a: f64, b: f64) -> (f64, f64) {
    if a >= b {
        (2.0 * PI * a, PI)
    } else if a <= -b {
        (0.0, 0.0)
    } else {
        let phi_m = (-a / b).clamp(-1.0, 1.0).acos();
        (2.0 * (a * phi_m + b * phi_m.sin()), phi_m)
    }
}

impl ProjectedCone {
    /// The cone around the unit `axis` with 1 − cos θmax = `s_max`, seen from a point
    /// with unit normal `n`; `None` when the whole cone is below the horizon.
    pub fn new(axis: Vec3, n: Vec3, s_max: f64) -> Option<ProjectedCone> {
        let (a, n) = (axis.as_dvec3(), n.as_dvec3());
        let cos_beta = a.dot(n).clamp(-1.0, 1.0);
        let perp = n - cos_beta * a;
        let sin_beta = perp.length();
        let e1 = if sin_beta > 1e-9 {
            perp / sin_beta
        } else {
            a.any_orthonormal_vector()
        };
        let e2 = a.cross(e1);
        let mut cone = ProjectedCone {
            a,
            e1,
            e2,
            n,
            cos_beta,
            sin_beta,
            s_max,
            z: [0.0; BINS + 1],
            total: 0.0,
        };
        // Above the horizon (A ≥ B at the rim, hence everywhere) Z = 2πA needs no acos.
        let (a_rim, b_rim) = cone.coefficients(s_max);
        let above = a_rim >= b_rim;
        for i in 0..=BINS {
            let s = i as f64 * s_max / BINS as f64;
            cone.z[i] = if above {
                2.0 * PI * cone.coefficients(s).0
            } else {
                cone.marginal(s).0
            };
        }
        let ds = s_max / BINS as f64;
        cone.total = (0..BINS)
            .map(|i| 0.5 * (cone.z[i] + cone.z[i + 1]) * ds)
            .sum();
        (cone.total > 0.0 && cone.total.is_finite()).then_some(cone)
    }

    /// (A, B) at s, then Z(s) and φm.
    fn coefficients(&self, s: f64) -> (f64, f64) {
        let cos_theta = 1.0 - s;
        let sin_theta = (s * (2.0 - s)).max(0.0).sqrt();
        (cos_theta * self.cos_beta, sin_theta * self.sin_beta)
    }

    fn marginal(&self, s: f64) -> (f64, f64) {
        let (a, b) = self.coefficients(s);
        clipped_integral(a, b)
    }

    /// The piecewise-linear marginal density of s (per unit s).
    fn marginal_pdf(&self, s: f64) -> f64 {
        let x = (s / self.s_max * BINS as f64).clamp(0.0, BINS as f64);
        let i = (x as usize).min(BINS - 1);
        let t = x - i as f64;
        ((1.0 - t) * self.z[i] + t * self.z[i + 1]) / self.total
    }

    /// A direction ∝ max(0, w·n) in the cone, and its density per steradian; `None` in
    /// the rare case the sampled s has no direction above the horizon.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let s = self.sample_s(u.x as f64);
        let (a, b) = self.coefficients(s);
        let (z, phi_m) = clipped_integral(a, b);
        if z.is_nan() || z <= 0.0 {
            return None;
        }
        let phi = invert_conditional(a, b, phi_m, u.y as f64 * z);
        let cos_theta = 1.0 - s;
        let sin_theta = (s * (2.0 - s)).max(0.0).sqrt();
        let w = cos_theta * self.a + sin_theta * (phi.cos() * self.e1 + phi.sin() * self.e2);
        let w = w.normalize().as_vec3();
        let pdf = self.pdf(w);
        (pdf > 0.0).then_some((w, pdf))
    }

    /// s from the piecewise-linear marginal: a bin by its trapezoid mass, then the root of
    /// the quadratic CDF inside it (in the stable form 2c/(z₀ + √(z₀² + 2Δc))).
    fn sample_s(&self, u: f64) -> f64 {
        let ds = self.s_max / BINS as f64;
        let mut target = u * self.total;
        for i in 0..BINS {
            let (z0, z1) = (self.z[i], self.z[i + 1]);
            let mass = 0.5 * (z0 + z1) * ds;
            if target < mass || i == BINS - 1 {
                // In units of t ∈ [0, 1]: ∫₀ᵗ z0 + (z1 − z0)τ dτ = c.
                let c = (target / ds).clamp(0.0, 0.5 * (z0 + z1));
                let delta = z1 - z0;
                let root = (z0 * z0 + 2.0 * delta * c).max(0.0).sqrt();
                let t = if z0 + root > 0.0 {
                    2.0 * c / (z0 + root)
                } else {
                    0.5
                };
                return (i as f64 + t.clamp(0.0, 1.0)) * ds;
            }
            target -= mass;
        }
        self.s_max
    }

    /// Density per steradian of [`ProjectedCone::sample`]: p(s)·max(0, w·n)/Z(s) for w in
    /// the cone (up to rounding), else 0.
    pub fn pdf(&self, w: Vec3) -> f32 {
        let w = w.as_dvec3();
        // s = 1 − w·a = |w − a|²/2 for unit vectors, exact near the axis.
        let s = 0.5 * (w - self.a).length_squared();
        if s > self.s_max * (1.0 + 1e-3) + 1e-7 {
            return 0.0;
        }
        let s = s.min(self.s_max);
        let (z, _) = self.marginal(s);
        let cos_x = w.dot(self.n);
        if !(z > 0.0 && cos_x > 0.0) {
            return 0.0;
        }
        (self.marginal_pdf(s) * cos_x / z) as f32
    }
}

/// The φ ∈ [−φm, φm] with A(φ + φm) + B(sin φ + sin φm) = c (the CDF of
/// max(0, A + B cos φ), increasing): Newton steps kept inside a shrinking bracket.
fn invert_conditional(a: f64, b: f64, phi_m: f64, c: f64) -> f64 {
    let cdf = |phi: f64| a * (phi + phi_m) + b * (phi.sin() + phi_m.sin()) - c;
    let (mut lo, mut hi) = (-phi_m, phi_m);
    let mut phi = -phi_m + 2.0 * phi_m * (c / (2.0 * (a * phi_m + b * phi_m.sin())).max(1e-300));
    phi = phi.clamp(lo, hi);
    for _ in 0..40 {
        let f = cdf(phi);
        if f.abs() < 1e-12 * c.max(1e-12) {
            break;
        }
        if f > 0.0 {
            hi = phi;
        } else {
            lo = phi;
        }
        let slope = a + b * phi.cos();
        let next = phi - f / slope;
        phi = if slope > 0.0 && next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo < 1e-12 {
            break;
        }
    }
    phi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conditional_inverse_hits_its_target() {
        for (a, b) in [(0.5, 0.2), (0.1, 0.4), (-0.1, 0.4), (1.0, 0.0)] {
            let (z, phi_m) = clipped_integral(a, b);
            for u in [0.0, 0.1, 0.5, 0.9, 1.0] {
                let phi = invert_conditional(a, b, phi_m, u * z);
                let f = a * (phi + phi_m) + b * (phi.sin() + phi_m.sin());
                assert!((f - u * z).abs() < 1e-9, "{a} {b} {u}: {f} vs {}", u * z);
            }
        }
    }

    #[test]
    fn cone_above_the_horizon_is_exactly_cosine_weighted() {
        // The cone of half-angle 30° around a 45°-tilted axis stays above the horizon.
        let axis = Vec3::new(1.0, 0.0, 1.0).normalize();
        let s_max = 1.0 - (30f64).to_radians().cos();
        let cone = ProjectedCone::new(axis, Vec3::Z, s_max).expect("visible");
        // Projected solid angle of a cap: π·sin²θmax·cos β.
        let expected = PI * (30f64).to_radians().sin().powi(2) * (0.5f64).sqrt();
        // (the axis is f32, so cos β carries ~10⁻⁸ relative error)
        assert!((cone.total - expected).abs() < 1e-6 * expected);
        for u in [Vec2::new(0.2, 0.3), Vec2::new(0.9, 0.7), Vec2::ZERO] {
            let (w, pdf) = cone.sample(u).expect("sample");
            assert!((pdf as f64 - w.z as f64 / expected).abs() < 1e-4 * pdf as f64);
        }
        assert!(ProjectedCone::new(-Vec3::Z, Vec3::Z, 0.01).is_none());
    }
}
