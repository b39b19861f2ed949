//! Per-sample uniform number sources: `independent` (PCG32), `stratified` (jittered,
//! dimensions decorrelated by permutation) and `sobol` (Owen-scrambled Sobol, Burley 2020,
//! computed by [`super::sobol`] bit for bit as the `sobol_burley` crate computes it).
//!
//! Every stream is derived from (seed, pixel, sample index) alone, so an image is the
//! same whatever the thread count or the split into passes.

use glam::Vec2;

mod chunk;
mod strata;

use super::rng::{HASH_START, Rng32, hash_more, hash_words, mix64};
use super::sobol::{SobolSeed, sobol_1d_seeded, sobol_2d_seeded};
use strata::EqualAreaRows;
pub use strata::{equal_area_cell, permute};

/// A source of uniform numbers in [0, 1). Rejection samplers draw from one of these.
pub trait Uniform {
    /// One uniform number.
    fn next_1d(&mut self) -> f32;
    /// Two uniform numbers meant to be used together (stratified jointly where the
    /// sampler can).
    fn next_2d(&mut self) -> Vec2;
}

impl Uniform for Rng32 {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        self.next_f32()
    }
    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_f32(), self.next_f32())
    }
}

pub use crate::settings::SamplerKind;

/// Sobol points exist for sample indices below 2¹⁶ (the `sobol_burley` crate's limit);
/// later samples fall back to independent numbers.
pub const SOBOL_MAX_SAMPLES: u32 = 1 << 16;

/// Dimensions whose Sobol seeds, or stratified keys, a [`PixelStreams`] hashes once per
/// pixel, and whose points (Sobol) or cells (stratified) the camera packets draw for a
/// chunk of samples at once ([`PixelStreams::chunk_points`],
/// [`PixelStreams::chunk_cells`]): the first four, which the
/// default estimate draws (film position, light choice, light point, BSDF direction).
/// Later dimensions are hashed and drawn per sample.
pub const SEEDED_DIMENSIONS: usize = 4;

/// The part of a pixel's sampler streams that every sample of the pixel shares: its key;
/// for `sobol`, the hashed seeds of its first [`SEEDED_DIMENSIONS`] dimensions (each
/// dimension's seed depends on the pixel alone, Burley 2020 §4), from which
/// [`PixelStreams::chunk_points`] draws a chunk's points without hashing them again for
/// every sample; for `stratified`, the strata's layout for the render's sample count
/// and the permutation keys of the same dimensions, from which
/// [`PixelStreams::chunk_cells`] draws a chunk's cells. [`Sampler::for_streams`], and
/// [`Sampler::with_points`] and [`Sampler::with_cells`] with their chunk's, draw the
/// same numbers as [`Sampler::for_pixel`] with the same key.
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelStreams {
    key: u64,
    /// The hash of a sample's PCG stream with the pixel's key folded in
    /// (`hash_more(HASH_START, key)`): each sample adds only its index.
    sample_hash: u64,
    /// [`SEEDED_DIMENSIONS`] where `sobol` or `cell_keys` holds them, else 0.
    seeded: u32,
    sobol: [SobolSeed; SEEDED_DIMENSIONS],
    /// The strata of `spp` samples (`stratified`; `n` = 0, no layout, otherwise).
    rows: EqualAreaRows,
    /// The permutation key of each seeded dimension (`stratified`), as
    /// [`Sampler::stratified_cell`] derives it from the pixel's key.
    cell_keys: [u32; SEEDED_DIMENSIONS],
}

/// The Sobol points of a sample's first [`SEEDED_DIMENSIONS`] dimensions, which its
/// chunk drew together ([`PixelStreams::chunk_points`]).
pub type Points = [Vec2; SEEDED_DIMENSIONS];

/// The stratified cells of a sample's first [`SEEDED_DIMENSIONS`] dimensions (its index
/// permuted in each), which its chunk drew together ([`PixelStreams::chunk_cells`]). The
/// jitter inside each cell still comes from the sample's PCG stream as it is drawn: a
/// 1D and a 2D draw take one and two numbers of it.
pub type Cells = [u32; SEEDED_DIMENSIONS];

