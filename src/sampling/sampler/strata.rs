//! Strata for the `stratified` sampler: equal-area cells of the unit square and
//! Kensler's hashed permutations, which give each dimension its own order of the cells.

use glam::Vec2;

use super::ONE_MINUS_EPSILON;
use crate::sampling::sobol::CHUNK_LANES;

/// A point jittered inside cell `cell` of `n` equal-area cells that tile the unit square:
/// ⌊√n⌋ rows, each cut into as many cells as its share of `n`, with row heights
/// proportional to their cell counts so that every cell has area 1/n. For square `n`
/// this is the usual jittered grid.
pub fn equal_area_cell(cell: u32, n: u32, jitter: Vec2) -> Vec2 {
    EqualAreaRows::new(n).cell(cell, jitter)
}

/// The strata of `n` samples: the row layout of [`equal_area_cell`] (a square root and
/// two integer divisions) and [`permute`]'s bit mask, computed once per pixel
/// ([`PixelStreams`](super::PixelStreams)) rather than once per sample and per dimension.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct EqualAreaRows {
    pub(super) n: u32,
    pub(super) base: u32,
    pub(super) extra: u32,
    /// [`permutation_mask`] of `n`.
    mask: u32,
}

/// 2⁻ᵏ, exactly (k ≤ 126): the reciprocal of a power of two, built from its exponent.
#[inline(always)]
fn exp2_neg(k: u32) -> f32 {
    f32::from_bits((127 - k) << 23)
}

impl EqualAreaRows {
    /// A placeholder for samplers that do not stratify.
    pub(super) const UNUSED: EqualAreaRows = EqualAreaRows {
        n: 1,
        base: 1,
        extra: 0,
        mask: 0,
    };

    pub(super) fn new(n: u32) -> EqualAreaRows {
        let rows = (n as f32).sqrt() as u32;
        let rows = rows.clamp(1, n.max(1));
        let (base, extra) = (n / rows, n % rows);
        EqualAreaRows {
            n,
            base,
            extra,
            mask: permutation_mask(n),
        }
    }

    /// Whether every divisor of the layout is a power of two: `n` a power of two and
    /// every row `base` cells long (n = 1, 2, 4, 8, 16, 64, 256, …). A cell's row and
    /// column are then a shift and a mask, and each float quotient a product with the
    /// divisor's reciprocal, which is exact (as is scaling by it), so
    /// [`EqualAreaRows::cell`] and [`EqualAreaRows::line`] give bit for bit what the
    /// divisions of [`equal_area_cell_in`] give, without them (two integer and three float
    /// divisions per 2D draw). Derived from the layout where it is used, so that the
    /// layout stays four words and a [`Sampler`](super::Sampler) small.
    #[inline(always)]
    pub(super) fn pow2(&self) -> bool {
        // n & mask is 0 exactly for a power of two (mask = n − 1 then) or for n = 0 (no
        // layout: `PixelStreams` of another sampler), as base & (base − 1) is for base.
        let Self { n, base, .. } = *self;
        self.extra == 0 && n & self.mask == 0 && base & base.wrapping_sub(1) == 0 && n != 0
    }

    /// [`equal_area_cell`] of `cell` in this layout.
    #[inline]
    pub(super) fn cell(&self, cell: u32, jitter: Vec2) -> Vec2 {
        if self.pow2() {
            let (shift, log_n) = (self.base.trailing_zeros(), self.n.trailing_zeros());
            let col = cell & ((1 << shift) - 1);
            // (cell − col) is the cells before this row, row × base; a row's height is
            // base/n.
            let y0 = (cell - col) as f32 * exp2_neg(log_n);
            return Vec2::new(
                ((col as f32 + jitter.x) * exp2_neg(shift)).min(ONE_MINUS_EPSILON),
                (y0 + jitter.y * exp2_neg(log_n - shift)).min(ONE_MINUS_EPSILON),
            );
        }
        let EqualAreaRows { n, base, extra, .. } = *self;
        equal_area_cell_in(cell, n, base, extra, jitter)
    }

    /// The point `jitter` of the way through cell `cell` of the unit interval's `n`
    /// equal cells: (cell + jitter)/n.
    #[inline]
    pub(super) fn line(&self, cell: u32, jitter: f32) -> f32 {
        let x = cell as f32 + jitter;
        match self.pow2() {
            true => x * exp2_neg(self.n.trailing_zeros()),
            false => x / self.n as f32,
        }
        .min(ONE_MINUS_EPSILON)
    }

    /// [`permute`] of `i` among the `n` samples under `seed`, for `i` < n (the
    /// sampler's indices; past the count it draws independent numbers): here an index
    /// ≥ n is not reduced, and its walk may never end.
    #[inline]
    pub(super) fn permute(&self, i: u32, seed: u32) -> u32 {
        permute_masked(i, self.n, self.mask, seed)
    }

