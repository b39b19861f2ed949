//! Albedo tables of a rough dielectric coat over a diffuse base, as Mitsuba 3's
//! `roughplastic` precomputes them: the coat's directional transmittance T(cos θ) from
//! outside, and its hemispherically averaged internal reflectance. Both integrate over
//! microfacet normals with Gauss–Legendre quadrature on the sampling square, weighting
//! each normal by D_v(m)/p(m) (visible-normal density over sampling density), so the
//! same code serves GGX (weight 1) and Beckmann (D·cos sampling).

use glam::{DVec2, Vec2, Vec3};
use rayon::prelude::*;

use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, reflect};

/// Number of cos θ nodes of the transmittance table (Mitsuba's
/// `MI_ROUGH_TRANSMITTANCE_RES`).
pub const TABLE_SIZE: usize = 64;

/// The coat's precomputed albedos.
#[derive(Clone, Debug, PartialEq)]
pub struct CoatTables {
    /// T(μ) at μ = i/(TABLE_SIZE − 1): fraction of light from outside at cos θ = μ that
    /// crosses the coat into the base (after masking of the refracted ray).
    pub external_transmittance: Box<[f32; TABLE_SIZE]>,
    /// 2·mean over the same nodes of R_int(μ)·μ, the coat's internal reflectance averaged
    /// over a cosine-distributed hemisphere (Mitsuba's discrete form, kept for matching).
    pub internal_reflectance: f32,
}

impl CoatTables {
    /// Tables for a coat with distribution `mf` and relative index `eta` (inside/outside).
    pub fn new(mf: &Microfacet, eta: f32) -> CoatTables {
        let (nodes_t, weights_t) = gauss_legendre(32);
        let (nodes_r, weights_r) = gauss_legendre(128);
        // The 64 rows (1.1·10⁶ microfacet samples in all, most of a scene's load with a
        // rough plastic) run in parallel; the reflectances are summed in row order after,
        // so the tables are the same bits on any number of threads.
        let rows: Vec<(f32, f64)> = (0..TABLE_SIZE)
            .into_par_iter()
            .map(|i| {
                let mu = (i as f64 / (TABLE_SIZE - 1) as f64).max(1e-6);
                let w = Vec3::new((1.0 - mu * mu).sqrt() as f32, 0.0, mu as f32);
                let t = integrate_square(&nodes_t, &weights_t, |m| transmitted(mf, w, m, eta));
                let r = integrate_square(&nodes_r, &weights_r, |m| reflected(mf, w, m, 1.0 / eta));
                (t as f32, r * mu)
            })
            .collect();
        let mut external_transmittance = Box::new([0.0f32; TABLE_SIZE]);
        let mut internal = 0.0f64;
        for (t, &(row_t, row_r)) in external_transmittance.iter_mut().zip(&rows) {
            *t = row_t;
            internal += row_r;
        }
        CoatTables {
            external_transmittance,
            internal_reflectance: (2.0 * internal / TABLE_SIZE as f64) as f32,
        }
    }

    /// T(cos θ) by linear interpolation in the table.
    pub fn transmittance(&self, cos_theta: f32) -> f32 {
        let x = cos_theta.clamp(0.0, 1.0) * (TABLE_SIZE - 1) as f32;
        let i = (x as usize).min(TABLE_SIZE - 2);
        let (a, b) = (
            self.external_transmittance[i],
            self.external_transmittance[i + 1],
        );
        a + (b - a) * (x - i as f32)
    }
}

/// Σ w_i w_j g(sample(u_ij))·D_v(m)/p(m) over the square, nodes mapped from [−1, 1].
fn integrate_square(nodes: &[f64], weights: &[f64], g: impl Fn(Vec3) -> (f64, f64)) -> f64 {
    let mut sum = 0.0;
    for (x, wx) in nodes.iter().zip(weights) {
        for (y, wy) in nodes.iter().zip(weights) {
            let u = (DVec2::new(*x, *y) * 0.5 + 0.5).as_vec2();
            let (value, weight) = g(Vec3::new(u.x, u.y, 0.0));
            sum += value * weight * wx * wy * 0.25;
        }
    }
    sum
}

