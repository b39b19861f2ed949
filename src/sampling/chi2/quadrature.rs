//! Adaptive midpoint quadrature of a pdf over one histogram cell: the expected share of
//! samples in the cell. Cells where a finer grid disagrees with a coarser one (edges of
//! the support, integrable singularities) are split recursively.

use glam::DVec2;

/// Midpoints per axis on each (sub)cell.
const POINTS: usize = 8;

/// How to integrate: function of t ∈ [0, 1]², dimension, tolerances.
pub struct Integrand<'a> {
    /// The pdf at unit parameters t, already checked (an `Err` stops the integration).
    pub f: &'a dyn Fn(DVec2) -> Result<f64, String>,
    /// Integrate over x only (y fixed at 0).
    pub one_dimensional: bool,
    /// Deepest recursion (each level halves the cell along each used axis).
    pub max_depth: u32,
}

/// A midpoint-rule estimate and whether the support's edge passes through the box
/// (some points had zero density and some did not).
#[derive(Clone, Copy)]
struct Estimate {
    value: f64,
    straddles_edge: bool,
}

impl Integrand<'_> {
    /// ∫ f dt over the box [lo, hi] (area in t, not yet times the domain's measure),
    /// refined until a subdivision changes it by less than `tolerance`. Boxes the edge
    /// of the support passes through are always refined to `max_depth`: there, coarse
    /// and fine grids can agree while both miscount a thin strip. Returns the integral
    /// and the part left unresolved: Σ |fine − coarse| over the boxes that reached
    /// `max_depth` without converging (an integrable singularity, a support edge).
    pub fn integrate(&self, lo: DVec2, hi: DVec2, tolerance: f64) -> Result<(f64, f64), String> {
        let coarse = self.midpoints(lo, hi)?;
        self.refine(lo, hi, coarse, tolerance, self.max_depth)
    }

    /// The plain midpoint estimate of ∫ f dt over [lo, hi], to scale tolerances.
    pub fn estimate(&self, lo: DVec2, hi: DVec2) -> Result<f64, String> {
        Ok(self.midpoints(lo, hi)?.value)
    }

    fn refine(
        &self,
        lo: DVec2,
        hi: DVec2,
        coarse: Estimate,
        tolerance: f64,
        depth: u32,
    ) -> Result<(f64, f64), String> {
        let children = self.split(lo, hi);
        let mut parts = Vec::with_capacity(children.len());
        for &(a, b) in &children {
            parts.push(self.midpoints(a, b)?);
        }
        let fine: f64 = parts.iter().map(|p| p.value).sum();
        let any_zero = parts.iter().any(|p| p.value == 0.0);
        let edge = coarse.straddles_edge
            || parts.iter().any(|p| p.straddles_edge)
            || (any_zero && fine > 0.0);
        let change = (fine - coarse.value).abs();
        if !edge && change <= tolerance {
            return Ok((fine, 0.0));
        }
        if depth == 0 {
            return Ok((fine, change));
        }
        let (mut total, mut unresolved) = (0.0, 0.0);
        for (&(a, b), &part) in children.iter().zip(&parts) {
            let (value, error) = self.refine(a, b, part, 0.5 * tolerance, depth - 1)?;
            total += value;
            unresolved += error;
        }
        Ok((total, unresolved))
    }

    /// The box cut in half along each axis in use.
    fn split(&self, lo: DVec2, hi: DVec2) -> Vec<(DVec2, DVec2)> {
        let mid = 0.5 * (lo + hi);
        if self.one_dimensional {
            vec![(lo, DVec2::new(mid.x, hi.y)), (DVec2::new(mid.x, lo.y), hi)]
        } else {
            vec![
                (lo, mid),
                (DVec2::new(mid.x, lo.y), DVec2::new(hi.x, mid.y)),
                (DVec2::new(lo.x, mid.y), DVec2::new(mid.x, hi.y)),
                (mid, hi),
            ]
        }
    }

    /// The midpoint rule on a POINTS × POINTS grid (POINTS × 1 in 1D).
    fn midpoints(&self, lo: DVec2, hi: DVec2) -> Result<Estimate, String> {
        let rows = if self.one_dimensional { 1 } else { POINTS };
        let step = (hi - lo) / DVec2::new(POINTS as f64, rows as f64);
        let (mut sum, mut zeros) = (0.0, 0);
        for j in 0..rows {
            for i in 0..POINTS {
                let t = lo + step * DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
                let value = (self.f)(t)?;
                sum += value;
                zeros += (value == 0.0) as usize;
            }
        }
        let area = if self.one_dimensional {
            hi.x - lo.x
        } else {
            (hi.x - lo.x) * (hi.y - lo.y)
        };
        let straddles_edge = zeros > 0 && zeros < POINTS * rows;
        Ok(Estimate {
            value: sum * area / (POINTS * rows) as f64,
            straddles_edge,
        })
    }
}
