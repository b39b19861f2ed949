//! Splatting with a filter wider than one pixel: each tile adds its samples into a
//! buffer that covers the tile and the filter's reach, and the buffers are merged into
//! the film in tile order (Chan's merge), so the image does not depend on the thread
//! count.

use std::ops::Range;

use glam::{DVec3, Vec2, Vec4};
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
    let lanes = Lanes::detect();
    let results: Vec<SplatBuffer> = tiles
        .par_iter()
        .map(|&tile| {
            let mut buf = SplatBuffer::around(tile, reach, (w, h));
            job.run(tile, samples.clone(), (seed, w), &mut |_, _, p, l| {
                buf.splat(lanes, &filter, (w, h), p, l)
            });
            buf
        })
        .collect();
    for buf in results {
        for i in 0..buf.cells {
            if buf.count[i] == 0 {
                continue;
            }
            let stats = buf.stats(i);
            let (x, y) = (buf.x0 + i as u32 % buf.width, buf.y0 + i as u32 / buf.width);
            let px = &mut film.pixels[(y * w + x) as usize];
            *px = px.merge(&stats);
        }
    }
}

/// The vector width the splat may use: AVX2 (four f64 lanes for the sums) only where
/// [`Lanes::detect`] found it on this processor; the field is private, so no other
/// value with AVX2 can be made.
#[derive(Clone, Copy, Debug)]
struct Lanes {
    avx2: bool,
}

impl Lanes {
    /// The baseline (SSE2 on x86-64), which every processor has.
    #[cfg(test)]
    const BASELINE: Lanes = Lanes { avx2: false };

    /// What this processor has, detected at run time.
    fn detect() -> Lanes {
        #[cfg(target_arch = "x86_64")]
        let avx2 = std::arch::is_x86_feature_detected!("avx2");
        #[cfg(not(target_arch = "x86_64"))]
        let avx2 = false;
        Lanes { avx2 }
    }
}

/// Weighted sums of the splats within a tile and round, for the pixels the tile's filter
/// reaches, in f64 so the variance from sums (M2 = Σw·x² − (Σw·x)²/W) keeps its
/// precision; cheaper per splat than a weighted Welford update, and turned into
/// [`PixelStats`] once per round. The sums lie plane by plane (W, Σw², Σw·x per channel,
/// Σ(w·x)·x per channel: [`PLANES`] arrays of the cells), so that a row of the filter's
/// footprint adds to four neighbouring cells of each plane in one vector step. (Cell by
/// cell, the eight sums of a cell had to be gathered into vectors from scalars on every
/// splat.)
struct SplatBuffer {
    /// The image pixel of cell 0.
    x0: u32,
    y0: u32,
    /// Cells per row.
    width: u32,
    /// Cells in use (rows × `width`); each plane has [`PAD`] more.
    cells: usize,
    /// Splats of positive weight per cell.
    count: Vec<u32>,
    /// The [`PLANES`] planes, each `cells + PAD` long.
    sums: Vec<f64>,
}

// `add_rows`'s bounds check relies on a 64-bit usize (x86-64 and aarch64 have one).
const _: () = assert!(usize::BITS == 64);

/// Sums per cell: W, Σw², Σw·x (r, g, b), Σ(w·x)·x (r, g, b).
const PLANES: usize = 8;

/// Cells past the last one in each plane: a footprint row is added in groups of four
/// lanes, and its last group may reach past the footprint (with zero weights there, so
/// the cells it touches, to the right in the same row, in the next row or these, keep
/// their sums). Three would do.
const PAD: usize = 4;

impl SplatBuffer {
    /// Empty sums for the pixels that samples in `tile` reach with a filter of radius
    /// at most `reach` pixels, in an image of `w` × `h` pixels: the tile widened by
    /// `reach` on each side, within the image.
    fn around((x0, y0, x1, y1): Tile, reach: u32, (w, h): (u32, u32)) -> Self {
        Self::new((
            x0.saturating_sub(reach),
            y0.saturating_sub(reach),
            (x1 + reach).min(w),
            (y1 + reach).min(h),
        ))
    }

