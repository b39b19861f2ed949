//! MIS weights (Veach & Guibas 1995; Veach's thesis §9.2). Each strategy i takes n_i samples
//! with density p_i, and the weights use the effective densities n_i·p_i, so unequal sample
//! counts are weighted right:
//!
//! - balance heuristic: w_i = n_i p_i / Σ_k n_k p_k           (thesis eq. 9.6)
//! - power heuristic:   w_i = (n_i p_i)^β / Σ_k (n_k p_k)^β, β = 2 (thesis eq. 9.12)

pub use crate::settings::MisHeuristic;

/// Weight of a sample drawn by strategy `a` (effective density `na_pa` = n_a·p_a) against
/// the other strategy's effective density `nb_pb` at the same direction. The weights of the
/// two strategies for one direction sum to one whenever either density is positive.
#[inline]
pub fn mis_weight(heuristic: MisHeuristic, na_pa: f32, nb_pb: f32) -> f32 {
    if na_pa.is_nan() || na_pa <= 0.0 || !nb_pb.is_finite() {
        return 0.0;
    }
    // w = a^β / (a^β + b^β) = 1 / (1 + (b/a)^β): the ratio form cannot overflow to ∞/∞
    // for a very peaked lobe.
    let r = nb_pb / na_pa;
    match heuristic {
        MisHeuristic::Power => 1.0 / (1.0 + r * r),
        // Optimal weights are the balance heuristic plus a control variate (`optimal`).
        MisHeuristic::Balance | MisHeuristic::OneSample | MisHeuristic::Optimal => 1.0 / (1.0 + r),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::rng::Rng32;

    #[test]
    fn weights_sum_to_one_over_the_strategies() {
        let mut rng = Rng32::new(7);
        for h in MisHeuristic::ALL {
            for _ in 0..100_000 {
                // Densities over many orders of magnitude, counts 1..8, and exact zeros.
                let p = |r: &mut Rng32| {
                    let u = r.next_f32();
                    if u < 0.05 {
                        0.0
                    } else {
                        10f32.powf(12.0 * u - 6.0)
                    }
                };
                let (pa, pb) = (p(&mut rng), p(&mut rng));
                let (na, nb) = (1 + rng.next_u32() % 8, 1 + rng.next_u32() % 8);
                let (ea, eb) = (na as f32 * pa, nb as f32 * pb);
                let s = mis_weight(h, ea, eb) + mis_weight(h, eb, ea);
                if pa > 0.0 || pb > 0.0 {
                    assert!((s - 1.0).abs() < 1e-5, "{h}: {ea} {eb} sum {s}");
                } else {
                    assert_eq!(s, 0.0);
                }
            }
        }
    }

    #[test]
    fn known_values() {
        assert_eq!(mis_weight(MisHeuristic::Balance, 1.0, 3.0), 0.25);
        assert_eq!(mis_weight(MisHeuristic::Power, 1.0, 3.0), 0.1);
        assert_eq!(mis_weight(MisHeuristic::Power, 2.0, 0.0), 1.0);
        assert_eq!(mis_weight(MisHeuristic::Balance, 0.0, 5.0), 0.0);
        assert_eq!(mis_weight(MisHeuristic::Power, f32::INFINITY, 5.0), 1.0);
    }
}