/// What [`Sampler::build`] is given of a sample's first dimensions.
#[derive(Clone, Copy)]
enum Ahead<'a> {
    Nothing,
    Points(&'a Points),
    Cells(&'a Cells),
}

impl PixelStreams {
    /// The streams of pixel `pixel` (a linear index) under `seed` for a sampler of `kind`
    /// drawing `spp` samples per pixel.
    pub fn new(kind: SamplerKind, seed: u64, pixel: u64, spp: u32) -> PixelStreams {
        let key = Sampler::pixel_key(seed, pixel);
        let sobol = kind == SamplerKind::Sobol;
        let strata = kind == SamplerKind::Stratified;
        let keys: [u32; SEEDED_DIMENSIONS] = match sobol || strata {
            true => std::array::from_fn(|d| dimension_key(key, d as u32) as u32),
            false => [0; SEEDED_DIMENSIONS],
        };
        PixelStreams {
            rows: if strata {
                EqualAreaRows::new(spp.max(1))
            } else {
                EqualAreaRows::default()
            },
            seeded: if sobol || strata {
                SEEDED_DIMENSIONS as u32
            } else {
                0
            },
            sobol: std::array::from_fn(|d| match sobol {
                true => SobolSeed::new(keys[d]),
                false => SobolSeed::default(),
            }),
            cell_keys: if strata { keys } else { [0; SEEDED_DIMENSIONS] },
            ..PixelStreams::keyed(key)
        }
    }

    /// The streams of the pixel whose key is `key`, with nothing hashed ahead but the
    /// PCG stream's first round.
    #[inline]
    fn keyed(key: u64) -> PixelStreams {
        PixelStreams {
            key,
            sample_hash: hash_more(HASH_START, key),
            ..PixelStreams::default()
        }
    }

    /// The pixel's key ([`Sampler::pixel_key`]).
    #[inline]
    pub fn key(&self) -> u64 {
        self.key
    }
}

/// The key of dimension `dimension` of the pixel whose key is `pixel_key`.
#[inline(always)]
fn dimension_key(pixel_key: u64, dimension: u32) -> u64 {
    mix64(pixel_key ^ (dimension as u64).wrapping_mul(0x9e37_79b9))
}

/// The uniform numbers of one pixel sample. Each call to `next_*` moves to the next
/// dimension.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SamplerKind,
    /// hash(seed, pixel): the same for every sample of the pixel.
    pixel_key: u64,
    sample_index: u32,
    /// `sample_index.reverse_bits()` (Sobol only: its points take the reversed index, so
    /// it is reversed once per sample rather than once per dimension).
    index_rev: u32,
    dimension: u32,
    rng: Rng32,
    /// The 2D stratification of the sample count's cells (its `n`) and the
    /// permutation's mask (stratified sampler only).
    rows: EqualAreaRows,
    /// The Sobol points of the first `pointed` dimensions, drawn ahead with the rest of
    /// their chunk ([`PixelStreams::chunk_points`]); `pointed` is 0 unless
    /// [`Sampler::with_points`] made a Sobol sampler.
    pointed: u32,
    points: [Vec2; SEEDED_DIMENSIONS],
    /// The stratified cells of the first `celled` dimensions, drawn ahead in the same
    /// way ([`PixelStreams::chunk_cells`]); `celled` is 0 unless [`Sampler::with_cells`]
    /// made a stratified sampler.
    celled: u32,
    cells: [u32; SEEDED_DIMENSIONS],
}

impl Sampler {
    /// The stream for sample `sample_index` (of `spp` in all) of pixel `pixel`
    /// (a linear index) under `seed`.
    pub fn new(kind: SamplerKind, seed: u64, pixel: u64, sample_index: u32, spp: u32) -> Sampler {
        Self::for_pixel(kind, Self::pixel_key(seed, pixel), sample_index, spp)
    }

