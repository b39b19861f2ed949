//! The sampling density of a lat-long map over its grid of cells: a cell is chosen in
//! proportion to the integral of its bilinear weight (times the mean of sin θ over its
//! row), then the point inside it is drawn ∝ the bilinear interpolation of the weights at
//! its four corner texels (the bilinear warp of Hart et al. 2020, as pbrt-v4's
//! `SampleBilinear`). So the density follows, up to sin θ's variation within a row, the
//! bilinearly interpolated radiance the map is evaluated with, instead of being constant
//! over each cell: a piecewise-constant density leaves the ratio radiance/density varying
//! by the texel contrast inside every cell, which on a small map with a sun a few texels
//! wide is most of the light estimator's variance. Mitsuba 3's `envmap` also samples a
//! bilinear interpolant (its `Hierarchical2D` warp), of luminance × sin θ per texel.
//!
//! Coordinates are the cell grid's: x ∈ [0, 1) over the W cells of a row (cell i lies
//! between texel columns i and i + 1, wrapping), y ∈ [0, 1) over the H − 1 rows of cells.

use glam::Vec2;

use super::LatLongImage;
use super::image::TexelCell;
use crate::math::{PI, Spectrum, spectrum::luminance};
use crate::sampling::distribution::{DistributionError, PiecewiseConstant2D};
use crate::sampling::sampler::ONE_MINUS_EPSILON;
use crate::sampling::warp::{bilinear_pdf, square_to_bilinear};

/// Cells chosen ∝ their weight, points inside ∝ the bilinear corner weights. A texel's
/// weight is max(0, luminance − `offset`): the luminance itself for the plain
/// distribution, its excess over the mean for the MIS-compensated one, scaled so that the
/// largest is 1 (the bilinear warp squares its weights: a sun of luminance 10²⁰ would
/// overflow). The weights are computed from the texels where they are needed (the four a
/// lookup reads anyway), not stored.
#[derive(Clone, Debug)]
pub(super) struct CellDistribution {
    cells: PiecewiseConstant2D,
    offset: f32,
    scale: f32,
    width: usize,
    rows: usize,
}

impl CellDistribution {
    /// The distribution of the W×H texels' `luminance` (clamped at 0) less `offset`.
    pub fn new(
        luminance: &[f32],
        offset: f32,
        width: usize,
        height: usize,
    ) -> Result<Self, DistributionError> {
        let largest = luminance
            .iter()
            .fold(0.0f32, |m, &l| m.max(weight(l, offset, 1.0)));
        let scale = if largest.is_normal() {
            1.0 / largest
        } else {
            1.0
        };
        let texels: Vec<f32> = luminance
            .iter()
            .map(|&l| weight(l, offset, scale))
            .collect();
        let rows = height - 1;
        let cells = PiecewiseConstant2D::new(&cell_weights(&texels, width, height), width, rows)?;
        Ok(CellDistribution {
            cells,
            offset,
            scale,
            width,
            rows,
        })
    }

    /// The corner weights `[w00, w10, w01, w11]` of a cell from its corner texels; all
    /// ones where all four are zero (such a cell is chosen only by an all-zero map's
    /// uniform fallback).
    #[inline]
    fn corner_weights(&self, texels: &[Spectrum; 4]) -> [f32; 4] {
        let w = texels.map(|t| weight(luminance(t), self.offset, self.scale));
        if w.iter().sum::<f32>() > 0.0 {
            w
        } else {
            [1.0; 4]
        }
    }

    /// A point of the cell grid of `image`, with the image cell it lies in, that cell's
    /// corner texels and the point's density (exactly [`CellDistribution::pdf`] of that
    /// cell and point).
    #[inline]
    pub fn sample(&self, u: Vec2, image: &LatLongImage) -> CellSample {
        let ((i, j), pmf, reused) = self.cells.sample_cell(u);
        // A reused number is exactly 0 when u hits a CDF entry (about 1 sample in 10⁶ of
        // f32 numbers); the bilinear warp would put it on the cell's edge, where a zero
        // corner gives density 0. Move it to 2⁻²⁴, the next number a uniform f32 takes.
        let reused = reused.max(Vec2::splat(0.5 * f32::EPSILON));
        let texels = image.corners(&TexelCell::new(i, j));
        let (p, inside) = square_to_bilinear(reused, self.corner_weights(&texels));
        CellSample {
            grid: Vec2::new(
                ((i as f32 + p.x) / self.width as f32).min(ONE_MINUS_EPSILON),
                ((j as f32 + p.y) / self.rows as f32).min(ONE_MINUS_EPSILON),
            ),
            // Cell i of the grid lies between texel columns i and i + 1, as the image's
            // cell i does: the point is at p in both.
            cell: TexelCell { i, j, f: p },
            texels,
            pdf: self.grid_pdf(pmf, inside),
        }
    }

