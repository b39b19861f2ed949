//! A piecewise-constant density on [0, 1)² from a table of weights (an environment map's
//! luminance, say), sampled as a marginal over rows times a conditional within the row
//! (pbrt-v4 §A.5.6, `PiecewiseConstant2D`).

use glam::Vec2;

use super::{DistributionError, PiecewiseConstant1D, check_weights};

/// Row-major weights on a `width × height` grid over [0, 1)²: x indexes columns, y rows.
/// All-zero weights give the uniform density.
#[derive(Clone, Debug)]
pub struct PiecewiseConstant2D {
    /// One 1D distribution per row, over x.
    conditionals: Vec<PiecewiseConstant1D>,
    /// Over y, weighted by each row's integral.
    marginal: PiecewiseConstant1D,
}

impl PiecewiseConstant2D {
    /// The distribution of the row-major `weights`; an error if their count is not
    /// `width × height` or a weight is negative or non-finite.
    pub fn new(weights: &[f32], width: usize, height: usize) -> Result<Self, DistributionError> {
        if width == 0 || height == 0 || weights.len() != width * height {
            return Err(DistributionError::Shape {
                len: weights.len(),
                width,
                height,
            });
        }
        check_weights(weights)?;
        let conditionals = weights
            .chunks_exact(width)
            .map(PiecewiseConstant1D::new)
            .collect::<Result<Vec<_>, _>>()?;
        let row_integrals: Vec<f32> = conditionals.iter().map(|c| c.integral()).collect();
        let marginal = PiecewiseConstant1D::new(&row_integrals)?;
        Ok(PiecewiseConstant2D {
            conditionals,
            marginal,
        })
    }

    /// A point p ∈ [0, 1)² and its density per unit area: u₁ picks y by the marginal,
    /// u₀ picks x by that row's conditional, both by continuous inversion.
    ///
    /// ```
    /// use lightlab::sampling::distribution::PiecewiseConstant2D;
    /// let d = PiecewiseConstant2D::new(&[0.0, 1.0, 0.0, 3.0], 2, 2).unwrap();
    /// let (p, pdf) = d.sample(glam::Vec2::new(0.3, 0.6));
    /// assert!(p.x >= 0.5 && (pdf - d.pdf(p)).abs() < 1e-5);
    /// ```
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (y, pdf_y) = self.marginal.sample_continuous(u.y);
        let (x, pdf_x) = self.row(y).sample_continuous(u.x);
        (Vec2::new(x, y), pdf_x * pdf_y)
    }

    /// The cell that [`PiecewiseConstant2D::sample`] would place its point in, by the same
    /// inversion: its (column, row), its probability, and u rescaled to [0, 1)² within
    /// the chosen CDF intervals, so the two numbers can place a point inside the cell by
    /// any other density (the lecture's one number reused for two choices).
    #[inline]
    pub fn sample_cell(&self, u: Vec2) -> ((usize, usize), f32, Vec2) {
        let (row, pmf_y, uy) = self.marginal.sample_discrete(u.y);
        let (column, pmf_x, ux) = self.conditionals[row].sample_discrete(u.x);
        ((column, row), pmf_x * pmf_y, Vec2::new(ux, uy))
    }

    /// The probability of cell (`column`, `row`) under [`PiecewiseConstant2D::sample_cell`];
    /// 0 outside the table.
    #[inline]
    pub fn cell_pmf(&self, column: usize, row: usize) -> f32 {
        match self.conditionals.get(row) {
            Some(c) => self.marginal.pmf(row) * c.pmf(column),
            None => 0.0,
        }
    }

    /// Density at p per unit area of [0, 1)²; 0 outside.
    pub fn pdf(&self, p: Vec2) -> f32 {
        if !(0.0..1.0).contains(&p.y) {
            return 0.0;
        }
        self.marginal.pdf(p.y) * self.row(p.y).pdf(p.x)
    }

    /// Inverse of [`PiecewiseConstant2D::sample`]: the u that maps to p.
    pub fn to_square(&self, p: Vec2) -> Vec2 {
        Vec2::new(self.row(p.y).cdf(p.x), self.marginal.cdf(p.y))
    }

    /// The conditional of the row containing y.
    fn row(&self, y: f32) -> &PiecewiseConstant1D {
        let index = ((y.clamp(0.0, 1.0) * self.conditionals.len() as f32) as usize)
            .min(self.conditionals.len() - 1);
        &self.conditionals[index]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_rows_are_never_chosen_and_inverse_round_trips() {
        let weights = [0.0, 0.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 0.0];
        let d = PiecewiseConstant2D::new(&weights, 3, 3).expect("valid");
        for (i, j) in (0..10).flat_map(|i| (0..10).map(move |j| (i, j))) {
            let u = Vec2::new(i as f32 + 0.5, j as f32 + 0.5) / 10.0;
            let (p, pdf) = d.sample(u);
            assert!(pdf > 0.0 && (d.pdf(p) - pdf).abs() < 1e-5);
            assert!((1.0 / 3.0..2.0 / 3.0).contains(&p.y), "{p}");
            assert!((d.to_square(p) - u).length() < 1e-4);
        }
        assert!(PiecewiseConstant2D::new(&weights, 2, 3).is_err());
        // The discrete choice: the same cell as the continuous point, its pmf, and the
        // reused numbers place the point back where `sample` put it.
        for k in 0..200 {
            let u = Vec2::new((k as f32 * 0.618_034).fract(), (k as f32 + 0.5) / 200.0);
            let ((i, j), pmf, reused) = d.sample_cell(u);
            let (p, pdf) = d.sample(u);
            assert_eq!((i, j), ((p.x * 3.0) as usize, (p.y * 3.0) as usize), "{u}");
            assert!((pmf * 9.0 - pdf).abs() < 1e-5 && d.cell_pmf(i, j) == pmf);
            let back = Vec2::new(i as f32 + reused.x, j as f32 + reused.y) / 3.0;
            assert!((back - p).length() < 1e-5, "{back} {p}");
        }
        assert_eq!(d.cell_pmf(0, 3), 0.0);
        let zero = PiecewiseConstant2D::new(&[0.0; 4], 2, 2).expect("uniform fallback");
        assert_eq!(zero.sample_cell(Vec2::splat(0.75)).1, 0.25);
        assert_eq!(zero.sample(Vec2::splat(0.25)), (Vec2::splat(0.25), 1.0));
    }
}
