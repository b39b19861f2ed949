//! Tests of the per-sample streams: unit interval, bijective permutations, strata that
//! tile the square, and the same numbers through a pixel's streams as through its key.

use super::strata::kensler_hash;
use super::*;
use crate::sampling::sobol::{CHUNK_LANES, chunk_is_wide};

/// An index at or past the count is taken modulo the count: Kensler's walk from one
/// may never end. Among 3 under seed 0, the hash (on 0..4) fixes 3, so a walk from 3
/// would stay there; `permute` returns what it returns for 0.
#[test]
fn permute_reduces_an_index_past_the_count() {
    assert_eq!(
        kensler_hash(3, 3, 0),
        3,
        "the walk from 3 among 3 would not end"
    );
    assert_eq!(permute(3, 3, 0), permute(0, 3, 0));
    for (i, n) in [(u32::MAX, 3u32), (7, 1), (100, 16), (5, 0), (15, 9)] {
        assert_eq!(
            permute(i, n, 0),
            permute(i % n.max(1), n, 0),
            "{i} among {n}"
        );
    }
}

/// The power-of-two layouts' shifts and reciprocals give bit for bit the divisions of
/// [`equal_area_cell_in`] (2D) and (cell + jitter)/n (1D), for every such count up
/// to 2³⁰, every cell of the small ones, jitters 0, just below 1 and between.
#[test]
fn power_of_two_layouts_divide_exactly() {
    use super::strata::equal_area_cell_in;
    for k in 0..32 {
        let n = 1u32 << k;
        let rows = EqualAreaRows::new(n);
        // Square counts and 2, 8; other odd powers have rows of unequal length.
        let square = k % 2 == 0 || k <= 3;
        assert_eq!(rows.pow2(), square, "{n} samples");
        if !square {
            continue;
        }
        let (base, extra) = (rows.base, rows.extra);
        let cells: Vec<u32> = if n <= 1024 {
            (0..n).collect()
        } else {
            vec![0, 1, base - 1, base, n / 3, n / 2 + 5, n - base, n - 1]
        };
        let jitters = [0.0, 0.25, 0.5, 0.7310585, ONE_MINUS_EPSILON];
        for &c in &cells {
            for (&jx, &jy) in jitters.iter().zip(jitters.iter().rev()) {
                let j = Vec2::new(jx, jy);
                let divided = equal_area_cell_in(c, n, base, extra, j);
                let shifted = rows.cell(c, j);
                assert_eq!(
                    shifted.to_array().map(f32::to_bits),
                    divided.to_array().map(f32::to_bits),
                    "n {n}, cell {c}, jitter {j}"
                );
                let line = ((c as f32 + jx) / n as f32).min(ONE_MINUS_EPSILON);
                assert_eq!(
                    rows.line(c, jx).to_bits(),
                    line.to_bits(),
                    "n {n}, cell {c}"
                );
            }
        }
    }
    for n in [0u32, 3, 12, 72, 100, 144] {
        assert!(!EqualAreaRows::new(n).pow2(), "{n} samples");
    }
}

#[test]
fn permute_is_a_bijection() {
    for n in [1u32, 2, 3, 7, 16, 100] {
        let mut seen = vec![false; n as usize];
        for i in 0..n {
            let p = permute(i, n, 0x1234_5678);
            assert!(!seen[p as usize]);
            seen[p as usize] = true;
        }
    }
}

/// Kensler's permutation as his note writes it: the mask smeared from n − 1 on every
/// call, the remainder by division (the hash round itself is shared, [`kensler_hash`]).
fn kensler_permute(mut i: u32, n: u32, seed: u32) -> u32 {
    if n <= 1 {
        return 0;
    }
    let mut w = n - 1;
    for shift in [1, 2, 4, 8, 16] {
        w |= w >> shift;
    }
    loop {
        i = kensler_hash(i, w, seed);
        if i < n {
            break;
        }
    }
    (i.wrapping_add(seed)) % n
}