    /// The density of [`CellDistribution::sample`] per unit area at the point `cell.f`
    /// of `cell`, whose corner texels are `texels`.
    #[inline]
    pub fn pdf(&self, cell: &TexelCell, texels: &[Spectrum; 4]) -> f32 {
        let pmf = self.cells.cell_pmf(cell.i, cell.j);
        if pmf <= 0.0 {
            return 0.0;
        }
        let inside = cell.f.clamp(Vec2::ZERO, Vec2::ONE);
        self.grid_pdf(pmf, bilinear_pdf(inside, self.corner_weights(texels)))
    }

    /// The density per unit area of the grid of a point inside a cell of probability
    /// `pmf` with density `inside` per unit area of the cell.
    #[inline]
    fn grid_pdf(&self, pmf: f32, inside: f32) -> f32 {
        pmf * (self.width * self.rows) as f32 * inside
    }
}

/// A point drawn by [`CellDistribution::sample`].
pub(super) struct CellSample {
    /// The point on the cell grid, in [0, 1)².
    pub(super) grid: Vec2,
    /// The image cell it lies in, and where in it.
    pub(super) cell: TexelCell,
    /// That cell's corner texels, `[t00, t10, t01, t11]`.
    pub(super) texels: [Spectrum; 4],
    /// Its density per unit area of the grid.
    pub(super) pdf: f32,
}

/// A texel's sampling weight: max(0, max(0, luminance) − offset) · scale.
#[inline]
fn weight(luminance: f32, offset: f32, scale: f32) -> f32 {
    (luminance.max(0.0) - offset).max(0.0) * scale
}

