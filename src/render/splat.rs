//! Splatting with a filter wider than one pixel: each tile adds its samples into a
//! buffer that covers the tile and the filter's reach, and the buffers are merged into
//! the film in tile order (Chan's merge), so the image does not depend on the thread
//! count.

use std::ops::Range;

use glam::{DVec3, Vec2};
use rayon::prelude::*;

use super::Tile;
use super::packets::TileSamples;
use crate::image::filter::{FOOTPRINT_LANES, PreparedFilter};
use crate::image::{Film, Filter, PixelStats};
use crate::math::Spectrum;

/// One round with a filter wider than the one-pixel box: the samples `samples` of every
/// pixel, splatted with the filter's separable weights.
pub(super) fn round_splatted(
    film: &mut Film,
    tiles: &[Tile],
    samples: Range<u32>,
    seed: u64,
    filter: Filter,
    job: &impl TileSamples,
) {
    let (w, h) = (film.width, film.height);
    let reach = filter.radius().ceil() as u32;
    let filter = filter.prepare();
    let results: Vec<(Tile, Vec<Splats>)> = tiles
        .par_iter()
        .map(|&(x0, y0, x1, y1)| {
            let bx0 = x0.saturating_sub(reach);
            let by0 = y0.saturating_sub(reach);
            let (bx1, by1) = ((x1 + reach).min(w), (y1 + reach).min(h));
            let bw = bx1 - bx0;
            let mut buf = vec![Splats::default(); (bw * (by1 - by0)) as usize];
            job.run(
                (x0, y0, x1, y1),
                samples.clone(),
                (seed, w),
                &mut |_, _, p, l| {
                    splat(&mut buf, (bx0, by0, bw), &filter, (w, h), p, l);
                },
            );
            ((bx0, by0, bx1, by1), buf)
        })
        .collect();
    for ((bx0, by0, bx1, _), buf) in results {
        for (i, splats) in buf.into_iter().enumerate() {
            if splats.count == 0 {
                continue;
            }
            let stats = splats.stats();
            let (x, y) = (bx0 + i as u32 % (bx1 - bx0), by0 + i as u32 / (bx1 - bx0));
            let px = &mut film.pixels[(y * w + x) as usize];
            *px = px.merge(&stats);
        }
    }
}

/// Adds the sample (film position `p`, radiance `l`) to every pixel of `buf` (whose
/// pixel (0, 0) is the image's (bx0, by0), rows `bw` wide) that the filter reaches with
/// a positive weight. The weights are evaluated once per axis (the filter is separable).
#[inline]
fn splat(
    buf: &mut [Splats],
    (bx0, by0, bw): (u32, u32, u32),
    filter: &PreparedFilter,
    (w, h): (u32, u32),
    p: Vec2,
    l: Spectrum,
) {
    let mut wx = [0.0f32; FOOTPRINT_LANES];
    let mut wy = [0.0f32; FOOTPRINT_LANES];
    let (xl, nx) = filter.weights(p.x, w, &mut wx);
    let (yl, ny) = filter.weights(p.y, h, &mut wy);
    let x = l.as_dvec3();
    for (j, &wyj) in wy[..ny].iter().enumerate() {
        if wyj <= 0.0 {
            continue;
        }
        let start = ((yl + j as u32 - by0) * bw + xl - bx0) as usize;
        for (cell, &wxk) in buf[start..start + nx].iter_mut().zip(&wx[..nx]) {
            let wt = wyj * wxk;
            if wt > 0.0 {
                cell.add(x, wt);
            }
        }
    }
}

/// Weighted sums of one pixel's splats within a tile and round, in f64 so the variance
/// from sums (M2 = Σw·x² − (Σw·x)²/W) keeps its precision; cheaper per splat than a
/// weighted Welford update, and turned into [`PixelStats`] once per round. The sums sit
/// in one array of eight (W, Σw², Σw·x, Σ(w·x)·x), so that the compiler can add them
/// in two-lane f64 steps.
#[derive(Clone, Copy, Default)]
struct Splats {
    count: u32,
    acc: [f64; 8],
}

impl Splats {
    /// Adds one splat of radiance `x` with weight `w`: the slots gain w, w·w, w·x and
    /// (w·x)·x. The eight terms are formed in registers (an earlier version patched w
    /// into a per-sample array in memory and read it back as vectors, a store-forwarding
    /// stall on every add that made the tent filter 10 % slower).
    #[inline(always)]
    fn add(&mut self, x: DVec3, w: f32) {
        let w = w as f64;
        let wx = w * x;
        let wxx = wx * x;
        let terms = [w, w * w, wx.x, wx.y, wx.z, wxx.x, wxx.y, wxx.z];
        self.count += 1;
        for (acc, t) in self.acc.iter_mut().zip(terms) {
            *acc += t;
        }
    }

    fn stats(&self) -> PixelStats {
        let [w, w2, sx, sy, sz, qx, qy, qz] = self.acc;
        let sum = DVec3::new(sx, sy, sz);
        let sum2 = DVec3::new(qx, qy, qz);
        let mean = sum / w;
        PixelStats {
            count: self.count,
            mean: mean.as_vec3(),
            m2: (sum2 - sum * mean).max(DVec3::ZERO).as_vec3(),
            weight: w as f32,
            weight2: w2 as f32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_are_the_weighted_moments() {
        let mut s = Splats::default();
        let samples = [
            (Spectrum::new(1.0, 2.0, 3.0), 0.5f32),
            (Spectrum::new(3.0, 0.0, 1.0), 0.25),
        ];
        for (l, w) in samples {
            s.add(l.as_dvec3(), w);
        }
        let stats = s.stats();
        assert_eq!(stats.count, 2);
        assert_eq!(stats.weight, 0.75);
        assert_eq!(stats.weight2, 0.3125);
        // Weighted mean (0.5·(1,2,3) + 0.25·(3,0,1)) / 0.75 and Σw(x − mean)².
        let mean = Spectrum::new(5.0 / 3.0, 4.0 / 3.0, 7.0 / 3.0);
        assert!((stats.mean - mean).abs().max_element() < 1e-6);
        let m2 = samples
            .iter()
            .fold(Spectrum::ZERO, |m, &(l, w)| m + w * (l - mean) * (l - mean));
        assert!(
            (stats.m2 - m2).abs().max_element() < 1e-5,
            "{} vs {m2}",
            stats.m2
        );
    }
}