/// The strata's mask, kept per pixel, and the remainder by masking for powers of two
/// give Kensler's permutation exactly, for powers of two, their neighbours and others.
#[test]
fn permute_is_kenslers() {
    let mut counts: Vec<u32> = (1..=70).collect();
    for k in 1..=31 {
        counts.extend([(1u32 << k) - 1, 1 << k, (1u32 << k) + 1]);
    }
    counts.push(u32::MAX);
    for &n in &counts {
        let strata = EqualAreaRows::new(n);
        for s in 0..40u32 {
            let seed = ((s as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 32) as u32;
            for i in [0, 1, 2, n / 3, n / 2, n.saturating_sub(1)] {
                assert_eq!(
                    strata.permute(i, seed),
                    kensler_permute(i, n, seed),
                    "n {n}, i {i}"
                );
            }
        }
    }
}

/// A chunk's cells, in AVX2 lanes (where this processor has them) and index by index,
/// are [`EqualAreaRows::permute`]'s, for powers of two (which take the lanes), other
/// counts and one sample, near the count's end; and a chunk at or past the count
/// returns (a cycle walk from an index ≥ n may never end, so none is started: this test
/// hung before that).
#[test]
fn chunk_cells_are_the_permutation() {
    let keys = [0u32, 1, 0x1234_5678, u32::MAX];
    for n in [
        1u32,
        2,
        3,
        8,
        16,
        64,
        72,
        100,
        256,
        1 << 12,
        1 << 20,
        u32::MAX,
    ] {
        let rows = EqualAreaRows::new(n);
        for first in [0u32, 1, 8, n / 2, n.wrapping_sub(3), n, u32::MAX - 7] {
            for len in [1, 2, 5, CHUNK_LANES] {
                for wide in [false, chunk_is_wide()] {
                    let cells = rows.permute_chunk(first, len, &keys, wide);
                    for (l, row) in cells.iter().enumerate().take(len) {
                        let i = first.wrapping_add(l as u32);
                        if i >= n {
                            continue;
                        }
                        let expected = keys.map(|k| rows.permute(i, k));
                        assert_eq!(*row, expected, "n {n} first {first} lane {l} {wide}");
                    }
                }
            }
        }
    }
}

#[test]
fn equal_area_cells_cover_each_cell_once() {
    for n in [1u32, 2, 3, 5, 8, 16, 17] {
        let mut area = 0.0;
        for c in 0..n {
            let lo = equal_area_cell(c, n, Vec2::ZERO);
            let hi = equal_area_cell(c, n, Vec2::splat(ONE_MINUS_EPSILON));
            area += (hi.x - lo.x) * (hi.y - lo.y);
            assert!(lo.cmpge(Vec2::ZERO).all() && hi.cmplt(Vec2::ONE).all());
        }
        assert!((area - 1.0).abs() < 1e-4, "n = {n}: area {area}");
    }
}

#[test]
fn every_sampler_stays_in_unit_interval() {
    for kind in SamplerKind::ALL {
        for s in 0..64 {
            let mut sampler = Sampler::new(kind, 7, 3, s, 64);
            for _ in 0..10 {
                let x = sampler.next_1d();
                let p = sampler.next_2d();
                assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&p.x));
                assert!((0.0..1.0).contains(&p.y));
            }
        }
    }
}