    /// The cells of samples `first`, `first` + 1, … (`len` ≤ [`CHUNK_LANES`] of them)
    /// in each dimension whose key is in `keys`: `cells[l][d]` is
    /// [`EqualAreaRows::permute`]`(first + l, keys[d])` for the samples below `n`. The
    /// others (lanes past `len`, and samples at or past `n`, which draw independent
    /// numbers instead) get unspecified cells: the cycle walk of a permutation may never
    /// end from an index ≥ n, whose cycle under the hash need not enter 0..n, so none is
    /// started there. In AVX2 lanes where `wide` asks for them
    /// ([`chunk_is_wide`](crate::sampling::sobol::chunk_is_wide)), the processor has
    /// them, the chunk holds two samples or more and `n` is a power of two (the usual
    /// sample counts, whose permutation takes one round of the hash and no walk); index
    /// by index otherwise.
    #[inline]
    pub(super) fn permute_chunk<const D: usize>(
        &self,
        first: u32,
        len: usize,
        keys: &[u32; D],
        wide: bool,
    ) -> [[u32; D]; CHUNK_LANES] {
        #[cfg(target_arch = "x86_64")]
        if wide
            && len >= 2
            && self.n & self.mask == 0
            && std::arch::is_x86_feature_detected!("avx2")
        {
            // SAFETY: the processor has AVX2, checked just above.
            return unsafe { permute_chunk_avx2(first, self.mask, keys) };
        }
        let _ = wide;
        let mut cells = [[0; D]; CHUNK_LANES];
        for (l, row) in cells.iter_mut().enumerate().take(len) {
            let i = first.wrapping_add(l as u32);
            if i < self.n {
                *row = std::array::from_fn(|d| self.permute(i, keys[d]));
            }
        }
        cells
    }
}

/// [`EqualAreaRows::permute_chunk`] for a power of two n = `w` + 1 (or n = 1, `w` = 0),
/// eight indices in the u32 lanes of an AVX2 register: [`kensler_hash`]'s steps, the
/// key broadcast, then the remainder as a mask.
///
/// # Safety
///
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn permute_chunk_avx2<const D: usize>(
    first: u32,
    w: u32,
    keys: &[u32; D],
) -> [[u32; D]; CHUNK_LANES] {
    use std::arch::x86_64::*;
    let splat = |v: u32| _mm256_set1_epi32(v as i32);
    let mask = splat(w);
    let index = _mm256_add_epi32(splat(first), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    let mut cells = [[0; D]; CHUNK_LANES];
    for (d, &seed) in keys.iter().enumerate() {
        let xor = |i: __m256i, v: u32| _mm256_xor_si256(i, splat(v));
        let mul = |i: __m256i, v: u32| _mm256_mullo_epi32(i, splat(v));
        // i ^= (i & w) >> k, the hash's folds of the bits kept.
        let fold = |i: __m256i, k: u32| {
            _mm256_xor_si256(i, _mm256_srlv_epi32(_mm256_and_si256(i, mask), splat(k)))
        };
        let mut i = mul(xor(index, seed), 0xe170_893d);
        i = xor(i, seed >> 16);
        i = fold(i, 4);
        i = mul(xor(i, seed >> 8), 0x0929_eb3f);
        i = xor(i, seed >> 23);
        i = fold(i, 1);
        i = mul(mul(i, 1 | seed >> 27), 0x6935_fa69);
        i = fold(i, 11);
        i = mul(i, 0x74dc_b303);
        i = fold(i, 2);
        i = mul(i, 0x9e50_1cc3);
        i = fold(i, 2);
        i = _mm256_and_si256(mul(i, 0xc860_a3df), mask);
        i = _mm256_xor_si256(i, _mm256_srli_epi32::<5>(i));
        // Below n already (n = w + 1): no walk; then (i + seed) mod n as a mask.
        i = _mm256_and_si256(_mm256_add_epi32(i, splat(seed)), mask);
        let mut lanes = [0u32; CHUNK_LANES];
        // SAFETY: the array holds eight u32, an unaligned store's width.
        unsafe { _mm256_storeu_si256(lanes.as_mut_ptr().cast(), i) };
        for (row, &cell) in cells.iter_mut().zip(&lanes) {
            row[d] = cell;
        }
    }
    cells
}

/// [`equal_area_cell`] with the layout given: `base` cells per row, the first `extra`
/// rows one more.
#[inline]
pub(super) fn equal_area_cell_in(cell: u32, n: u32, base: u32, extra: u32, jitter: Vec2) -> Vec2 {
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
/// two, cycle-walked back into range. An `i` ≥ n is taken modulo n first: the walk
/// from such an index may never end (its cycle under the hash need not enter 0..n).
pub fn permute(i: u32, n: u32, seed: u32) -> u32 {
    permute_masked(i % n.max(1), n, permutation_mask(n), seed)
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
pub(super) fn kensler_hash(mut i: u32, w: u32, seed: u32) -> u32 {
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
