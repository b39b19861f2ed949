//! Per-sample uniform number sources: `independent` (PCG32), `stratified` (jittered,
//! dimensions decorrelated by permutation) and `sobol` (Owen-scrambled Sobol, Burley 2020,
//! computed by [`super::sobol`] bit for bit as the `sobol_burley` crate computes it).
//!
//! Every stream is derived from (seed, pixel, sample index) alone, so an image is the
//! same whatever the thread count or the split into passes.

use glam::Vec2;

use super::rng::{HASH_START, Rng32, hash_more, hash_words, mix64};
use super::sobol::{SobolSeed, sobol_1d_seeded, sobol_2d_seeded};

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

/// Dimensions whose Sobol seeds a [`PixelStreams`] hashes once per pixel: the first four,
/// which the default estimate draws (film position, light choice, light point, BSDF
/// direction). Later dimensions are hashed per sample.
pub const SEEDED_DIMENSIONS: usize = 4;

/// The part of a pixel's sampler streams that every sample of the pixel shares: its key;
/// for `sobol`, the hashed seeds of its first [`SEEDED_DIMENSIONS`] dimensions (each
/// dimension's seed depends on the pixel alone, Burley 2020 §4, so its three hashes need
/// not be redone for every sample); for `stratified`, the strata's layout for the
/// render's sample count. [`Sampler::for_streams`] draws the same numbers as
/// [`Sampler::for_pixel`] with the same key.
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelStreams {
    key: u64,
    /// The hash of a sample's PCG stream with the pixel's key folded in
    /// (`hash_more(HASH_START, key)`): each sample adds only its index.
    sample_hash: u64,
    seeded: u32,
    sobol: [SobolSeed; SEEDED_DIMENSIONS],
    /// The strata of `spp` samples (`stratified`; `n` = 0, no layout, otherwise).
    rows: EqualAreaRows,
}

