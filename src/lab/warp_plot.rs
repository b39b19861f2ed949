//! A warp's picture: its samples in the domain's unit parameterisation (for directions
//! that is the (z, φ) cylindrical equal-area projection) beside the observed and
//! expected histograms of its chi-square test, on one shared grey scale.

use image::{Rgb, RgbImage};

use crate::sampling::Rng32;
use crate::sampling::chi2::Chi2Report;
use crate::sampling::registry::Entry;

/// Side of each square panel in pixels.
const PANEL: u32 = 256;
/// Gap between panels.
const GAP: u32 = 8;
/// Samples drawn in the scatter panel.
const SCATTER: usize = 4000;

/// Three panels: scatter of `SCATTER` samples from `seed`, observed histogram, expected
/// histogram (cells scaled to the panel; t₀ runs right, t₁ up).
pub fn warp_plot(entry: &Entry, report: &Chi2Report, seed: u64) -> RgbImage {
    let mut image = RgbImage::from_pixel(3 * PANEL + 2 * GAP, PANEL, Rgb([255, 255, 255]));
    let mut rng = Rng32::new(seed);
    let one_d = entry.domain.is_one_dimensional();
    for k in 0..SCATTER {
        let (x, _) = entry.sample(&mut rng);
        let Some(t) = entry.domain.to_unit(x) else {
            continue;
        };
        // 1D samples are spread vertically by their index so density shows as columns.
        let y = if one_d {
            k as f32 / SCATTER as f32
        } else {
            t.y
        };
        let (px, py) = (
            (t.x * PANEL as f32) as u32,
            PANEL - 1 - ((y * PANEL as f32) as u32).min(PANEL - 1),
        );
        image.put_pixel(px.min(PANEL - 1), py, Rgb([20, 60, 160]));
    }
    let peak = report
        .observed
        .iter()
        .chain(&report.expected)
        .fold(1e-9f64, |a, &b| a.max(b));
    for (panel, grid) in [(1, &report.observed), (2, &report.expected)] {
        draw_histogram(
            &mut image,
            panel * (PANEL + GAP),
            grid,
            report.resolution,
            peak,
        );
    }
    image
}

/// Paints a row-major histogram into the panel starting at column `left`.
fn draw_histogram(image: &mut RgbImage, left: u32, grid: &[f64], [nx, ny]: [usize; 2], peak: f64) {
    for py in 0..PANEL {
        for px in 0..PANEL {
            let i = (px as usize * nx / PANEL as usize).min(nx - 1);
            let j = ((PANEL - 1 - py) as usize * ny / PANEL as usize).min(ny - 1);
            let level = (255.0 * (1.0 - grid[j * nx + i] / peak)).clamp(0.0, 255.0) as u8;
            image.put_pixel(left + px, py, Rgb([level, level, level]));
        }
    }
}
