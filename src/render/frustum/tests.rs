//! Tests of the frustum culling: a culled rectangle has no ray that meets the box, and
//! boxes out of view are culled.

use glam::{Affine3A, DVec3, Vec2, Vec3};

use super::*;
use crate::sampling::rng::Rng32;

/// Whether the ray o + t·d, t ≥ 0, meets the box [lo, hi] (slab test in f64, with
/// touching counted as meeting).
fn ray_meets_box(o: DVec3, d: DVec3, lo: DVec3, hi: DVec3) -> bool {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for axis in 0..3 {
        if d[axis] == 0.0 {
            if o[axis] < lo[axis] || o[axis] > hi[axis] {
                return false;
            }
            continue;
        }
        let (a, b) = (
            (lo[axis] - o[axis]) / d[axis],
            (hi[axis] - o[axis]) / d[axis],
        );
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

fn uniform(rng: &mut Rng32, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * rng.next_f32()
}

fn point(rng: &mut Rng32, r: f32) -> Vec3 {
    Vec3::new(
        uniform(rng, -r, r),
        uniform(rng, -r, r),
        uniform(rng, -r, r),
    )
}

/// Over random cameras (mirrored ones and ones far from the origin among them), boxes
/// and rectangles of the film, no ray through a culled rectangle (its corners and 60
/// points inside) meets the box, however close the box is to the rectangle's cone:
/// the boxes are placed where the camera looks, so many rectangles are near its edge.
/// Both decisions are common, so the test sees both sides of every plane.
#[test]
fn culled_rectangles_have_no_ray_that_meets_the_box() {
    let mut rng = Rng32::new(7);
    let (mut culled, mut kept) = (0, 0);
    for case in 0..4000 {
        let far = if case % 4 == 3 { 1000.0 } else { 0.0 };
        let eye = point(&mut rng, 5.0) + Vec3::splat(far);
        let centre = eye + point(&mut rng, 4.0);
        let size = Vec3::new(
            uniform(&mut rng, 0.001, 3.0),
            uniform(&mut rng, 0.001, 3.0),
            uniform(&mut rng, 0.001, 3.0),
        );
        let bounds = Aabb {
            min: centre - size,
            max: centre + size,
        };
        let target = centre + point(&mut rng, 2.0);
        let up = point(&mut rng, 1.0);
        if (target - eye).cross(up).length() < 1e-3 {
            continue;
        }
        let (w, h) = (1 + rng.next_u32() % 300, 1 + rng.next_u32() % 200);
        let fov = uniform(&mut rng, 5.0, 150.0);
        let look = Camera::look_at(eye, target, up, fov, w, h);
        // Every other camera mirrored, as a Mitsuba `scale x="-1"` makes it.
        let camera = if case % 2 == 0 {
            look
        } else {
            let flip = Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
            Camera::new(look.to_world() * flip, fov, w, h)
        };
        let cull = FrustumCull::new(&camera, &[bounds]).expect("a finite box");
        let x0 = uniform(&mut rng, 0.0, w as f32).floor();
        let y0 = uniform(&mut rng, 0.0, h as f32).floor();
        let (x1, y1) = (
            x0 + 1.0 + (rng.next_u32() % 4) as f32,
            y0 + 1.0 + (rng.next_u32() % 2) as f32,
        );
        if !cull.misses((x0 as f64, y0 as f64), (x1 as f64, y1 as f64)) {
            kept += 1;
            continue;
        }
        culled += 1;
        let (lo, hi) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
        let corners = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)].map(|(x, y)| Vec2::new(x, y));
        let inside =
            (0..60).map(|_| Vec2::new(uniform(&mut rng, x0, x1), uniform(&mut rng, y0, y1)));
        for p in corners.into_iter().chain(inside.collect::<Vec<_>>()) {
            let ray = camera.ray(p);
            assert!(
                !ray_meets_box(ray.o.as_dvec3(), ray.d.as_dvec3(), lo, hi),
                "case {case}: the ray through {p} meets a box the rectangle \
                 [{x0}, {x1}] × [{y0}, {y1}] culled"
            );
        }
    }
    assert!(culled > 1000 && kept > 1000, "culled {culled}, kept {kept}");
}

/// A box in the middle of the view is seen through the middle of the film and not
/// through its corner; a box behind the camera, or beside it, through no part of it.
#[test]
fn boxes_out_of_view_are_culled() {
    let camera = Camera::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y, 60.0, 64, 48);
    let unit = |c: Vec3| Aabb {
        min: c - Vec3::splat(0.5),
        max: c + Vec3::splat(0.5),
    };
    let whole = |cull: &FrustumCull| cull.misses((0.0, 0.0), (64.0, 48.0));
    let ahead = FrustumCull::new(&camera, &[unit(Vec3::new(0.0, 0.0, 10.0))]).unwrap();
    assert!(!ahead.misses((31.0, 23.0), (33.0, 25.0)));
    assert!(ahead.misses((0.0, 0.0), (4.0, 2.0)));
    assert!(!whole(&ahead));
    let behind = FrustumCull::new(&camera, &[unit(Vec3::new(0.0, 0.0, -10.0))]).unwrap();
    assert!(whole(&behind));
    // Camera space has x to the left: a box at +x is seen on the film's left.
    let left = FrustumCull::new(&camera, &[unit(Vec3::new(5.0, 0.0, 10.0))]).unwrap();
    assert!(!left.misses((0.0, 20.0), (4.0, 28.0)));
    assert!(left.misses((60.0, 20.0), (64.0, 28.0)));
    let beside = FrustumCull::new(&camera, &[unit(Vec3::new(20.0, 0.0, 1.0))]).unwrap();
    assert!(whole(&beside));
    // The camera inside the box sees it everywhere.
    let around = FrustumCull::new(&camera, &[unit(Vec3::ZERO)]).unwrap();
    assert!(!around.misses((0.0, 0.0), (1.0, 1.0)));
    // Of two boxes, each is seen where it is.
    let both = [
        unit(Vec3::new(5.0, 0.0, 10.0)),
        unit(Vec3::new(-5.0, 0.0, 10.0)),
    ];
    let two = FrustumCull::new(&camera, &both).unwrap();
    assert!(!two.misses((0.0, 20.0), (4.0, 28.0)));
    assert!(!two.misses((60.0, 20.0), (64.0, 28.0)));
    assert!(two.misses((30.0, 20.0), (34.0, 28.0)));
    // No box (an empty scene) is seen nowhere; an infinite box disables culling.
    assert!(
        FrustumCull::new(&camera, &[Aabb::EMPTY])
            .unwrap()
            .misses((0.0, 0.0), (64.0, 48.0))
    );
    let infinite = Aabb {
        min: Vec3::splat(f32::NEG_INFINITY),
        max: Vec3::ZERO,
    };
    assert!(FrustumCull::new(&camera, &[infinite]).is_none());
}
