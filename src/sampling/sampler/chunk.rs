//! What the camera packets draw ahead for a chunk of one pixel's samples: the Sobol
//! points, or the stratified cells, of their first [`SEEDED_DIMENSIONS`] dimensions,
//! eight samples at a time in AVX2 lanes where the processor has them.

use super::{Cells, PixelStreams, Points, SEEDED_DIMENSIONS, SOBOL_MAX_SAMPLES};
use crate::sampling::sobol::{CHUNK_LANES, chunk_is_wide, sobol_2d_chunk, sobol_2d_seeded};

impl PixelStreams {
    /// The Sobol points of the first [`SEEDED_DIMENSIONS`] dimensions of samples
    /// `first`, `first` + 1, … (`len` ≤ [`CHUNK_LANES`] of them), for
    /// [`Sampler::with_points`](super::Sampler::with_points): computed together
    /// ([`sobol_2d_chunk`]) where that pays (a whole chunk, or two samples and more where
    /// the lanes are AVX2's), else sample by sample from the pixel's seeds. `None` unless
    /// the streams are Sobol's and the first sample has Sobol points (past
    /// [`SOBOL_MAX_SAMPLES`] samples fall back to independent numbers).
    #[inline]
    pub fn chunk_points(&self, first: u32, len: usize) -> Option<[Points; CHUNK_LANES]> {
        self.chunk_points_in(first, len, chunk_is_wide())
    }

    /// [`PixelStreams::chunk_points`] with the lanes' width given (`wide`: AVX2's).
    #[inline(always)]
    pub(super) fn chunk_points_in(
        &self,
        first: u32,
        len: usize,
        wide: bool,
    ) -> Option<[Points; CHUNK_LANES]> {
        if self.seeded != SEEDED_DIMENSIONS as u32 || self.rows.n != 0 || first >= SOBOL_MAX_SAMPLES
        {
            return None;
        }
        if len >= CHUNK_LANES || (len >= 2 && wide) {
            return Some(sobol_2d_chunk(first, &self.sobol));
        }
        // Sample by sample, up to Sobol's last index (later samples take none).
        let len = len.min((SOBOL_MAX_SAMPLES - first) as usize);
        let mut points = [Points::default(); CHUNK_LANES];
        for (l, row) in points.iter_mut().enumerate().take(len) {
            let index_rev = first.wrapping_add(l as u32).reverse_bits();
            *row = std::array::from_fn(|d| sobol_2d_seeded(index_rev, &self.sobol[d]));
        }
        Some(points)
    }

    /// The stratified cells of the first [`SEEDED_DIMENSIONS`] dimensions of samples
    /// `first`, `first` + 1, … (`len` ≤ [`CHUNK_LANES`] of them), for
    /// [`Sampler::with_cells`](super::Sampler::with_cells): eight samples at a time in
    /// AVX2 lanes where the sample count is a power of two and the chunk holds two
    /// samples or more, else sample by sample from the pixel's keys (a sample past the
    /// count draws independent numbers and takes no cells). `None` unless the streams
    /// are the stratified sampler's.
    #[inline]
    pub fn chunk_cells(&self, first: u32, len: usize) -> Option<[Cells; CHUNK_LANES]> {
        self.chunk_cells_in(first, len, chunk_is_wide())
    }

    /// [`PixelStreams::chunk_cells`] with the lanes' width given (`wide`: AVX2's).
    #[inline(always)]
    pub(super) fn chunk_cells_in(
        &self,
        first: u32,
        len: usize,
        wide: bool,
    ) -> Option<[Cells; CHUNK_LANES]> {
        if self.seeded != SEEDED_DIMENSIONS as u32 || self.rows.n == 0 {
            return None;
        }
        Some(self.rows.permute_chunk(first, len, &self.cell_keys, wide))
    }
}
