//! What the packet loop draws ahead for a chunk of one pixel's samples: nothing
//! (`independent`), the Sobol points of the first dimensions (`sobol`) or their
//! stratified cells (`stratified`). The loop is compiled once for each, so that each
//! sampler's loop carries only its own work.

use crate::sampling::sampler::{Cells, PixelStreams, Points};
use crate::sampling::sobol::CHUNK_LANES;
use crate::sampling::{Sampler, SamplerKind};

/// The sampler kind and the render's samples per pixel.
pub(super) type KindSpp = (SamplerKind, u32);

/// One sampler's work ahead: a chunk's rows, and the sampler of one sample made from its
/// row.
pub(super) trait DrawsAhead {
    /// What one sample of the chunk draws ahead.
    type Row: Copy;

    /// The rows of samples `first`, `first` + 1, … (`len` of them) of the pixel whose
    /// streams are `streams`, or `None` where they draw nothing ahead.
    fn chunk(streams: &PixelStreams, first: u32, len: usize) -> Option<[Self::Row; CHUNK_LANES]>;

    /// Sample `s`'s sampler made with its row.
    fn with_row(streams: &PixelStreams, s: u32, kind: KindSpp, row: &Self::Row) -> Sampler;

    /// Sample `s`'s sampler, from its row where there is one.
    #[inline(always)]
    fn sampler(
        streams: &PixelStreams,
        s: u32,
        (kind, spp): KindSpp,
        row: Option<&Self::Row>,
    ) -> Sampler {
        match row {
            Some(row) => Self::with_row(streams, s, (kind, spp), row),
            None => Sampler::for_streams(kind, streams, s, spp),
        }
    }
}

/// Sample `s`'s row among `rows`, the rows [`DrawsAhead::chunk`] drew for the chunk
/// whose first sample is `first` (`s` in the chunk), if it drew any.
#[inline(always)]
pub(super) fn row_of<R>(rows: &Option<[R; CHUNK_LANES]>, first: u32, s: u32) -> Option<&R> {
    rows.as_ref().map(|r| &r[(s - first) as usize])
}

/// Nothing ahead (the independent sampler).
pub(super) struct Nothing;

impl DrawsAhead for Nothing {
    type Row = ();

    #[inline(always)]
    fn chunk(_: &PixelStreams, _: u32, _: usize) -> Option<[(); CHUNK_LANES]> {
        None
    }

    #[inline(always)]
    fn with_row(streams: &PixelStreams, s: u32, (kind, spp): KindSpp, _: &()) -> Sampler {
        Sampler::for_streams(kind, streams, s, spp)
    }
}

/// Sobol points ([`PixelStreams::chunk_points`]).
pub(super) struct SobolPoints;

impl DrawsAhead for SobolPoints {
    type Row = Points;

    #[inline(always)]
    fn chunk(streams: &PixelStreams, first: u32, len: usize) -> Option<[Points; CHUNK_LANES]> {
        streams.chunk_points(first, len)
    }

    #[inline(always)]
    fn with_row(streams: &PixelStreams, s: u32, (kind, spp): KindSpp, p: &Points) -> Sampler {
        Sampler::with_points(kind, streams, s, spp, p)
    }
}

/// Stratified cells ([`PixelStreams::chunk_cells`]).
pub(super) struct StrataCells;

impl DrawsAhead for StrataCells {
    type Row = Cells;

    #[inline(always)]
    fn chunk(streams: &PixelStreams, first: u32, len: usize) -> Option<[Cells; CHUNK_LANES]> {
        streams.chunk_cells(first, len)
    }

    #[inline(always)]
    fn with_row(streams: &PixelStreams, s: u32, (kind, spp): KindSpp, c: &Cells) -> Sampler {
        Sampler::with_cells(kind, streams, s, spp, c)
    }
}
