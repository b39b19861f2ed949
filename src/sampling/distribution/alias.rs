//! Vose's alias table (Vose 1991, "A Linear Algorithm for Generating Random Numbers with
//! a Given Distribution", IEEE TSE 17(9)): O(1) discrete sampling after O(n) setup.

use super::{DistributionError, check_weights};
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// One column of the table: keep bin i with probability `keep`, else take `alias`.
#[derive(Clone, Copy, Debug)]
struct Column {
    keep: f32,
    alias: u32,
}

/// A discrete distribution over 0..n sampled with one uniform number in O(1). All-zero
/// weights give the uniform distribution.
#[derive(Clone, Debug)]
pub struct AliasTable {
    columns: Vec<Column>,
    pmf: Vec<f32>,
}

impl AliasTable {
    /// The table of `weights`; an error for an empty table or a negative or non-finite
    /// weight.
    pub fn new(weights: &[f32]) -> Result<Self, DistributionError> {
        check_weights(weights)?;
        let n = weights.len();
        let total: f64 = weights.iter().map(|&w| w as f64).sum();
        let pmf: Vec<f64> = weights
            .iter()
            .map(|&w| {
                if total > 0.0 {
                    w as f64 / total
                } else {
                    1.0 / n as f64
                }
            })
            .collect();
        // Scaled probabilities n·p_i: columns below 1 are topped up by one above 1.
        let mut scaled: Vec<f64> = pmf.iter().map(|p| p * n as f64).collect();
        let mut columns = vec![
            Column {
                keep: 1.0,
                alias: 0
            };
            n
        ];
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            columns[s] = Column {
                keep: scaled[s] as f32,
                alias: l as u32,
            };
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // Whatever is left is 1 up to rounding (keep = 1 from initialisation), except that
        // a zero-weight column must never keep itself: send it to the heaviest bin.
        let heaviest = (0..n)
            .max_by(|&a, &b| pmf[a].total_cmp(&pmf[b]))
            .unwrap_or(0);
        for (column, &p) in columns.iter_mut().zip(&pmf) {
            if p == 0.0 {
                column.keep = 0.0;
                if pmf[column.alias as usize] == 0.0 {
                    column.alias = heaviest as u32;
                }
            }
        }
        Ok(AliasTable {
            columns,
            pmf: pmf.iter().map(|&p| p as f32).collect(),
        })
    }

    /// Number of outcomes.
    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    /// Always false: a table has at least one outcome.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Probability of outcome `index` (0 outside the table).
    pub fn pmf(&self, index: usize) -> f32 {
        self.pmf.get(index).copied().unwrap_or(0.0)
    }

    /// Draws an outcome with one uniform number: n·u picks a column, its fraction
    /// decides between the column and its alias. Returns (index, pmf, u rescaled to
    /// [0, 1) within the part of the column that was taken).
    ///
    /// ```
    /// use lightlab::sampling::distribution::AliasTable;
    /// let t = AliasTable::new(&[1.0, 0.0, 3.0]).unwrap();
    /// let (i, pmf, _) = t.sample(0.9);
    /// assert!(i != 1 && pmf == t.pmf(i));
    /// ```
    pub fn sample(&self, u: f32) -> (usize, f32, f32) {
        let scaled = u.clamp(0.0, ONE_MINUS_EPSILON) * self.len() as f32;
        let column = (scaled as usize).min(self.len() - 1);
        let fraction = (scaled - column as f32).clamp(0.0, ONE_MINUS_EPSILON);
        let Column { keep, alias } = self.columns[column];
        let (index, u_reused) = if fraction < keep {
            (column, fraction / keep)
        } else {
            (alias as usize, (fraction - keep) / (1.0 - keep))
        };
        (
            index,
            self.pmf[index],
            u_reused.clamp(0.0, ONE_MINUS_EPSILON),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_add_up_to_the_pmf_and_zero_bins_are_never_chosen() {
        for weights in [
            vec![1.0, 0.0, 3.0, 0.5],
            vec![0.0, 0.0, 1.0],
            vec![0.0; 3],
            vec![1e-30, 1.0, 0.0],
        ] {
            let table = AliasTable::new(&weights).expect("valid");
            let n = table.len() as f64;
            let mut mass = vec![0.0f64; table.len()];
            for (i, c) in table.columns.iter().enumerate() {
                mass[i] += c.keep as f64 / n;
                mass[c.alias as usize] += (1.0 - c.keep as f64) / n;
            }
            for (i, m) in mass.iter().enumerate() {
                assert!(
                    (m - table.pmf(i) as f64).abs() < 1e-6,
                    "{weights:?}: bin {i}"
                );
            }
            for k in 0..=1000 {
                let (i, pmf, u) = table.sample(k as f32 / 1000.0);
                assert!(
                    pmf > 0.0 && (0.0..1.0).contains(&u),
                    "{weights:?}: chose {i}"
                );
            }
        }
    }
}
