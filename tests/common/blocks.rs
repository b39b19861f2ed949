//! Per-pixel-block comparison of two renders: the sum of the pixel means in each 16×16
//! block with the variance of that sum (from the films' per-pixel Welford variances), and
//! the z-score of the worst block. Blocks average out pixel noise while keeping bias that
//! is local to a region visible.

use lightlab::image::Film;
use lightlab::math::Spectrum;
use lightlab::render::{RenderSettings, render_quiet};
use lightlab::sampling::SamplerKind;
use lightlab::scene::Scene;

/// Per 16×16 block: the sum of the pixel means (RGB summed) and the variance of that sum.
pub fn blocks(film: &Film) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for by in (0..film.height).step_by(16) {
        for bx in (0..film.width).step_by(16) {
            let (mut m, mut v) = (0f64, 0f64);
            for y in by..(by + 16).min(film.height) {
                for x in bx..(bx + 16).min(film.width) {
                    let p = film.pixel(x, y);
                    m += p.mean.element_sum() as f64;
                    v += p.variance_of_mean().element_sum() as f64;
                }
            }
            out.push((m, v));
        }
    }
    out
}

/// z-scores of `test` against `reference`, block by block.
pub fn block_z(test: &[(f64, f64)], reference: &[(f64, f64)]) -> Vec<f64> {
    test.iter()
        .zip(reference)
        .map(|(a, r)| (a.0 - r.0) / (a.1 + r.1).sqrt().max(1e-9))
        .collect()
}

/// The z-score of largest magnitude (0 for no blocks).
pub fn worst(z: &[f64]) -> f64 {
    z.iter()
        .copied()
        .fold(0f64, |w, z| if z.abs() > w.abs() { z } else { w })
}

/// Per-block variance of the mean of a reference from its per-pixel variances: channels
/// taken as fully correlated (an upper bound), pixels as independent (exact for the box
/// filter).
pub fn block_variances(variance: &[Spectrum], w: u32, h: u32, block: u32) -> Vec<f64> {
    let per_pixel: Vec<Spectrum> = variance
        .iter()
        .map(|v| {
            let sd = v.max(Spectrum::ZERO).to_array().map(f32::sqrt);
            // Var((R + G + B)/3) with fully correlated channels.
            Spectrum::splat(((sd[0] + sd[1] + sd[2]) / 3.0).powi(2))
        })
        .collect();
    // The block mean of n independent pixels: Var = Σ var / n² = (mean var) / n.
    let n = (block * block) as f64;
    block_means(&per_pixel, w, h, block)
        .into_iter()
        .map(|v| v / n)
        .collect()
}

/// Per `block`×`block` means of one image (channels averaged).
pub fn block_means(rgb: &[Spectrum], w: u32, h: u32, block: u32) -> Vec<f64> {
    let (bw, bh) = (w.div_ceil(block), h.div_ceil(block));
    let mut sums = vec![(0.0f64, 0u32); (bw * bh) as usize];
    for y in 0..h {
        for x in 0..w {
            let b = ((y / block) * bw + x / block) as usize;
            sums[b].0 += rgb[(y * w + x) as usize].element_sum() as f64 / 3.0;
            sums[b].1 += 1;
        }
    }
    sums.iter().map(|(s, n)| s / *n as f64).collect()
}

/// `scene` rendered small for a per-block test: 48×32 pixels, `spp` independent samples
/// under `seed`, with `set` changing the settings; every pixel must be finite.
pub fn render_small(
    scene: &Scene,
    spp: u32,
    seed: u64,
    set: impl FnOnce(&mut RenderSettings),
) -> Film {
    let mut s = RenderSettings::for_scene(scene);
    s.spp = spp;
    s.seed = seed;
    s.sampler = SamplerKind::Independent;
    s.resolution = Some((48, 32));
    set(&mut s);
    let film = render_quiet(scene, &s).film;
    assert!(
        film.pixels.iter().all(|p| p.mean.is_finite()),
        "{}: non-finite pixel",
        s.patch()
    );
    film
}
