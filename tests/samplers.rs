//! Sample-pattern properties of the stratified and Sobol samplers.

use glam::Vec2;
use lightlab::sampling::sampler::{ONE_MINUS_EPSILON, equal_area_cell};
use lightlab::sampling::{Sampler, SamplerKind, Uniform};

/// The first 2D point of sample `index` of pixel `pixel`.
fn first_2d(kind: SamplerKind, pixel: u64, index: u32, spp: u32) -> Vec2 {
    Sampler::new(kind, 17, pixel, index, spp).next_2d()
}

#[test]
fn stratified_and_sobol_points_are_in_the_unit_interval() {
    for kind in [SamplerKind::Stratified, SamplerKind::Sobol] {
        for pixel in 0..16 {
            for index in 0..256 {
                let mut sampler = Sampler::new(kind, 3, pixel, index, 256);
                for _ in 0..8 {
                    let (x, p) = (sampler.next_1d(), sampler.next_2d());
                    assert!(
                        (0.0..1.0).contains(&x)
                            && p.cmpge(Vec2::ZERO).all()
                            && p.cmplt(Vec2::ONE).all()
                    );
                }
            }
        }
    }
}

#[test]
fn sobol_prefixes_are_0_k_2_nets() {
    for k in [4u32, 6, 8] {
        for pixel in 0..4 {
            let points: Vec<Vec2> = (0..1u32 << k)
                .map(|i| first_2d(SamplerKind::Sobol, pixel, i, 1 << k))
                .collect();
            // Every elementary interval of area 2^-k: 2^a columns × 2^(k−a) rows.
            for a in 0..=k {
                let (columns, rows) = (1u32 << a, 1u32 << (k - a));
                let mut count = vec![0u32; 1 << k];
                for p in &points {
                    let (i, j) = ((p.x * columns as f32) as u32, (p.y * rows as f32) as u32);
                    count[(j * columns + i) as usize] += 1;
                }
                assert!(
                    count.iter().all(|&c| c == 1),
                    "k = {k}, pixel {pixel}, {columns}x{rows}: {count:?}"
                );
            }
        }
    }
}

#[test]
fn stratified_2d_puts_one_point_in_each_equal_area_cell() {
    for spp in [1u32, 7, 10, 16, 64] {
        for pixel in 0..4 {
            let mut count = vec![0u32; spp as usize];
            for index in 0..spp {
                let p = first_2d(SamplerKind::Stratified, pixel, index, spp);
                let cell = (0..spp).find(|&c| {
                    let (lo, hi) = (
                        equal_area_cell(c, spp, Vec2::ZERO),
                        equal_area_cell(c, spp, Vec2::splat(ONE_MINUS_EPSILON)),
                    );
                    p.cmpge(lo).all() && p.cmple(hi).all()
                });
                count[cell.expect("point lies in some cell") as usize] += 1;
            }
            assert!(
                count.iter().all(|&c| c == 1),
                "spp = {spp}, pixel {pixel}: {count:?}"
            );
        }
    }
}
