//! Tests of the splat buffers: the sums' moments, and the vector lanes against the cell
//! by cell sums.

use super::*;
use crate::image::Filter;
use crate::sampling::rng::Rng32;

/// The sums of one cell (count, then the eight planes).
fn cell(buf: &SplatBuffer, i: usize) -> (u32, [f64; PLANES]) {
    let stride = buf.stride();
    (
        buf.count[i],
        std::array::from_fn(|k| buf.sums[k * stride + i]),
    )
}

#[test]
fn sums_are_the_weighted_moments() {
    // A tent of radius 1 on a 1 × 1 image: a sample at (0.5, 0) weighs 1 · 0.5, one
    // at (0, 0) 0.5 · 0.5 (the footprint clamped to the one pixel).
    let filter = Filter::TENT.prepare();
    let mut buf = SplatBuffer::new((0, 0, 1, 1));
    let samples = [
        (Vec2::new(0.5, 0.0), Spectrum::new(1.0, 2.0, 3.0), 0.5f32),
        (Vec2::new(0.0, 0.0), Spectrum::new(3.0, 0.0, 1.0), 0.25),
    ];
    for (p, l, _) in samples {
        buf.splat(Lanes::detect(), &filter, (1, 1), p, l);
    }
    let stats = buf.stats(0);
    assert_eq!(stats.count, 2);
    assert_eq!(stats.weight, 0.75);
    assert_eq!(stats.weight2, 0.3125);
    // Weighted mean (0.5·(1,2,3) + 0.25·(3,0,1)) / 0.75 and Σw(x − mean)².
    let mean = Spectrum::new(5.0 / 3.0, 4.0 / 3.0, 7.0 / 3.0);
    assert!((stats.mean - mean).abs().max_element() < 1e-6);
    let m2 = samples.iter().fold(Spectrum::ZERO, |m, &(_, l, w)| {
        m + w * (l - mean) * (l - mean)
    });
    assert!(
        (stats.m2 - m2).abs().max_element() < 1e-5,
        "{} vs {m2}",
        stats.m2
    );
}

/// The plane-by-plane sums, with and without AVX2, are bit for bit those of adding
/// each sample to each cell it reaches with a positive weight, one cell at a time, all
/// eight terms (also for samples of radiance zero): tiles at two opposite corners of
/// the image, each buffer widened by the filter's reach on its inner sides (as
/// [`round_splatted`] makes it), footprints of 0 to 6 pixels per axis (both the
/// four-lane path and the wider one). (On a processor without AVX2 both buffers take
/// the baseline.)
#[test]
fn lanes_are_the_cell_by_cell_sums() {
    let (w, h) = (13, 11);
    for (x0, y0, x1, y1) in [(0, 4, 6, h), (7, 0, w, 5)] {
        splat_tile(w, h, (x0, y0, x1, y1));
    }
}

fn splat_tile(w: u32, h: u32, (x0, y0, x1, y1): Tile) {
    let filters = [
        Filter::default(),
        Filter::TENT,
        Filter::GAUSSIAN,
        Filter::Gaussian { stddev: 0.3 },
        Filter::Tent { radius: 2.5 },
        // Narrower than half a pixel: a sample may reach no pixel at all.
        Filter::Box { radius: 0.3 },
    ];
    let mut rng = Rng32::new(7);
    let mut reached = 0;
    for filter in filters {
        let reach = filter.radius().ceil() as u32;
        let around = || SplatBuffer::around((x0, y0, x1, y1), reach, (w, h));
        let (mut lanes, mut avx2, mut reference) = (around(), around(), around());
        let rows = (reference.cells as u32) / reference.width;
        let (bx0, by0) = (reference.x0, reference.y0);
        let (bx1, by1) = (bx0 + reference.width, by0 + rows);
        let prepared = filter.prepare();
        for n in 0..400 {
            // Film positions in the tile's pixels [x0, x1) × [y0, y1), some on
            // pixel edges and centres exactly.
            let lo = Vec2::new(x0 as f32, y0 as f32);
            let size = Vec2::new((x1 - x0) as f32, (y1 - y0) as f32);
            let mut p = lo + size * Vec2::new(rng.next_f32(), rng.next_f32());
            if n % 5 == 0 {
                p = ((p * 2.0).floor() / 2.0).min(lo + size - 0.5);
            }
            // Some samples bring no light (with signed zeros too), which add only
            // their weights; some bring negative values (as control variates may),
            // so that sums cancel to zero before a sample of zero comes.
            let l = match n % 6 {
                0 => Spectrum::ZERO,
                1 => Spectrum::new(-0.0, 0.0, -0.0),
                2 => Spectrum::new(-0.5, 0.25, -1.0),
                3 => Spectrum::new(0.5, -0.25, 1.0),
                _ => Spectrum::new(rng.next_f32(), 3.0 * rng.next_f32(), 0.0),
            };
            lanes.splat(Lanes::BASELINE, &prepared, (w, h), p, l);
            avx2.splat(Lanes::detect(), &prepared, (w, h), p, l);
            let (mut wx, mut wy) = ([0.0; FOOTPRINT_LANES], [0.0; FOOTPRINT_LANES]);
            let (xl, nx) = prepared.weights(p.x, w, &mut wx);
            let (yl, ny) = prepared.weights(p.y, h, &mut wy);
            for (j, &wyj) in wy[..ny].iter().enumerate() {
                for (k, &wxk) in wx[..nx].iter().enumerate() {
                    let (x, y) = (xl + k as u32, yl + j as u32);
                    assert!((bx0..bx1).contains(&x) && (by0..by1).contains(&y));
                    let wt = wyj * wxk;
                    if wt > 0.0 {
                        let i = ((y - by0) * reference.width + x - bx0) as usize;
                        let stride = reference.stride();
                        let (wt, x) = (wt as f64, l.as_dvec3());
                        let terms = [
                            wt,
                            wt * wt,
                            wt * x.x,
                            wt * x.y,
                            wt * x.z,
                            (wt * x.x) * x.x,
                            (wt * x.y) * x.y,
                            (wt * x.z) * x.z,
                        ];
                        for (k, t) in terms.into_iter().enumerate() {
                            reference.sums[k * stride + i] += t;
                        }
                        reference.count[i] += 1;
                    }
                }
            }
        }
        for i in 0..reference.cells {
            let want = cell(&reference, i);
            assert_eq!(cell(&lanes, i), want, "{filter:?}, cell {i}");
            assert_eq!(cell(&avx2, i), want, "{filter:?}, cell {i} (AVX2)");
            if filter.radius() >= 0.5 {
                reached += want.0;
            }
        }
    }
    // Every splat of the filters at least half a pixel wide reaches its own pixel.
    assert!(reached >= 5 * 400, "{reached} splats");
}
