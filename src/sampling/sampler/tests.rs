//! Tests of the per-sample streams: unit interval, bijective permutations, strata that
//! tile the square, and the same numbers through a pixel's streams as through its key.

use super::strata::kensler_hash;
use super::*;

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
                    let ahead = streams.chunk_ahead(first, len as usize);
                    let chunked = kind == SamplerKind::Sobol && first < SOBOL_MAX_SAMPLES;
                    assert_eq!(ahead.is_some(), chunked);
                    // A chunk may straddle Sobol's last index: its later samples take none.
                    let sobol = kind == SamplerKind::Sobol && s < SOBOL_MAX_SAMPLES;
                    let mut c = match &ahead {
                        Some(a) => {
                            Sampler::with_ahead(kind, &streams, s, spp, &a[(s - first) as usize])
                        }
                        None => Sampler::for_streams(kind, &streams, s, spp),
                    };
                    assert_eq!(c.pointed, if sobol { SEEDED_DIMENSIONS as u32 } else { 0 });
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
    // would take), hand every sample of theirs its own points, up to Sobol's last index.
    let streams = PixelStreams::new(SamplerKind::Sobol, 11, 5, 64);
    for first in [0u32, 5, 64, SOBOL_MAX_SAMPLES - 3] {
        for len in 1..=CHUNK_LANES {
            for wide in [false, true] {
                let ahead = streams.chunk_ahead_in(first, len, wide).expect("Sobol's");
                for s in first..first + len as u32 {
                    let mut a = Sampler::new(SamplerKind::Sobol, 11, 5, s, 64);
                    let row = &ahead[(s - first) as usize];
                    let mut c = Sampler::with_ahead(SamplerKind::Sobol, &streams, s, 64, row);
                    for d in 0..SEEDED_DIMENSIONS {
                        let (x, z) = (a.next_2d(), c.next_2d());
                        assert_eq!(x.to_array(), z.to_array(), "{first} {len} {wide} {s} {d}");
                    }
                }
            }
        }
    }
    // The seeds are hashed for Sobol only, and differ from dimension to dimension.
    let sobol = PixelStreams::new(SamplerKind::Sobol, 11, 5, 64);
    assert_eq!(sobol.seeded, SEEDED_DIMENSIONS as u32);
    assert_ne!(sobol.sobol[0], sobol.sobol[1]);
    // The strata's layout is kept for the sample count, for `stratified` only.
    let strata = PixelStreams::new(SamplerKind::Stratified, 11, 5, 64);
    assert_eq!((strata.seeded, strata.rows.n), (0, 64));
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