/// For the sample point `u` (in x, y): the normal m drawn from w, and the weight
/// D_v(m)/p(m) that turns the sampling density into the visible-normal density.
fn visible_normal(mf: &Microfacet, w: Vec3, u: Vec3) -> Option<(Vec3, f64)> {
    let (m, p) = mf.sample(w, Vec2::new(u.x, u.y));
    let visible = mf.g1(w, m) * w.dot(m).max(0.0) * mf.d(m) / w.z;
    (p > 0.0 && visible > 0.0).then(|| (m, (visible / p) as f64))
}

/// (1 − F)·G1 of the ray refracted into the coat, with its weight.
fn transmitted(mf: &Microfacet, w: Vec3, u: Vec3, eta: f32) -> (f64, f64) {
    let Some((m, weight)) = visible_normal(mf, w, u) else {
        return (0.0, 0.0);
    };
    let cos_i = w.dot(m);
    let fresnel = fresnel_dielectric(cos_i, eta);
    // Snell: cos θ_t = −√(1 − (1 − cos²θ_i)/η²), t = m(cos θ_i/η + cos θ_t) − w/η.
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return (0.0, weight);
    }
    let cos_t = -(1.0 - sin2_t).sqrt();
    let t = m * (cos_i / eta + cos_t) - w / eta;
    if t.z * w.z >= 0.0 {
        return (0.0, weight);
    }
    (((1.0 - fresnel) * mf.g1(t, m)) as f64, weight)
}

/// F·G1 of the ray reflected back inside (w taken as seen from within), with its weight.
fn reflected(mf: &Microfacet, w: Vec3, u: Vec3, eta: f32) -> (f64, f64) {
    let Some((m, weight)) = visible_normal(mf, w, u) else {
        return (0.0, 0.0);
    };
    let r = reflect(w, m);
    if r.z <= 0.0 {
        return (0.0, weight);
    }
    (
        (fresnel_dielectric(w.dot(m), eta) * mf.g1(r, m)) as f64,
        weight,
    )
}

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton's method on P_n, starting from
/// cos(π(i − ¼)/(n + ½)); Press et al., "Numerical Recipes", §4.6).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                (p0, p1) = (p1, p2);
            }
            let p = if n == 1 { x } else { p1 };
            let p_prev = if n == 1 { 1.0 } else { p0 };
            derivative = n as f64 * (x * p - p_prev) / (x * x - 1.0);
            let step = p / derivative;
            x -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::microfacet::MicrofacetType;

    #[test]
    fn gauss_legendre_is_exact_for_polynomials() {
        let (x, w) = gauss_legendre(8);
        let total: f64 = w.iter().sum();
        assert!((total - 2.0).abs() < 1e-12);
        // ∫ x¹⁴ = 2/15 is exact for 8 nodes (degree ≤ 15).
        let p14: f64 = x.iter().zip(&w).map(|(x, w)| x.powi(14) * w).sum();
        assert!((p14 - 2.0 / 15.0).abs() < 1e-12, "{p14}");
    }

    #[test]
    fn smooth_coat_limits() {
        // A nearly smooth coat transmits 1 − F at normal incidence.
        let mf = Microfacet::isotropic(MicrofacetType::Ggx, 0.001);
        let tables = CoatTables::new(&mf, 1.5);
        let t = tables.transmittance(1.0);
        assert!((t - 0.96).abs() < 2e-3, "{t}");
        // Rising Fresnel makes transmittance fall towards grazing.
        assert!(tables.transmittance(0.1) < tables.transmittance(0.9));
        // Internal reflectance of η = 1.5 is ≈ 0.6 (total internal reflection).
        assert!(
            (0.5..0.7).contains(&tables.internal_reflectance),
            "{}",
            tables.internal_reflectance
        );
    }
}
