//! Albedo tables of a rough dielectric coat over a diffuse base, as Mitsuba 3's
//! `roughplastic` precomputes them: the coat's directional transmittance T(cos θ) from
//! outside, and its hemispherically averaged internal reflectance. Both integrate over
//! microfacet normals with Gauss–Legendre quadrature on the sampling square, weighting
//! each normal by D_v(m)/p(m) (visible-normal density over sampling density), so the
//! same code serves GGX (weight 1) and Beckmann (D·cos sampling).

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::fresnel::fresnel_dielectric;
use super::microfacet::{Microfacet, MicrofacetType, reflect};

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
        let rule_t = SquareRule::new(mf, 32);
        let rule_r = SquareRule::new(mf, 128);
        // The 64 rows (1.1·10⁶ microfacet normals in all, most of a scene's load with a
        // rough plastic) run in parallel; the reflectances are summed in row order after,
        // so the tables are the same bits on any number of threads.
        let rows: Vec<(f32, f64)> = (0..TABLE_SIZE)
            .into_par_iter()
            .map(|i| {
                let mu = (i as f64 / (TABLE_SIZE - 1) as f64).max(1e-6);
                let w = Vec3::new((1.0 - mu * mu).sqrt() as f32, 0.0, mu as f32);
                let t = rule_t.integrate(mf, w, |m| transmitted(mf, w, m, eta));
                let r = rule_r.integrate(mf, w, |m| reflected(mf, w, m, 1.0 / eta));
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

/// n × n Gauss–Legendre nodes on the sampling square, with what the microfacet sampler
/// needs of them precomputed: the same normals as `mf.sample(w, u)` at each node, bit
/// for bit, without repeating per row the work that does not depend on w.
struct SquareRule {
    /// Weight of each node along one axis (Gauss–Legendre on [−1, 1]).
    weights: Vec<f64>,
    normals: Normals,
}

/// The microfacet normals at the nodes of a [`SquareRule`].
enum Normals {
    /// GGX visible normals depend on w: per node √u₀ and the sine and cosine of 2πu₁.
    Visible {
        r: Vec<f32>,
        sin_cos: Vec<(f32, f32)>,
    },
    /// Beckmann's D·cos normals do not: per node pair (row-major) m, D(m) and the
    /// sampling density D(m)·cos θ_m.
    Fixed(Vec<(Vec3, f32, f32)>),
}

impl SquareRule {
    fn new(mf: &Microfacet, n: usize) -> SquareRule {
        let (nodes, weights) = gauss_legendre(n);
        let u: Vec<f32> = nodes.iter().map(|&x| (x * 0.5 + 0.5) as f32).collect();
        let normals = match mf.distribution {
            MicrofacetType::Ggx => Normals::Visible {
                r: u.iter().map(|u| u.sqrt()).collect(),
                sin_cos: u.iter().map(|u| (TAU * u).sin_cos()).collect(),
            },
            MicrofacetType::Beckmann => Normals::Fixed(
                u.iter()
                    .flat_map(|&x| u.iter().map(move |&y| Vec2::new(x, y)))
                    .map(|u| {
                        let (m, p) = mf.sample(Vec3::Z, u);
                        (m, mf.d(m), p)
                    })
                    .collect(),
            ),
        };
        SquareRule { weights, normals }
    }

    /// Σ w_i w_j g(m_ij)·D_v(m_ij)/p(m_ij) over the square (the nodes mapped from
    /// [−1, 1], hence the ¼), D_v the density of normals visible from `w`. Nodes whose
    /// weight is zero add nothing and are skipped.
    fn integrate(&self, mf: &Microfacet, w: Vec3, g: impl Fn(Vec3) -> f64) -> f64 {
        let n = self.weights.len();
        let frame = mf.visible_frame(w);
        let mut sum = 0.0;
        for (i, wx) in self.weights.iter().enumerate() {
            for (j, wy) in self.weights.iter().enumerate() {
                let (m, weight) = match &self.normals {
                    // D_v is GGX's sampling density itself: the weight is exactly 1
                    // wherever the density is positive (D_v(m)/D_v(m) in floats).
                    Normals::Visible { r, sin_cos } => {
                        let (sin_phi, cos_phi) = sin_cos[j];
                        let m = frame.normal(r[i], sin_phi, cos_phi);
                        if mf.sample_pdf(w, m) > 0.0 {
                            (m, 1.0)
                        } else {
                            continue;
                        }
                    }
                    Normals::Fixed(normals) => {
                        let (m, d, p) = normals[i * n + j];
                        let visible = mf.g1(w, m) * w.dot(m).max(0.0) * d / w.z;
                        if p > 0.0 && visible > 0.0 {
                            (m, (visible / p) as f64)
                        } else {
                            continue;
                        }
                    }
                };
                sum += g(m) * weight * wx * wy * 0.25;
            }
        }
        sum
    }
}

/// (1 − F)·G1 of the ray refracted into the coat through the microfacet m.
fn transmitted(mf: &Microfacet, w: Vec3, m: Vec3, eta: f32) -> f64 {
    let cos_i = w.dot(m);
    let fresnel = fresnel_dielectric(cos_i, eta);
    // Snell: cos θ_t = −√(1 − (1 − cos²θ_i)/η²), t = m(cos θ_i/η + cos θ_t) − w/η.
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 0.0;
    }
    let cos_t = -(1.0 - sin2_t).sqrt();
    let t = m * (cos_i / eta + cos_t) - w / eta;
    if t.z * w.z >= 0.0 {
        return 0.0;
    }
    ((1.0 - fresnel) * mf.g1(t, m)) as f64
}

/// F·G1 of the ray reflected back inside by m (w taken as seen from within).
fn reflected(mf: &Microfacet, w: Vec3, m: Vec3, eta: f32) -> f64 {
    let r = reflect(w, m);
    if r.z <= 0.0 {
        return 0.0;
    }
    (fresnel_dielectric(w.dot(m), eta) * mf.g1(r, m)) as f64
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

    /// The tables by the plain quadrature: `mf.sample(w, u)` at every node of every row,
    /// weighted by D_v(m)/p(m) computed afresh.
    fn plain_tables(mf: &Microfacet, eta: f32) -> CoatTables {
        let integrate = |n: usize, w: Vec3, g: &dyn Fn(Vec3) -> f64| {
            let (nodes, weights) = gauss_legendre(n);
            let mut sum = 0.0;
            for (x, wx) in nodes.iter().zip(&weights) {
                for (y, wy) in nodes.iter().zip(&weights) {
                    let u = Vec2::new((x * 0.5 + 0.5) as f32, (y * 0.5 + 0.5) as f32);
                    let (m, p) = mf.sample(w, u);
                    let visible = mf.g1(w, m) * w.dot(m).max(0.0) * mf.d(m) / w.z;
                    if p > 0.0 && visible > 0.0 {
                        sum += g(m) * (visible / p) as f64 * wx * wy * 0.25;
                    }
                }
            }
            sum
        };
        let mut external_transmittance = Box::new([0.0f32; TABLE_SIZE]);
        let mut internal = 0.0;
        for (i, t) in external_transmittance.iter_mut().enumerate() {
            let mu = (i as f64 / (TABLE_SIZE - 1) as f64).max(1e-6);
            let w = Vec3::new((1.0 - mu * mu).sqrt() as f32, 0.0, mu as f32);
            *t = integrate(32, w, &|m| transmitted(mf, w, m, eta)) as f32;
            internal += integrate(128, w, &|m| reflected(mf, w, m, 1.0 / eta)) * mu;
        }
        CoatTables {
            external_transmittance,
            internal_reflectance: (2.0 * internal / TABLE_SIZE as f64) as f32,
        }
    }

    #[test]
    fn precomputed_nodes_give_the_plain_quadrature_bit_for_bit() {
        for (kind, alpha_u, alpha_v, eta) in [
            (MicrofacetType::Ggx, 0.2, 0.2, 1.5),
            (MicrofacetType::Ggx, 0.05, 0.6, 1.33),
            (MicrofacetType::Beckmann, 0.3, 0.3, 1.5),
            (MicrofacetType::Beckmann, 0.7, 0.1, 1.9),
        ] {
            let mf = Microfacet::anisotropic(kind, alpha_u, alpha_v);
            assert_eq!(CoatTables::new(&mf, eta), plain_tables(&mf, eta), "{mf:?}");
        }
    }
}