/// A sampler made from a pixel's streams draws what one made from the pixel's key
/// draws, for every kind, past the seeded dimensions and past Sobol's last index, with
/// streams laid out for the sample count drawn (64; 72, not a power of two; 0 and 1) and
/// for another one (72 against 64: another row layout).
#[test]
fn streams_draw_what_the_key_draws() {
    for kind in SamplerKind::ALL {
        let counts = [(0u64, 64, 64), (5, 64, 64), (1 << 20, 64, 64), (9, 72, 64)];
        let more = [(9, 72, 72), (3, 1, 1), (3, 0, 0)];
        for (pixel, laid_out, spp) in counts.into_iter().chain(more) {
            let streams = PixelStreams::new(kind, 11, pixel, laid_out);
            assert_eq!(streams.key(), Sampler::pixel_key(11, pixel));
            for s in [0u32, 1, 7, 63, 71, SOBOL_MAX_SAMPLES] {
                let a = Sampler::new(kind, 11, pixel, s, spp);
                let b = Sampler::for_streams(kind, &streams, s, spp);
                // The first dimensions' numbers computed with the sample's chunk: whole
                // (in lanes), of three samples (in lanes where AVX2 is), of one (alone).
                for len in [CHUNK_LANES as u32, 3, 1] {
                    let first = s - s % len;
                    let points = streams.chunk_points(first, len as usize);
                    let cells = streams.chunk_cells(first, len as usize);
                    let pointed = kind == SamplerKind::Sobol && first < SOBOL_MAX_SAMPLES;
                    assert_eq!(points.is_some(), pointed);
                    assert_eq!(cells.is_some(), kind == SamplerKind::Stratified);
                    // Cells only for samples within the count, from strata laid out for it.
                    let celled =
                        kind == SamplerKind::Stratified && s < spp && laid_out.max(1) == spp.max(1);
                    // A chunk may straddle Sobol's last index: its later samples take none.
                    let sobol = kind == SamplerKind::Sobol && s < SOBOL_MAX_SAMPLES;
                    let row = (s - first) as usize;
                    let mut c = match (&points, &cells) {
                        (Some(p), _) => Sampler::with_points(kind, &streams, s, spp, &p[row]),
                        (_, Some(c)) => Sampler::with_cells(kind, &streams, s, spp, &c[row]),
                        _ => Sampler::for_streams(kind, &streams, s, spp),
                    };
                    assert_eq!(c.pointed, if sobol { SEEDED_DIMENSIONS as u32 } else { 0 });
                    assert_eq!(c.celled, if celled { SEEDED_DIMENSIONS as u32 } else { 0 });
                    let mut a = a.clone();
                    let mut b = b.clone();
                    for d in 0..3 * SEEDED_DIMENSIONS {
                        let (x, y, z) = if d % 3 == 1 {
                            let one = |s: &mut Sampler| Vec2::splat(s.next_1d());
                            (one(&mut a), one(&mut b), one(&mut c))
                        } else {
                            (a.next_2d(), b.next_2d(), c.next_2d())
                        };
                        let bits = |v: Vec2| v.to_array().map(f32::to_bits);
                        assert_eq!(bits(x), bits(y));
                        assert_eq!(bits(x), bits(z), "{kind:?} sample {s} draw {d} of {len}");
                    }
                }
            }
        }
    }
    // Chunks of every length, in lanes and sample by sample (whichever this processor
    // would take), hand every sample of theirs its own points, up to Sobol's last index,
    // or its own cells, up to the sample count (a power of two, as the lanes need).
    let firsts = [
        (SamplerKind::Sobol, [0u32, 5, 64, SOBOL_MAX_SAMPLES - 3]),
        (SamplerKind::Stratified, [0, 5, 56, 60]),
    ];
    for (kind, firsts) in firsts {
        let streams = PixelStreams::new(kind, 11, 5, 64);
        for first in firsts {
            for len in 1..=CHUNK_LANES {
                for wide in [false, true] {
                    let points = streams.chunk_points_in(first, len, wide);
                    let cells = streams.chunk_cells_in(first, len, wide);
                    for s in first..first + len as u32 {
                        let mut a = Sampler::new(kind, 11, 5, s, 64);
                        let row = (s - first) as usize;
                        let mut c = match (&points, &cells) {
                            (Some(p), None) => Sampler::with_points(kind, &streams, s, 64, &p[row]),
                            (None, Some(c)) => Sampler::with_cells(kind, &streams, s, 64, &c[row]),
                            _ => panic!("{kind:?} draws points or cells ahead"),
                        };
                        for d in 0..SEEDED_DIMENSIONS {
                            let (x, z) = (a.next_2d(), c.next_2d());
                            let at = format!("{kind:?} {first} {len} {wide} {s} {d}");
                            assert_eq!(x.to_array(), z.to_array(), "{at}");
                        }
                    }
                }
            }
        }
    }
    // The seeds are hashed for Sobol only, and differ from dimension to dimension.
    let sobol = PixelStreams::new(SamplerKind::Sobol, 11, 5, 64);
    assert_eq!(sobol.seeded, SEEDED_DIMENSIONS as u32);
    assert_ne!(sobol.sobol[0], sobol.sobol[1]);
    // The strata's layout and keys are kept for the sample count, for `stratified` only.
    let strata = PixelStreams::new(SamplerKind::Stratified, 11, 5, 64);
    assert_eq!(
        (strata.seeded, strata.rows.n),
        (SEEDED_DIMENSIONS as u32, 64)
    );
    assert_ne!(strata.cell_keys[0], strata.cell_keys[1]);
    assert_eq!(sobol.cell_keys, [0; SEEDED_DIMENSIONS]);
    assert_eq!(sobol.rows.n, 0);
}

/// The independent stream of a sample is PCG32 keyed by hash(pixel key, sample
/// index), however the hash is split between pixel and sample.
#[test]
fn independent_streams_hash_pixel_and_sample_index() {
    for (pixel, s) in [(0u64, 0u32), (5, 1), (1 << 20, 1000), (7, u32::MAX)] {
        let key = Sampler::pixel_key(3, pixel);
        let streams = PixelStreams::new(SamplerKind::Independent, 3, pixel, 16);
        let mut a = Sampler::new(SamplerKind::Independent, 3, pixel, s, 16);
        let mut b = Sampler::for_streams(SamplerKind::Independent, &streams, s, 16);
        let mut rng = Rng32::new(hash_words(&[key, s as u64]));
        for _ in 0..4 {
            let expected = rng.next_f32().to_bits();
            assert_eq!(a.next_1d().to_bits(), expected);
            assert_eq!(b.next_1d().to_bits(), expected);
        }
    }
}

/// A sampler is stored per pixel between the spatial reuse's passes, whose second
/// pass reads the neighbours': a version 60 bytes larger made that render 0.82× as
/// fast.
#[test]
fn samplers_stay_small() {
    assert!(
        std::mem::size_of::<Sampler>() <= 112,
        "{}",
        std::mem::size_of::<Sampler>()
    );
}

#[test]
fn names_round_trip() {
    for kind in SamplerKind::ALL {
        assert_eq!(kind.name().parse::<SamplerKind>().unwrap(), kind);
    }
    assert!("halton".parse::<SamplerKind>().is_err());
}