    /// The key every sample of pixel `pixel` under `seed` shares (hash once per pixel,
    /// not per sample).
    #[inline]
    pub fn pixel_key(seed: u64, pixel: u64) -> u64 {
        hash_words(&[seed, pixel])
    }

    /// [`Sampler::new`] for the pixel whose [`Sampler::pixel_key`] is `pixel_key`.
    #[inline]
    pub fn for_pixel(kind: SamplerKind, pixel_key: u64, sample_index: u32, spp: u32) -> Sampler {
        Self::for_streams(kind, &PixelStreams::keyed(pixel_key), sample_index, spp)
    }

    /// [`Sampler::for_pixel`] for the pixel whose streams are `streams` (made for the
    /// same `kind`). Every Sobol dimension is hashed as it is drawn (three hashes each):
    /// a hot path takes [`Sampler::with_points`] (or, stratified, [`Sampler::with_cells`]),
    /// which use the pixel's seeds (keys).
    #[inline]
    pub fn for_streams(
        kind: SamplerKind,
        streams: &PixelStreams,
        sample_index: u32,
        spp: u32,
    ) -> Sampler {
        Self::build(kind, streams, sample_index, spp, Ahead::Nothing)
    }

    /// [`Sampler::for_streams`] with what its first [`SEEDED_DIMENSIONS`] dimensions
    /// draw given: `points`, this sample's row of its chunk's
    /// [`PixelStreams::chunk_points`] (the same numbers, computed together).
    #[inline]
    pub fn with_points(
        kind: SamplerKind,
        streams: &PixelStreams,
        sample_index: u32,
        spp: u32,
        points: &Points,
    ) -> Sampler {
        Self::build(kind, streams, sample_index, spp, Ahead::Points(points))
    }

    /// [`Sampler::for_streams`] with the cells of its first [`SEEDED_DIMENSIONS`]
    /// dimensions given: `cells`, this sample's row of its chunk's
    /// [`PixelStreams::chunk_cells`] (the same cells, computed together).
    #[inline]
    pub fn with_cells(
        kind: SamplerKind,
        streams: &PixelStreams,
        sample_index: u32,
        spp: u32,
        cells: &Cells,
    ) -> Sampler {
        Self::build(kind, streams, sample_index, spp, Ahead::Cells(cells))
    }

    #[inline(always)]
    fn build(
        kind: SamplerKind,
        streams: &PixelStreams,
        sample_index: u32,
        spp: u32,
        ahead: Ahead<'_>,
    ) -> Sampler {
        let pixel_key = streams.key;
        let kind = match kind {
            SamplerKind::Sobol if sample_index >= SOBOL_MAX_SAMPLES => SamplerKind::Independent,
            SamplerKind::Stratified if sample_index >= spp => SamplerKind::Independent,
            k => k,
        };
        // The pixel's layout (and its chunk's cells) where its streams have one for
        // this count.
        let laid_out = kind == SamplerKind::Stratified && streams.rows.n == spp.max(1);
        // The first dimensions' points (Sobol) or cells (stratified) from the chunk,
        // where given; otherwise every dimension is hashed as it is drawn.
        let none = (
            0,
            [Vec2::ZERO; SEEDED_DIMENSIONS],
            0,
            [0; SEEDED_DIMENSIONS],
        );
        let (pointed, points, celled, cells) = match ahead {
            Ahead::Points(p) if kind == SamplerKind::Sobol => (streams.seeded, *p, 0, none.3),
            Ahead::Cells(c) if laid_out => (0, none.1, streams.seeded, *c),
            _ => none,
        };
        Sampler {
            kind,
            pixel_key,
            sample_index,
            index_rev: if kind == SamplerKind::Sobol {
                sample_index.reverse_bits()
            } else {
                0
            },
            rows: match kind {
                _ if laid_out => streams.rows,
                SamplerKind::Stratified => EqualAreaRows::new(spp.max(1)),
                _ => EqualAreaRows::UNUSED,
            },
            dimension: 0,
            // Sobol points draw nothing from the PCG stream: skip its three hashes
            // (a quarter of the set-up cost of a sample).
            rng: if kind == SamplerKind::Sobol {
                Rng32::unused()
            } else {
                // hash_words(&[pixel_key, sample_index]), the key folded in already.
                Rng32::new(hash_more(streams.sample_hash, sample_index as u64))
            },
            pointed,
            points,
            celled,
            cells,
        }
    }

