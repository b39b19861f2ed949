//! Selection by emitted power: p_i = Φ_i / Σ Φ_j (lecture, many lights, solution #2:
//! "importance sampling of the light source w.r.t. its power"), drawn in O(1) from
//! Vose's alias table.

use super::{LightSelector, Selection};
use crate::light::ShadingPoint;
use crate::sampling::distribution::AliasTable;

/// Chooses light i with probability Φ_i / ΣΦ, whatever the shading point. When every
/// power is zero the table is uniform (see [`AliasTable`]).
#[derive(Clone, Debug)]
pub struct PowerSelector {
    table: Option<AliasTable>,
}

impl PowerSelector {
    /// A selector over lights of the given powers; negative or non-finite powers count
    /// as zero (such a light is never chosen).
    pub fn new(powers: &[f32]) -> PowerSelector {
        let weights: Vec<f32> = powers
            .iter()
            .map(|&p| if p.is_finite() && p > 0.0 { p } else { 0.0 })
            .collect();
        PowerSelector {
            table: AliasTable::new(&weights).ok(),
        }
    }
}

impl LightSelector for PowerSelector {
    #[inline]
    fn select(&self, _at: &ShadingPoint, u: f32) -> Option<Selection> {
        let (index, pmf, u_reused) = self.table.as_ref()?.sample(u);
        Some(Selection {
            index,
            pmf,
            u_reused,
        })
    }

    #[inline]
    fn pmf(&self, _at: &ShadingPoint, index: usize) -> f32 {
        self.table.as_ref().map_or(0.0, |t| t.pmf(index))
    }
}
