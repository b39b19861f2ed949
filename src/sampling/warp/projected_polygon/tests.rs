//! Tests of [`ProjectedPolygon`](super::ProjectedPolygon) and the horizon clipping.

use super::*;

fn d(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// (name, shading point, normal, polygon): far, near, straddling the horizon, around
/// the zenith, with a vertex at the zenith, seen from behind (clockwise).
fn cases() -> Vec<(&'static str, DVec3, DVec3, Vec<DVec3>)> {
    let z = DVec3::Z;
    let square = |h: f64, x0: f64, y0: f64, s: f64| {
        vec![
            d(x0, y0, h),
            d(x0 + s, y0, h),
            d(x0 + s, y0 + s, h),
            d(x0, y0 + s, h),
        ]
    };
    vec![
        (
            "far",
            DVec3::ZERO,
            z,
            vec![d(3.0, 1.0, 9.0), d(3.4, 1.1, 9.2), d(3.1, 1.6, 8.8)],
        ),
        ("near", DVec3::ZERO, z, square(0.3, 0.2, -0.4, 1.0)),
        (
            "around-zenith",
            DVec3::ZERO,
            z,
            square(0.5, -0.3, -0.6, 1.0),
        ),
        ("zenith-vertex", DVec3::ZERO, z, square(0.7, 0.0, 0.0, 0.8)),
        (
            "straddling",
            DVec3::ZERO,
            d(-0.3, 0.0, 1.0).normalize(),
            vec![
                d(-1.0, -0.5, 0.2),
                d(-1.0, 0.6, 0.3),
                d(-1.0, 0.5, -0.6),
                d(-1.0, -0.5, -0.5),
            ],
        ),
        ("clockwise", d(0.1, 0.2, 0.0), z, {
            let mut v = square(0.4, -1.0, 0.3, 0.9);
            v.reverse();
            v
        }),
    ]
}

/// Ω⊥ by midpoint quadrature over the hemisphere in (cos²θ, φ), where cos θ dω =
/// ½ d(cos²θ) dφ, with a ray–plane point-in-polygon test.
fn quadrature(x: DVec3, n: DVec3, poly: &[DVec3]) -> f64 {
    use std::f64::consts::PI;
    let frame = Frame64::new(n);
    let normal = (poly[1] - poly[0]).cross(poly[2] - poly[0]).normalize();
    let inside = |w: DVec3| {
        let t = (poly[0] - x).dot(normal) / w.dot(normal);
        if t.is_nan() || t <= 0.0 {
            return false;
        }
        let y = x + w * t;
        let k = poly.len();
        let signs: Vec<f64> = (0..k)
            .map(|i| (poly[(i + 1) % k] - poly[i]).cross(y - poly[i]).dot(normal))
            .collect();
        signs.iter().all(|&s| s >= 0.0) || signs.iter().all(|&s| s <= 0.0)
    };
    let (nu, nphi) = (1500, 3000);
    let mut sum = 0.0;
    for i in 0..nu {
        let c2 = (i as f64 + 0.5) / nu as f64;
        let (c, s) = (c2.sqrt(), (1.0 - c2).sqrt());
        for j in 0..nphi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / nphi as f64;
            let w = frame.to_world(d(s * phi.cos(), s * phi.sin(), c));
            if inside(w) {
                sum += 1.0;
            }
        }
    }
    sum / (nu * nphi) as f64 * PI
}

#[test]
fn lamberts_formula_matches_quadrature() {
    for (name, x, n, poly) in cases() {
        let exact = projected_solid_angle(x, n, &poly);
        let numeric = quadrature(x, n, &poly);
        assert!(
            (exact - numeric).abs() < 2e-3 * exact.max(1e-3),
            "{name}: Lambert {exact} vs quadrature {numeric}"
        );
        if let Some(p) = ProjectedPolygon::new(x, n, &poly) {
            let total: f64 = p.intervals[..p.count].iter().map(|i| i.area).sum();
            assert!(
                (total - exact).abs() < 1e-12 * exact,
                "{name}: {total} vs {exact}"
            );
        }
    }
}