/// The weights of the W×(H − 1) cells of W×H texel weights: the mean of the cell's four
/// corners (the integral of its bilinear patch) times the mean of sin θ over its row, the
/// lat-long map's area element (θ from 0 at row 0 to π at row H − 1).
pub(super) fn cell_weights(texels: &[f32], width: usize, height: usize) -> Vec<f32> {
    let rows = height - 1;
    let dtheta = PI / rows as f32;
    let mut weights = Vec::with_capacity(width * rows);
    for j in 0..rows {
        // (cos θ₀ − cos θ₁)/Δθ, written as 2·sin θ_mid·sin(Δθ/2)/Δθ with θ_mid measured
        // from the nearer pole: the difference of cosines cancels in f32 near the poles of
        // a tall map (0 for the polar rows from about 12 900 rows on), and an f32 θ near π
        // would carry an error of 10⁻³ of sin θ.
        let from_pole = (j as f32 + 0.5).min((rows - j) as f32 - 0.5) * dtheta;
        let mean_sin = 2.0 * from_pole.sin() * (0.5 * dtheta).sin() / dtheta;
        for i in 0..width {
            let i1 = (i + 1) % width;
            let corners = texels[j * width + i]
                + texels[j * width + i1]
                + texels[(j + 1) * width + i]
                + texels[(j + 1) * width + i1];
            weights.push(0.25 * corners * mean_sin);
        }
    }
    weights
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: usize, h: usize, texels: &[f32]) -> LatLongImage {
        LatLongImage::new(w, h, texels.iter().map(|&t| Spectrum::splat(t)).collect())
            .expect("image")
    }

    /// The density of a point of the cell grid, located as a lookup locates it.
    fn pdf_at(d: &CellDistribution, img: &LatLongImage, p: Vec2) -> f32 {
        let cell = TexelCell::new(
            ((p.x * img.width as f32) as usize).min(img.width - 1),
            ((p.y * (img.height - 1) as f32) as usize).min(img.height - 2),
        );
        let f = Vec2::new(
            p.x * img.width as f32 - cell.i as f32,
            p.y * (img.height - 1) as f32 - cell.j as f32,
        );
        d.pdf(&TexelCell { f, ..cell }, &img.corners(&cell))
    }

    /// The density integrates to one over the grid and follows the bilinear weights
    /// inside a cell: at a cell's corners it is in the ratio of the corner texels.
    #[test]
    fn density_is_normalised_and_bilinear_inside_cells() {
        let (w, h) = (5, 4);
        let texels: Vec<f32> = (0..w * h).map(|k| ((k * 7) % 5) as f32).collect();
        let img = image(w, h, &texels);
        let d = CellDistribution::new(&texels, 0.0, w, h).expect("valid");
        let n = 400;
        let mut sum = 0.0f64;
        for a in 0..n {
            for b in 0..n {
                let p = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                sum += pdf_at(&d, &img, p) as f64;
            }
        }
        let mean = sum / (n * n) as f64;
        assert!((mean - 1.0).abs() < 2e-3, "∫ pdf = {mean}");
        // Near the corners of cell (1, 1): the density's ratios are the texels' ratios.
        let eps = 1e-4;
        let at = |fx: f32, fy: f32| {
            pdf_at(
                &d,
                &img,
                Vec2::new((1.0 + fx) / w as f32, (1.0 + fy) / (h - 1) as f32),
            )
        };
        let (c00, c10) = (texels[w + 1], texels[w + 2]);
        let (p00, p10) = (at(eps, eps), at(1.0 - eps, eps));
        assert!(
            (p00 * c10 - p10 * c00).abs() < 1e-2 * p10.max(p00),
            "{p00} {p10}"
        );
        // Samples land where the density is positive (that they follow it is the χ² of
        // tests/chi2_environment.rs).
        for k in 0..500 {
            let u = Vec2::new(
                ((k as f32 + 0.5) * 0.618_034).fract(),
                (k as f32 + 0.5) / 500.0,
            );
            let drawn = d.sample(u, &img);
            let p = drawn.grid;
            assert!(pdf_at(&d, &img, p) > 0.0, "{u}: {p}");
            // Its cell is where a lookup of the grid point's image coordinates finds it
            // (up to rounding, and a whole turn in u: the last column's cells wrap), and
            // the density it carries is its cell's density there.
            let x = p.x + img.half_texel();
            let found = img.locate(Vec2::new(x - x.floor(), p.y));
            let at = |c: &TexelCell| Vec2::new(c.i as f32, c.j as f32) + c.f;
            let gap = at(&found) - at(&drawn.cell);
            let turns = (gap.x / w as f32).round() * w as f32;
            assert!((gap - Vec2::new(turns, 0.0)).length() < 1e-4, "{u}: {gap}");
            let there = d.pdf(&drawn.cell, &drawn.texels);
            assert_eq!(drawn.pdf.to_bits(), there.to_bits(), "{u}");
        }
        // With an offset, texels at or below it weigh nothing.
        let above = CellDistribution::new(&texels, 3.5, w, h).expect("valid");
        for k in 0..500 {
            let u = Vec2::new(
                ((k as f32 + 0.5) * 0.618_034).fract(),
                (k as f32 + 0.5) / 500.0,
            );
            let p = above.sample(u, &img).grid;
            let x = p * Vec2::new(w as f32, (h - 1) as f32);
            let cell = TexelCell::new(x.x as usize, x.y as usize);
            assert!(img.corners(&cell).iter().any(|t| t.x > 3.5), "{p}");
        }
    }

    /// The polar rows of a tall map keep their weight: the mean of sin θ over a row is
    /// within 10⁻⁴ of its closed form, at the poles too.
    #[test]
    fn tall_maps_keep_their_polar_rows() {
        let (w, h) = (2, 20_001);
        let weights = cell_weights(&vec![1.0; w * h], w, h);
        let dtheta = std::f64::consts::PI / (h - 1) as f64;
        for j in [0, 1, h / 2, h - 3, h - 2] {
            let (t0, t1) = (j as f64 * dtheta, (j + 1) as f64 * dtheta);
            let exact = (t0.cos() - t1.cos()) / dtheta;
            let got = weights[j * w] as f64;
            assert!(
                (got - exact).abs() <= 1e-4 * exact,
                "row {j}: {got} vs {exact}"
            );
        }
    }

    /// A u that hits a CDF entry exactly (its reused number is 0) still gives a point of
    /// positive density inside a cell with zero corners.
    #[test]
    fn numbers_on_cdf_entries_give_points_of_positive_density() {
        let (w, h) = (4, 3);
        let texels = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 3.0, 0.0, 1.0];
        let img = image(w, h, &texels);
        let d = CellDistribution::new(&texels, 0.0, w, h).expect("valid");
        for a in 0..=64 {
            for b in 0..=64 {
                let u = Vec2::new(a as f32, b as f32) / 64.0;
                let p = d.sample(u.min(Vec2::splat(ONE_MINUS_EPSILON)), &img).grid;
                assert!(pdf_at(&d, &img, p) > 0.0, "{u}: {p} has density 0");
            }
        }
    }

    #[test]
    fn an_all_zero_map_is_uniform() {
        let img = image(4, 3, &[0.0; 12]);
        let d = CellDistribution::new(&[0.0; 12], 0.0, 4, 3).expect("valid");
        let p = d.sample(Vec2::new(0.3, 0.6), &img).grid;
        assert!((p - Vec2::new(0.3, 0.6)).length() < 1e-6, "{p}");
        assert!((pdf_at(&d, &img, p) - 1.0).abs() < 1e-6, "{p}");
    }
}
