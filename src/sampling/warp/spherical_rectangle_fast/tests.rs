//! The fast rectangle map against the f64 version: solid angles, domains, samples, and
//! the placements where both give `None`.

use super::super::SphericalRectangle;
use super::*;

/// Shading points and rectangles from near, far, grazing and off-centre views.
fn cases() -> Vec<(Vec3, Vec3, Vec3, Vec3)> {
    let mut out = Vec::new();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    for i in 0..6000 {
        // A third of the points far away (down to 10⁻⁶ sr), a third near the plane.
        let far = if i % 3 == 0 {
            10f32.powf(next() * 3.0)
        } else {
            1.0
        };
        let height = if i % 3 == 1 {
            10f32.powf(-4.0 * next())
        } else {
            next() * 3.0
        };
        let p = Vec3::new(next() * 8.0 - 4.0, next() * 8.0 - 4.0, -height) * far;
        let corner = Vec3::new(next() * 2.0 - 1.0, next() * 2.0 - 1.0, 0.0);
        let (w, h) = (0.01 + next() * 3.0, 0.01 + next() * 3.0);
        let a = next() * std::f32::consts::TAU;
        let ex = Vec3::new(a.cos(), a.sin(), 0.0) * w;
        let ey = Vec3::new(-a.sin(), a.cos(), 0.0) * h;
        out.push((p, corner, ex, ey));
    }
    out
}

/// S by the same two triangles with f64 `atan2`: the oracle for the fast S.
fn oracle(p: Vec3, corner: Vec3, ex: Vec3, ey: Vec3) -> f64 {
    let (p, o, ex, ey) = (
        p.as_dvec3(),
        corner.as_dvec3(),
        ex.as_dvec3(),
        ey.as_dvec3(),
    );
    let (a, b, cc, d) = (o - p, o + ex - p, o + ex + ey - p, o + ey - p);
    let tri = |a: DVec3, b: DVec3, c: DVec3| {
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        2.0 * a.dot(b.cross(c)).abs().atan2(den)
    };
    tri(a, b, cc) + tri(a, cc, d)
}

#[test]
fn solid_angle_and_domain_agree_with_the_f64_version() {
    let (mut compared, mut worst, mut worst_f64) = (0, 0.0f64, 0.0f64);
    for (p, corner, ex, ey) in cases() {
        let fast = FastSphericalRectangle::new(p, corner, ex, ey);
        let exact = SphericalRectangle::new(p, corner, ex, ey);
        match (fast, exact) {
            (Some(f), Some(e)) => {
                let s = oracle(p, corner, ex, ey);
                let rel = (f.solid_angle / s - 1.0).abs();
                worst = worst.max(rel);
                worst_f64 = worst_f64.max((e.solid_angle() as f64 / s - 1.0).abs());
                assert_eq!(
                    FastSphericalRectangle::solid_angle_at(p, corner, ex, ey),
                    Some(f.solid_angle())
                );
                compared += 1;
            }
            (None, None) => {}
            // Only where S rounds across the bound.
            (f, e) => {
                let s = f.map(|f| f.solid_angle()).or(e.map(|e| e.solid_angle()));
                let s = s.expect("one is Some") as f64;
                assert!((s / MIN_SOLID_ANGLE - 1.0).abs() < 1e-5, "{f:?} vs {e:?}");
            }
        }
    }
    assert!(compared > 5000, "only {compared} cases compared");
    // The series below 0.05 rad, the f32 polynomial (4·10⁻⁷ rad) above: 3.4·10⁻⁶
    // measured.
    assert!(worst < 1e-5, "worst relative error of S {worst}");
    eprintln!("worst relative error of S: fast {worst:.1e}, f64 version {worst_f64:.1e}");
}

#[test]
fn samples_agree_with_the_f64_version() {
    // The fast sample of u is the f64 sample of a u' next to u (u' = the f64 map's
    // inverse at the fast direction) as closely as the f64 sample of u is, and a
    // point on the rectangle.
    let mut worst = 0.0f32;
    for (p, corner, ex, ey) in cases() {
        let Some(fast) = FastSphericalRectangle::new(p, corner, ex, ey) else {
            continue;
        };
        let exact = SphericalRectangle::new(p, corner, ex, ey).expect("f64 takes it too");
        for u in [
            Vec2::new(0.5, 0.5),
            Vec2::new(0.01, 0.99),
            Vec2::new(0.99, 0.01),
            Vec2::new(0.3, 0.7),
            Vec2::new(0.999_999, 0.999_999),
        ] {
            let (w, offset, pdf) = fast.sample(u);
            // Both measured the same way, so the f32 rounding of a far rectangle's
            // direction (up to 10⁻³ of the square at 10⁻⁷ sr) cancels out.
            let e_fast = (exact.to_square(w) - u).abs().max_element();
            let e_f64 = (exact.to_square(exact.sample(u).0) - u).abs().max_element();
            let e = e_fast - e_f64;
            worst = worst.max(e);
            assert!((w.length() - 1.0).abs() < 1e-5 && pdf == 1.0 / fast.solid_angle());
            assert!((offset.normalize() - w).length() < 1e-5);
            // The point lies on the rectangle, to f32 rounding of its coordinates.
            let q = p + offset - corner;
            let (a, b) = (
                q.dot(ex) / ex.length_squared(),
                q.dot(ey) / ey.length_squared(),
            );
            let tol = 1e-4 * (1.0 + p.length() / ex.length().min(ey.length()));
            assert!(
                (-tol..=1.0 + tol).contains(&a) && (-tol..=1.0 + tol).contains(&b),
                "({a}, {b}) off the rectangle"
            );
        }
    }
    // 4·10⁻⁵ measured, on points 10⁻⁴ above the plane, where the f64 version's
    // γ sums cancel (its S is then off by 2·10⁻⁶ relative, the fast one's by 10⁻⁷:
    // checked against 50-digit arithmetic).
    assert!(worst < 1e-4, "worst error {worst} in the unit square");
}

#[test]
fn in_plane_skewed_and_tiny_rectangles_give_none() {
    let r = |p: Vec3, c: Vec3, ex: Vec3, ey: Vec3| FastSphericalRectangle::new(p, c, ex, ey);
    assert!(r(Vec3::ZERO, Vec3::X, Vec3::X, Vec3::Y).is_none());
    assert!(r(Vec3::ZERO, Vec3::Z * 1e5, Vec3::X * 1e-2, Vec3::Y * 1e-2).is_none());
    assert!(r(Vec3::ZERO, Vec3::Z, Vec3::X, Vec3::X + Vec3::Y).is_none());
    assert!(r(Vec3::ZERO, Vec3::Z, Vec3::ZERO, Vec3::Y).is_none());
    let square = r(
        Vec3::ZERO,
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::X * 2.0,
        Vec3::Y * 2.0,
    );
    // 4·asin(1/2) = 2π/3 (as the f64 version's test).
    let s = square.expect("visible").solid_angle();
    assert!((s - 2.0 * std::f32::consts::PI / 3.0).abs() < 1e-6);
}