impl PixelStreams {
    /// The streams of pixel `pixel` (a linear index) under `seed` for a sampler of `kind`
    /// drawing `spp` samples per pixel.
    pub fn new(kind: SamplerKind, seed: u64, pixel: u64, spp: u32) -> PixelStreams {
        let key = Sampler::pixel_key(seed, pixel);
        let sobol = kind == SamplerKind::Sobol;
        PixelStreams {
            rows: if kind == SamplerKind::Stratified {
                EqualAreaRows::new(spp.max(1))
            } else {
                EqualAreaRows::default()
            },
            seeded: if sobol { SEEDED_DIMENSIONS as u32 } else { 0 },
            sobol: std::array::from_fn(|d| {
                if sobol {
                    SobolSeed::new(dimension_key(key, d as u32) as u32)
                } else {
                    SobolSeed::default()
                }
            }),
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
    spp: u32,
    dimension: u32,
    rng: Rng32,
    /// The 2D stratification of `spp` cells and the permutation's mask (stratified
    /// sampler only).
    rows: EqualAreaRows,
    /// The hashed Sobol seeds of the first `seeded` dimensions (see [`PixelStreams`]).
    seeded: u32,
    sobol: [SobolSeed; SEEDED_DIMENSIONS],
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
    /// same `kind`), with its seeds hashed already.
    #[inline]
    pub fn for_streams(
        kind: SamplerKind,
        streams: &PixelStreams,
        sample_index: u32,
        spp: u32,
    ) -> Sampler {
        let pixel_key = streams.key;
        let kind = match kind {
            SamplerKind::Sobol if sample_index >= SOBOL_MAX_SAMPLES => SamplerKind::Independent,
            SamplerKind::Stratified if sample_index >= spp => SamplerKind::Independent,
            k => k,
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
            spp: spp.max(1),
            rows: match kind {
                // The pixel's layout where its streams have one for this count.
                SamplerKind::Stratified if streams.rows.n == spp.max(1) => streams.rows,
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
            seeded: if kind == SamplerKind::Sobol {
                streams.seeded
            } else {
                0
            },
            sobol: streams.sobol,
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

    /// The hashed Sobol seed of the next dimension: from the pixel's streams where they
    /// hold it, else hashed here.
    #[inline(always)]
    fn sobol_seed(&mut self) -> SobolSeed {
        let d = self.dimension;
        if d < self.seeded {
            self.dimension += 1;
            self.sobol[d as usize]
        } else {
            SobolSeed::new(self.dimension_key() as u32)
        }
    }

    /// The jittered stratum of this sample in a 1D or 2D pattern of `spp` cells.
    fn stratified_cell(&mut self) -> (u32, u64) {
        let key = self.dimension_key();
        (self.rows.permute(self.sample_index, key as u32), key)
    }
}

impl Uniform for Sampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        match self.kind {
            SamplerKind::Independent => self.rng.next_f32(),
            SamplerKind::Stratified => {
                let (cell, _) = self.stratified_cell();
                let jitter = self.rng.next_f32();
                ((cell as f32 + jitter) / self.spp as f32).min(ONE_MINUS_EPSILON)
            }
            SamplerKind::Sobol => {
                // Padding by reseeding (Burley 2020 §4): dimension 0 of a fresh
                // shuffled, scrambled sequence for every 1D request.
                let seed = self.sobol_seed();
                sobol_1d_seeded(self.index_rev, &seed)
            }
        }
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        match self.kind {
            SamplerKind::Independent => Vec2::new(self.rng.next_f32(), self.rng.next_f32()),
            SamplerKind::Stratified => {
                let (cell, _) = self.stratified_cell();
                let jitter = Vec2::new(self.rng.next_f32(), self.rng.next_f32());
                self.rows.cell(cell, jitter)
            }
            SamplerKind::Sobol => {
                // Dimensions 0 and 1 of Sobol form a (0,2)-sequence: every 2D request
                // uses that pair under its own seed.
                let seed = self.sobol_seed();
                sobol_2d_seeded(self.index_rev, &seed)
            }
        }
    }
}

/// The largest `f32` below one.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// A point jittered inside cell `cell` of `n` equal-area cells that tile the unit square:
/// ⌊√n⌋ rows, each cut into as many cells as its share of `n`, with row heights
/// proportional to their cell counts so that every cell has area 1/n. For square `n`
/// this is the usual jittered grid.
pub fn equal_area_cell(cell: u32, n: u32, jitter: Vec2) -> Vec2 {
    EqualAreaRows::new(n).cell(cell, jitter)
}

/// The strata of `n` samples: the row layout of [`equal_area_cell`] (a square root and
/// two integer divisions) and [`permute`]'s bit mask, computed once per pixel
/// ([`PixelStreams`]) rather than once per sample and per dimension.
#[derive(Clone, Copy, Debug, Default)]
struct EqualAreaRows {
    n: u32,
    base: u32,
    extra: u32,
    /// [`permutation_mask`] of `n`.
    mask: u32,
}

impl EqualAreaRows {
    /// A placeholder for samplers that do not stratify.
    const UNUSED: EqualAreaRows = EqualAreaRows {
        n: 1,
        base: 1,
        extra: 0,
        mask: 0,
    };

    fn new(n: u32) -> EqualAreaRows {
        let rows = (n as f32).sqrt() as u32;
        let rows = rows.clamp(1, n.max(1));
        EqualAreaRows {
            n,
            base: n / rows,
            extra: n % rows,
            mask: permutation_mask(n),
        }
    }

    /// [`equal_area_cell`] of `cell` in this layout.
    #[inline]
    fn cell(&self, cell: u32, jitter: Vec2) -> Vec2 {
        let EqualAreaRows { n, base, extra, .. } = *self;
        equal_area_cell_in(cell, n, base, extra, jitter)
    }

    /// [`permute`] of `i` among the `n` samples under `seed`.
    #[inline]
    fn permute(&self, i: u32, seed: u32) -> u32 {
        permute_masked(i, self.n, self.mask, seed)
    }
}

/// [`equal_area_cell`] with the layout given: `base` cells per row, the first `extra`
/// rows one more.
#[inline]
fn equal_area_cell_in(cell: u32, n: u32, base: u32, extra: u32, jitter: Vec2) -> Vec2 {
    // Rows 0..extra hold base + 1 cells, the rest hold base.
    let (row, col, before) = if cell < extra * (base + 1) {
        let r = cell / (base + 1);
        (r, cell % (base + 1), r * (base + 1))
    } else {
        let c = cell - extra * (base + 1);
        let r = extra + c / base;
        (r, c % base, extra * (base + 1) + (r - extra) * base)
    };
    let cells_in_row = if row < extra { base + 1 } else { base };
    let y0 = before as f32 / n as f32;
    let height = cells_in_row as f32 / n as f32;
    Vec2::new(
        ((col as f32 + jitter.x) / cells_in_row as f32).min(ONE_MINUS_EPSILON),
        (y0 + jitter.y * height).min(ONE_MINUS_EPSILON),
    )
}

/// A pseudo-random permutation of 0..n evaluated at `i` (Kensler 2013, "Correlated
/// Multi-Jittered Sampling", Pixar TM 13-01): a hashed bijection on the next power of
/// two, cycle-walked back into range.
pub fn permute(i: u32, n: u32, seed: u32) -> u32 {
    permute_masked(i, n, permutation_mask(n), seed)
}

/// [`permute`]'s bit mask for `n` samples: n − 1's highest bit and every bit below it
/// (0 for n ≤ 1).
fn permutation_mask(n: u32) -> u32 {
    match n.saturating_sub(1) {
        0 => 0,
        m => u32::MAX >> m.leading_zeros(),
    }
}

/// [`permute`] with its mask `w` (n − 1's highest bit and the bits below) given.
#[inline]
fn permute_masked(mut i: u32, n: u32, w: u32, seed: u32) -> u32 {
    if n <= 1 {
        return 0;
    }
    loop {
        i = kensler_hash(i, w, seed);
        if i < n {
            break;
        }
    }
    let i = i.wrapping_add(seed);
    // n a power of two (the usual sample counts): the remainder is the low bits.
    if n & w == 0 { i & w } else { i % n }
}

/// One round of Kensler's hash: a bijection on the integers below the power of two
/// `w` + 1, keyed by `seed` ([`permute`] walks it until the value falls below n).
#[inline(always)]
fn kensler_hash(mut i: u32, w: u32, seed: u32) -> u32 {
    i ^= seed;
    i = i.wrapping_mul(0xe170_893d);
    i ^= seed >> 16;
    i ^= (i & w) >> 4;
    i ^= seed >> 8;
    i = i.wrapping_mul(0x0929_eb3f);
    i ^= seed >> 23;
    i ^= (i & w) >> 1;
    i = i.wrapping_mul(1 | seed >> 27);
    i = i.wrapping_mul(0x6935_fa69);
    i ^= (i & w) >> 11;
    i = i.wrapping_mul(0x74dc_b303);
    i ^= (i & w) >> 2;
    i = i.wrapping_mul(0x9e50_1cc3);
    i ^= (i & w) >> 2;
    i = i.wrapping_mul(0xc860_a3df);
    i &= w;
    i ^ (i >> 5)
}

#[cfg(test)]
mod tests;