    /// The sampler kind actually in use for this sample (after fall-backs).
    pub fn kind(&self) -> SamplerKind {
        self.kind
    }

    #[inline]
    fn dimension_key(&mut self) -> u64 {
        let key = dimension_key(self.pixel_key, self.dimension);
        self.dimension += 1;
        key
    }

    /// The stratum of this sample in a 1D or 2D pattern of the sample count's cells
    /// (drawn ahead for the first `celled` dimensions).
    #[inline]
    fn stratified_cell(&mut self) -> u32 {
        let d = self.dimension;
        if d < self.celled {
            self.dimension = d + 1;
            // d < celled ≤ SEEDED_DIMENSIONS: the mask only spares a bounds check.
            return self.cells[d as usize & (SEEDED_DIMENSIONS - 1)];
        }
        let key = self.dimension_key();
        self.rows.permute(self.sample_index, key as u32)
    }
}

impl Uniform for Sampler {
    #[inline(always)]
    fn next_1d(&mut self) -> f32 {
        // A pair drawn ahead gives its first number (`sobol_1d` is the pair's x).
        match self.ahead() {
            Some(p) => p.x,
            None => self.draw_1d(),
        }
    }

    #[inline(always)]
    fn next_2d(&mut self) -> Vec2 {
        match self.ahead() {
            Some(p) => p,
            None => self.draw_2d(),
        }
    }
}

impl Sampler {
    /// The next dimension's Sobol point, where it was drawn ahead: a few instructions
    /// inlined where it is drawn, where a call and a match on the kind cost more
    /// (README render: 2 % of all instructions).
    #[inline(always)]
    fn ahead(&mut self) -> Option<Vec2> {
        const _: () = assert!(SEEDED_DIMENSIONS.is_power_of_two());
        let d = self.dimension;
        (d < self.pointed).then(|| {
            self.dimension = d + 1;
            // d < pointed ≤ SEEDED_DIMENSIONS: the mask only spares a bounds check.
            self.points[d as usize & (SEEDED_DIMENSIONS - 1)]
        })
    }

    #[inline]
    fn draw_1d(&mut self) -> f32 {
        match self.kind {
            SamplerKind::Independent => self.rng.next_f32(),
            SamplerKind::Stratified => {
                let cell = self.stratified_cell();
                let jitter = self.rng.next_f32();
                self.rows.line(cell, jitter)
            }
            SamplerKind::Sobol => {
                // Padding by reseeding (Burley 2020 §4): dimension 0 of a fresh
                // shuffled, scrambled sequence for every 1D request.
                let seed = SobolSeed::new(self.dimension_key() as u32);
                sobol_1d_seeded(self.index_rev, &seed)
            }
        }
    }

    #[inline]
    fn draw_2d(&mut self) -> Vec2 {
        match self.kind {
            SamplerKind::Independent => Vec2::new(self.rng.next_f32(), self.rng.next_f32()),
            SamplerKind::Stratified => {
                let cell = self.stratified_cell();
                let jitter = Vec2::new(self.rng.next_f32(), self.rng.next_f32());
                self.rows.cell(cell, jitter)
            }
            SamplerKind::Sobol => {
                // Dimensions 0 and 1 of Sobol form a (0,2)-sequence: every 2D request
                // uses that pair under its own seed.
                let seed = SobolSeed::new(self.dimension_key() as u32);
                sobol_2d_seeded(self.index_rev, &seed)
            }
        }
    }
}

/// The largest `f32` below one.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests;