    /// Empty sums for the pixels [x0, x1) × [y0, y1).
    fn new((x0, y0, x1, y1): Tile) -> Self {
        let cells = ((x1 - x0) * (y1 - y0)) as usize;
        Self {
            x0,
            y0,
            width: x1 - x0,
            cells,
            count: vec![0; cells + PAD],
            sums: vec![0.0; PLANES * (cells + PAD)],
        }
    }

    /// Length of each plane.
    fn stride(&self) -> usize {
        self.cells + PAD
    }

    /// Adds the sample (film position `p`, radiance `l`) to every cell that the filter
    /// reaches with a positive weight, in an image of `w` × `h` pixels, with the vector
    /// width `lanes`. `l` must be finite (the renderer scores a non-finite estimate as
    /// zero before it gets here, `CameraPackets::counted`): the lanes of zero weight
    /// add 0 · l, which is zero only for finite `l`.
    #[inline(always)]
    fn splat(
        &mut self,
        lanes: Lanes,
        filter: &PreparedFilter,
        size: (u32, u32),
        p: Vec2,
        l: Spectrum,
    ) {
        debug_assert!(l.is_finite(), "splatted radiance {l}");
        #[cfg(target_arch = "x86_64")]
        if lanes.avx2 {
            // SAFETY: `Lanes` has AVX2 only where `Lanes::detect` found it on this
            // processor.
            unsafe { self.splat_avx2(filter, size, p, l) };
            return;
        }
        // The same code either way (adds and products, no fused multiply–add), so the
        // sums are bit for bit the same with and without AVX2.
        let _ = lanes;
        self.splat_lanes(filter, size, p, l);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn splat_avx2(&mut self, filter: &PreparedFilter, size: (u32, u32), p: Vec2, l: Spectrum) {
        self.splat_lanes(filter, size, p, l);
    }

    /// [`splat`](Self::splat)'s body. The weights are evaluated once per axis (the
    /// filter is separable); each cell gains w, w², w·x and (w·x)·x with w = w_y·w_x.
    /// A sample of radiance zero (every channel ±0: a ray that saw nothing, or a
    /// shadowed point) adds only w and w²: its other terms are ±0, and adding ±0 leaves
    /// every sum as it was, bit for bit, since no sum is ever −0 (each starts at +0, and
    /// in round-to-nearest a + b is −0 only where a and b both are).
    #[inline(always)]
    fn splat_lanes(&mut self, filter: &PreparedFilter, (w, h): (u32, u32), p: Vec2, l: Spectrum) {
        if l == Spectrum::ZERO {
            self.splat_sums::<false>(filter, (w, h), p, DVec3::ZERO);
        } else {
            self.splat_sums::<true>(filter, (w, h), p, l.as_dvec3());
        }
    }

    /// [`splat_lanes`](Self::splat_lanes) for radiance `x`, all eight sums where `LIT`,
    /// else only w and w² (for `x` zero).
    #[inline(always)]
    fn splat_sums<const LIT: bool>(
        &mut self,
        filter: &PreparedFilter,
        (w, h): (u32, u32),
        p: Vec2,
        x: DVec3,
    ) {
        // Lanes past the footprint add nothing (the filter's values further on are
        // positive where the footprint was cut at the image's edge).
        if let Some((((xl, nx), (yl, ny)), ex, ey)) = filter.weights_xy4(p, (w, h)) {
            // Both footprints fit four lanes (the common case): the weights stay in
            // registers, one group of four cells per row. A filter narrower than half a
            // pixel may reach none.
            if nx == 0 {
                return;
            }
            let inside = Vec4::new(0.0, 1.0, 2.0, 3.0).cmplt(Vec4::splat(nx as f32));
            let wx = Vec4::select(inside, ex, Vec4::ZERO).to_array();
            self.add_rows::<LIT>((xl, yl), &wx, &ey.to_array()[..ny], x);
            return;
        }
        let mut wx = [0.0f32; FOOTPRINT_LANES];
        let mut wy = [0.0f32; FOOTPRINT_LANES];
        let ((xl, nx), (yl, ny)) = (
            filter.weights(p.x, w, &mut wx),
            filter.weights(p.y, h, &mut wy),
        );
        wx[nx..].fill(0.0);
        self.add_rows::<LIT>((xl, yl), &wx[..nx.next_multiple_of(4)], &wy[..ny], x);
    }

    /// Adds w = `wy[j]`·`wx[i]` and its products with `x` (where `LIT`, else w and w²
    /// alone) to the cell of pixel (`xl` + i, `yl` + j), in groups of four lanes (`wx`'s
    /// length is a multiple of four; zero weights past the footprint).
    #[inline(always)]
    fn add_rows<const LIT: bool>(
        &mut self,
        (xl, yl): (u32, u32),
        wx: &[f32],
        wy: &[f32],
        x: DVec3,
    ) {
        let stride = self.stride();
        let Self {
            x0,
            y0,
            width,
            count,
            sums,
            ..
        } = self;
        // Every plane is `stride` long: a group of cells checked to lie within `stride`
        // lies within each plane.
        assert!(sums.len() == PLANES * stride && count.len() == stride);
        for (j, &wyj) in wy.iter().enumerate() {
            if wyj <= 0.0 {
                continue;
            }
            let row = ((yl + j as u32 - *y0) * *width + xl - *x0) as usize;
            for (g, wx4) in wx.chunks_exact(4).enumerate() {
                let at = row + 4 * g;
                // `at` < 2³² + 40 (from u32 rows), so `at + 4` cannot wrap (usize is 64
                // bits, below).
                let end = at + 4;
                assert!(end <= stride, "a footprint beyond the tile's buffer");
                let wt: [f64; 4] = std::array::from_fn(|k| (wyj * wx4[k]) as f64);
                let adds: [[f64; 4]; PLANES] = [
                    wt,
                    wt.map(|w| w * w),
                    wt.map(|w| w * x.x),
                    wt.map(|w| w * x.y),
                    wt.map(|w| w * x.z),
                    wt.map(|w| (w * x.x) * x.x),
                    wt.map(|w| (w * x.y) * x.y),
                    wt.map(|w| (w * x.z) * x.z),
                ];
                let used = if LIT { PLANES } else { 2 };
                for (k, add) in adds.iter().enumerate().take(used) {
                    let cells = k * stride + at..k * stride + end;
                    // SAFETY: k < PLANES (`adds` has PLANES rows) and end ≤ stride
                    // (checked once per group rather than once per plane), so `cells`
                    // lies within `sums`, PLANES × stride long (asserted above).
                    let group = unsafe { sums.get_unchecked_mut(cells) };
                    for (sum, t) in group.iter_mut().zip(add) {
                        *sum += t;
                    }
                }
                for (n, &w) in count[at..end].iter_mut().zip(&wt) {
                    *n += (w > 0.0) as u32;
                }
            }
        }
    }

    /// Cell `i`'s sums as pixel statistics.
    fn stats(&self, i: usize) -> PixelStats {
        let stride = self.stride();
        let [w, w2, sx, sy, sz, qx, qy, qz]: [f64; PLANES] =
            std::array::from_fn(|k| self.sums[k * stride + i]);
        let sum = DVec3::new(sx, sy, sz);
        let sum2 = DVec3::new(qx, qy, qz);
        let mean = sum / w;
        PixelStats {
            count: self.count[i],
            mean: mean.as_vec3(),
            m2: (sum2 - sum * mean).max(DVec3::ZERO).as_vec3(),
            weight: w as f32,
            weight2: w2 as f32,
        }
    }
}

#[cfg(test)]
mod tests;
