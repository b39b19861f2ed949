//! The cost of one solid-angle sample of a rectangle light, one shading point at a time
//! (`FastSphericalRectangle`) and `LANES` at a time (`sample_lanes`, AVX2 where the
//! processor has it), at points below a ceiling light as in a Cornell box: ns per sample,
//! best of seven passes over 10⁶ points. Both give the same bits (checked here too).
//!
//! `cargo run --release --example rectangle_lanes`

use std::hint::black_box;
use std::time::Instant;

use glam::{Vec2, Vec3};
use lightlab::sampling::warp::{
    FastSphericalRectangle, LANES, RectangleFrame, RectangleLane, sample_lanes,
};
use lightlab::sampling::{Rng32, Uniform};

fn main() {
    let (corner, ex, ey) = (
        Vec3::new(-0.25, 1.99, -0.25),
        Vec3::new(0.5, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 0.5),
    );
    let frame = RectangleFrame::new(ex, ey).expect("perpendicular edges");
    let mut rng = Rng32::new(7);
    let points: Vec<(Vec3, Vec2)> = (0..1_000_000)
        .map(|_| {
            let q = rng.next_2d() * 2.0 - 1.0;
            (Vec3::new(q.x, rng.next_1d() * 1.9, q.y), rng.next_2d())
        })
        .collect();
    let lanes_of = |c: &[(Vec3, Vec2)]| -> [RectangleLane; LANES] {
        std::array::from_fn(|l| RectangleLane {
            frame: &frame,
            corner,
            p: c[l].0,
            u: c[l].1,
        })
    };
    // Same bits.
    for c in points.chunks_exact(LANES).take(10_000) {
        let wide = sample_lanes(&lanes_of(c));
        for (l, got) in wide.into_iter().enumerate() {
            let one = FastSphericalRectangle::from_frame(&frame, c[l].0, corner)
                .map(|r| r.sample(c[l].1))
                .map(|(_, offset, pdf)| (offset, pdf));
            let bits = |s: Option<(Vec3, f32)>| {
                s.map(|(o, p)| (o.to_array().map(f32::to_bits), p.to_bits()))
            };
            assert_eq!(bits(got), bits(one));
        }
    }
    let best = |f: &dyn Fn() -> Vec3| {
        (0..7)
            .map(|_| {
                let t = Instant::now();
                black_box(f());
                t.elapsed().as_secs_f64() * 1e9 / points.len() as f64
            })
            .fold(f64::INFINITY, f64::min)
    };
    let one_at_a_time = best(&|| {
        let mut acc = Vec3::ZERO;
        for (p, u) in &points {
            if let Some(r) = FastSphericalRectangle::from_frame(&frame, black_box(*p), corner) {
                let (_, offset, pdf) = r.sample(*u);
                acc += offset * pdf;
            }
        }
        acc
    });
    let lanes_at_a_time = best(&|| {
        let mut acc = Vec3::ZERO;
        for c in points.chunks_exact(LANES) {
            for (offset, pdf) in sample_lanes(black_box(&lanes_of(c))).into_iter().flatten() {
                acc += offset * pdf;
            }
        }
        acc
    });
    println!(
        "one at a time {one_at_a_time:.1} ns/sample, {LANES} at a time {lanes_at_a_time:.1} \
         ns/sample ({:.2}x)",
        one_at_a_time / lanes_at_a_time
    );
}
