//! Optimal MIS weights for light + BSDF sampling (Kondapaneni, Vévoda, Grittmann, Skřivan,
//! Slusallek & Křivánek 2019, "Optimal Multiple Importance Sampling", ACM TOG 38(4)).
//!
//! With n_L light and n_B BSDF samples, the optimal weights turn the estimate into the
//! balance heuristic plus a control variate Σ_t α_t p_t (their eq. 14):
//!
//! F = α_L + α_B + Σ_t Σ_j (f(X_tj) − α_L p_L(X_tj) − α_B p_B(X_tj)) / (n_L p_L + n_B p_B),
//!
//! unbiased for any fixed α (each p_t integrates to one), and of least variance when α
//! solves A α = b with A_tk = ∫ p_t p_k / Σ n p and b_t = ∫ f p_t / Σ n p (eq. 15). lightlab
//! estimates A and b per pixel from its samples (Σ p_t p_k / (Σ n p)² and Σ f p_t / (Σ n p)²)
//! and uses, in each round, the α of the rounds before it, so α never depends on the
//! samples it weights: the first round is the balance heuristic (α = 0) unless the render
//! continues earlier ones (`render::Carry`: a timed render's rounds, a reference's
//! passes), and so is a pixel whose A is singular.
//!
//! Densities are taken in path space, where each technique's failures live apart: a light
//! sample that is occluded, faces away, lies below the horizon, carries no radiance, or
//! finds no light is a point only light sampling reaches (p_B = 0 there), scoring
//! −α_L/n_L; a BSDF sample that fails or reaches no emitter scores −α_B/n_B. Delta
//! samples (point lights, mirror lobes) keep weight 1 and count as such failures of the
//! continuous part.

use glam::Vec3;

use crate::math::Spectrum;

/// Index of light sampling in α and in the moments.
pub const LIGHT: usize = 0;
/// Index of BSDF sampling.
pub const BSDF: usize = 1;

/// Estimates of the technique matrix A (A_LL, A_LB, A_BB) and of b (per technique, RGB),
/// as sums over samples.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TechniqueMoments {
    /// A_LL, A_LB, A_BB.
    pub a: [f64; 3],
    /// b_L and b_B, per channel.
    pub b: [[f64; 3]; 2],
}

impl TechniqueMoments {
    /// Adds a sample of the shared domain: integrand `f`, densities `p_light`, `p_bsdf`,
    /// and `d` = n_L p_L + n_B p_B.
    #[inline]
    pub fn add(&mut self, f: Spectrum, p_light: f32, p_bsdf: f32, d: f32) {
        let (pl, pb) = (p_light as f64, p_bsdf as f64);
        let d2 = (d as f64) * (d as f64);
        if !(d2 > 0.0 && d2.is_finite()) {
            return;
        }
        self.a[0] += pl * pl / d2;
        self.a[1] += pl * pb / d2;
        self.a[2] += pb * pb / d2;
        for c in 0..3 {
            self.b[LIGHT][c] += f[c] as f64 * pl / d2;
            self.b[BSDF][c] += f[c] as f64 * pb / d2;
        }
    }

    /// Adds a failure of technique `t` drawn `n` times per estimate: a point only `t`
    /// reaches, so p_t²/(n p_t)² = 1/n² to A_tt.
    #[inline]
    pub fn add_failure(&mut self, t: usize, n: f32) {
        self.a[if t == LIGHT { 0 } else { 2 }] += 1.0 / (n as f64 * n as f64);
    }

    /// Adds another pixel's or sample's moments.
    #[inline]
    pub fn merge(&mut self, o: &TechniqueMoments) {
        for i in 0..3 {
            self.a[i] += o.a[i];
        }
        for t in 0..2 {
            for c in 0..3 {
                self.b[t][c] += o.b[t][c];
            }
        }
    }

    /// α = A⁻¹ b per channel; zero (the balance heuristic) where A is singular: a
    /// technique never seen, or the two densities proportional on every sample.
    pub fn alpha(&self) -> [Spectrum; 2] {
        let [all, alb, abb] = self.a;
        let det = all * abb - alb * alb;
        if !(all > 0.0 && abb > 0.0 && det > 1e-6 * all * abb && det.is_finite()) {
            return [Spectrum::ZERO; 2];
        }
        let solve = |c: usize| {
            let (bl, bb) = (self.b[LIGHT][c], self.b[BSDF][c]);
            ((abb * bl - alb * bb) / det, (all * bb - alb * bl) / det)
        };
        let (r, g, b) = (solve(0), solve(1), solve(2));
        let alpha = [
            Vec3::new(r.0 as f32, g.0 as f32, b.0 as f32),
            Vec3::new(r.1 as f32, g.1 as f32, b.1 as f32),
        ];
        if alpha.iter().all(|a| a.is_finite()) {
            alpha
        } else {
            [Spectrum::ZERO; 2]
        }
    }
}

/// One pixel's state: the α its samples use this round, and the moments of every sample
/// so far (α for the next round).
#[derive(Clone, Copy, Debug, Default)]
pub struct OptimalPixel {
    /// α_L and α_B for the current round.
    pub alpha: [Spectrum; 2],
    /// Moments of all earlier samples and of this round's so far.
    pub moments: TechniqueMoments,
}

impl OptimalPixel {
    /// Ends a round: α from every sample so far.
    pub fn next_round(&mut self) {
        self.alpha = self.moments.alpha();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_solves_the_two_by_two_system() {
        // A = [[2, 1], [1, 3]], b = A·(0.5, −0.25) per channel (scaled by c + 1).
        let mut m = TechniqueMoments {
            a: [2.0, 1.0, 3.0],
            b: [[0.0; 3]; 2],
        };
        for c in 0..3 {
            let s = c as f64 + 1.0;
            m.b[LIGHT][c] = s * (2.0 * 0.5 + 1.0 * -0.25);
            m.b[BSDF][c] = s * (1.0 * 0.5 + 3.0 * -0.25);
        }
        let [al, ab] = m.alpha();
        assert!((al - Vec3::new(0.5, 1.0, 1.5)).length() < 1e-6, "{al}");
        assert!((ab - Vec3::new(-0.25, -0.5, -0.75)).length() < 1e-6, "{ab}");
        // Proportional densities on every sample make A singular: balance (α = 0).
        let mut singular = TechniqueMoments::default();
        for k in 1..10 {
            let p = k as f32;
            singular.add(Spectrum::ONE, p, 2.0 * p, 3.0 * p);
        }
        assert_eq!(singular.alpha(), [Spectrum::ZERO; 2]);
        assert_eq!(TechniqueMoments::default().alpha(), [Spectrum::ZERO; 2]);
    }
}
