//! Registry rows for the tabulated and generic distributions. Tables contain zero
//! weights on purpose: a sample in a zero bin fails the test hard.

use glam::{Vec2, Vec3};

use super::{Draw, Entry, Family, boxed};
use crate::sampling::chi2::Domain;
use crate::sampling::distribution::piecewise_constant::point_in_bin;
use crate::sampling::distribution::{
    AliasTable, PiecewiseConstant1D, PiecewiseConstant2D, RejectionSampler, sample_by_inversion,
};

/// A 1D table with zero bins at both ends and inside.
const WEIGHTS_1D: [f32; 16] = [
    0.0, 1.0, 3.0, 0.0, 0.5, 8.0, 2.0, 0.0, 0.0, 4.0, 1.0, 1.0, 0.0, 6.0, 0.25, 0.0,
];

/// An 8 × 6 table (row-major) with a zero row and zero cells.
fn weights_2d() -> Vec<f32> {
    (0..48)
        .map(|i| {
            let (x, y) = (i % 8, i / 8);
            if y == 2 || (x + y) % 5 == 0 {
                0.0
            } else {
                1.0 + ((x * 7 + y * 3) % 11) as f32
            }
        })
        .collect()
}

/// p(x) = (1 + x + ½ sin 2πx)/1.5 on [0, 1): a smooth density whose CDF
/// (x + x²/2 + (1 − cos 2πx)/(4π))/1.5 has no closed-form inverse.
fn smooth_pdf(x: f64) -> f64 {
    if (0.0..1.0).contains(&x) {
        (1.0 + x + 0.5 * (2.0 * std::f64::consts::PI * x).sin()) / 1.5
    } else {
        0.0
    }
}

fn smooth_cdf(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    (x + 0.5 * x * x
        + (1.0 - (2.0 * std::f64::consts::PI * x).cos()) / (4.0 * std::f64::consts::PI))
        / 1.5
}

fn on_line(x: f32) -> Vec3 {
    Vec3::new(x, 0.0, 0.0)
}

pub(super) fn entries() -> Vec<Entry> {
    let table = PiecewiseConstant1D::new(&WEIGHTS_1D).unwrap_or_else(|e| unreachable!("{e}"));
    let alias = AliasTable::new(&WEIGHTS_1D).unwrap_or_else(|e| unreachable!("{e}"));
    let table_2d =
        PiecewiseConstant2D::new(&weights_2d(), 8, 6).unwrap_or_else(|e| unreachable!("{e}"));
    let n = WEIGHTS_1D.len();
    let bins = Some([n * 25, 1]);
    let entry = |name: &str, description: &str, domain, draw, pdf, inverse| Entry {
        name: name.into(),
        description: description.into(),
        family: Family::Distribution,
        domain,
        draw,
        pdf,
        inverse,
        samples: 1_000_000,
        resolution: bins,
    };
    let table_pdf = |t: PiecewiseConstant1D| boxed(move |x: Vec3| t.pdf(x.x));
    let (t1, t2, t3, t4) = (table.clone(), table.clone(), table.clone(), table.clone());
    let a2 = alias.clone();
    let rejection = RejectionSampler {
        min: 0.0,
        max: 1.0,
        bound: 2.5 / 1.5,
        max_tries: 1000,
    };
    let smooth = || boxed(|x: Vec3| smooth_pdf(x.x as f64) as f32);
    let mut list = vec![
        entry(
            "pc1d-two-numbers",
            "piecewise-constant 1D: u0 picks the rectangle, u1 places x (lecture)",
            Domain::UNIT_INTERVAL,
            Draw::Square(boxed(move |u: Vec2| {
                let (x, pdf) = t1.sample_two(u);
                (on_line(x), pdf)
            })),
            table_pdf(table.clone()),
            None,
        ),
        entry(
            "pc1d-one-number",
            "piecewise-constant 1D: one number picks the rectangle and is reused for x",
            Domain::UNIT_INTERVAL,
            Draw::Square(boxed(move |u: Vec2| {
                let (index, pmf, u_reused) = t2.sample_discrete(u.x);
                (on_line(point_in_bin(index, u_reused, n)), pmf * n as f32)
            })),
            table_pdf(table.clone()),
            None,
        ),
        entry(
            "pc1d-continuous",
            "piecewise-constant 1D by continuous inversion of the piecewise-linear CDF",
            Domain::UNIT_INTERVAL,
            Draw::Square(boxed(move |u: Vec2| {
                let (x, pdf) = t3.sample_continuous(u.x);
                (on_line(x), pdf)
            })),
            table_pdf(table),
            Some(boxed(move |x: Vec3| Vec2::new(t4.cdf(x.x), 0.0))),
        ),
        entry(
            "alias",
            "Vose alias table; x = (index + reused u)/n shows the pmf and the reused number",
            Domain::UNIT_INTERVAL,
            Draw::Square(boxed(move |u: Vec2| {
                let (index, pmf, u_reused) = alias.sample(u.x);
                (on_line(point_in_bin(index, u_reused, n)), pmf * n as f32)
            })),
            boxed(move |x: Vec3| {
                if (0.0..1.0).contains(&x.x) {
                    a2.pmf((x.x * n as f32) as usize) * n as f32
                } else {
                    0.0
                }
            }),
            None,
        ),
        entry(
            "rejection-1d",
            "rejection under a bound: p(x) = (1 + x + sin(2 pi x)/2)/1.5",
            Domain::UNIT_INTERVAL,
            Draw::Stream(Box::new(move |rng: &mut crate::sampling::Rng32| {
                let p = |x: f32| smooth_pdf(x as f64) as f32;
                rejection
                    .sample(p, rng)
                    .map_or((on_line(0.0), 0.0), |(x, pdf)| (on_line(x), pdf))
            })),
            smooth(),
            None,
        ),
        entry(
            "inversion-newton",
            "numerical CDF inversion (safeguarded Newton) of p(x) = (1 + x + sin(2 pi x)/2)/1.5",
            Domain::UNIT_INTERVAL,
            Draw::Square(boxed(|u: Vec2| {
                let x = sample_by_inversion(smooth_cdf, smooth_pdf, 0.0, 1.0, u.x)
                    .min(1.0 - f32::EPSILON);
                (on_line(x), smooth_pdf(x as f64) as f32)
            })),
            smooth(),
            Some(boxed(|x: Vec3| {
                Vec2::new(smooth_cdf(x.x as f64) as f32, 0.0)
            })),
        ),
    ];
    for e in &mut list[4..] {
        e.resolution = None;
    }
    let (d1, d2) = (table_2d.clone(), table_2d.clone());
    list.push(Entry {
        resolution: Some([48, 48]),
        ..entry(
            "pc2d",
            "piecewise-constant 2D by marginal and conditional (8 x 6 table, one zero row)",
            Domain::UNIT_SQUARE,
            Draw::Square(boxed(move |u: Vec2| {
                let (p, pdf) = table_2d.sample(u);
                (p.extend(0.0), pdf)
            })),
            boxed(move |x: Vec3| d1.pdf(x.truncate())),
            Some(boxed(move |x: Vec3| d2.to_square(x.truncate()))),
        )
    });
    list
}