/// Every sample lies in the polygon and above the horizon, and its density is
/// cos θ / Ω⊥, so cos θ / pdf — the unoccluded Lambertian estimate — is Ω⊥ exactly.
#[test]
fn samples_lie_in_the_polygon_and_the_estimate_is_constant() {
    for (name, x, n, poly) in cases() {
        let p = ProjectedPolygon::new(x, n, &poly).expect(name);
        let omega = p.projected_solid_angle();
        for i in 0..64 {
            for j in 0..64 {
                let u = DVec2::new((i as f64 + 0.5) / 64.0, (j as f64 + 0.37) / 64.0);
                let (w, pdf) = p.sample(u);
                assert!((w.length() - 1.0).abs() < 1e-12, "{name}");
                assert!(p.pdf(w) > 0.0, "{name}: {w} at {u} outside");
                assert!((pdf - p.pdf(w)).abs() <= 1e-12 * pdf, "{name}");
                let estimate = w.dot(n) / pdf;
                assert!(
                    (estimate - omega).abs() < 1e-9 * omega,
                    "{name}: {estimate}"
                );
            }
        }
    }
}

/// The map is monotone in u.x along each u.y, as an inversion of the CDF in φ is: the
/// fraction of Ω⊥ at azimuths before the sample's is u.x.
#[test]
fn first_coordinate_is_the_azimuth_cdf() {
    for (name, x, n, poly) in cases() {
        let p = ProjectedPolygon::new(x, n, &poly).expect(name);
        let total: f64 = p.intervals[..p.count].iter().map(|i| i.area).sum();
        for k in 1..40 {
            let ux = k as f64 / 40.0;
            let (w, _) = p.sample(DVec2::new(ux, 0.5));
            let local = p.frame.to_local(w);
            // The sample's pseudo-azimuth from the start vertex, as the intervals'.
            let step = pseudo_azimuth(local) - pseudo_azimuth(p.start);
            let off = if p.around_zenith {
                step.rem_euclid(4.0)
            } else {
                azimuth_step(p.start, local)
            };
            // Area over the azimuths before the sample's.
            let ivs: Vec<&Interval> = p.intervals[..p.count].iter().collect();
            let mut before = 0.0;
            for iv in &ivs {
                if iv.lo + iv.width <= off {
                    before += iv.area;
                } else if iv.lo <= off {
                    before += iv.area_until(DVec2::new(local.x, local.y).normalize());
                }
            }
            let cdf = before / total;
            assert!((cdf - ux).abs() < 1e-9, "{name}: u.x {ux} gives cdf {cdf}");
        }
    }
}

#[test]
fn below_the_horizon_is_nothing() {
    let poly = [d(0.0, 0.0, -1.0), d(1.0, 0.0, -1.0), d(0.0, 1.0, -1.0)];
    assert!(ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &poly).is_none());
    assert_eq!(projected_solid_angle(DVec3::ZERO, DVec3::Z, &poly), 0.0);
}

/// A rectangle with two edges parallel to the receiver's normal (a light facing down
/// seen from a wall): those edges are meridians, whose end azimuths differ only by
/// rounding. From f32 points they must neither split the azimuth range nor lose
/// the polygon (it once returned `None` here, darkening the `assignment` wall by 1%).
#[test]
fn meridian_edges_from_f32_points() {
    let s = 0.3f32;
    let o = glam::Vec3::new(-0.5 * s, 2.4, 1.0 - 0.5 * s);
    let corners = [
        o,
        o + glam::Vec3::new(s, 0.0, 0.0),
        o + glam::Vec3::new(s, 0.0, s),
        o + glam::Vec3::new(0.0, 0.0, s),
    ]
    .map(|c| c.as_dvec3());
    let mut rng = crate::sampling::Rng32::new(3);
    for _ in 0..20_000 {
        let x = glam::Vec3::new(rng.next_f32() * 6.0 - 3.0, rng.next_f32() * 2.39, -3.0);
        let x = x.as_dvec3();
        let p = ProjectedPolygon::new(x, DVec3::Z, &corners).expect("visible");
        let lambert = projected_solid_angle(x, DVec3::Z, &corners);
        assert!(
            (p.projected_solid_angle() - lambert).abs() < 1e-10 * lambert,
            "{x}"
        );
        let (w, pdf) = p.sample(DVec2::new(rng.next_f32() as f64, rng.next_f32() as f64));
        assert!(w.is_finite() && pdf > 0.0 && p.pdf(w) > 0.0, "{x}");
    }
}
