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

/// Where case `case` takes place: every other pair of cases 1 000 units from the
/// origin (rays and hits are rounded relative to their coordinates).
fn place(rng: &mut Rng32, case: u32) -> Vec3 {
    let far = if (case / 2) % 2 == 1 { 1000.0 } else { 0.0 };
    point(rng, 5.0) + Vec3::X * far
}

/// A random camera for case `case` within 5 units of `centre`, looking near it, with a
/// field of view of 5° to 170°: every other one mirrored (as a Mitsuba `scale x="-1"`
/// makes it).
fn random_camera(rng: &mut Rng32, case: u32, centre: Vec3) -> Option<Camera> {
    let eye = centre + point(rng, 5.0);
    let target = centre + point(rng, 2.0);
    let up = point(rng, 1.0);
    if (target - eye).cross(up).length() < 1e-3 * (target - eye).length() {
        return None;
    }
    let (w, h) = (1 + rng.next_u32() % 300, 1 + rng.next_u32() % 200);
    let fov = uniform(rng, 5.0, 170.0);
    let look = Camera::look_at(eye, target, up, fov, w, h);
    Some(if case.is_multiple_of(2) {
        look
    } else {
        let flip = Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        Camera::new(look.to_world() * flip, fov, w, h)
    })
}

/// A film rectangle of 1 to 4 × 1 to 2 pixels at a random place of `camera`'s film.
fn random_rectangle(rng: &mut Rng32, camera: &Camera) -> (Vec2, Vec2) {
    let x0 = uniform(rng, 0.0, camera.width as f32).floor();
    let y0 = uniform(rng, 0.0, camera.height as f32).floor();
    let x1 = x0 + 1.0 + (rng.next_u32() % 4) as f32;
    let y1 = y0 + 1.0 + (rng.next_u32() % 2) as f32;
    (Vec2::new(x0, y0), Vec2::new(x1, y1))
}

fn misses(cull: &FrustumCull, (a, b): (Vec2, Vec2)) -> bool {
    cull.misses((a.x as f64, a.y as f64), (b.x as f64, b.y as f64))
}

/// Over random cameras, boxes (flat ones among them, as rectangles' are) and rectangles
/// of the film, no ray through a culled rectangle (its corners and 60 points inside)
/// meets the box. The boxes are placed where the camera looks, so that both decisions
/// are common and the test sees both sides of every plane.
#[test]
fn culled_rectangles_have_no_ray_that_meets_the_box() {
    let mut rng = Rng32::new(7);
    let (mut culled, mut kept) = (0, 0);
    for case in 0..4000 {
        let centre = place(&mut rng, case);
        let mut size = Vec3::new(
            uniform(&mut rng, 0.001, 3.0),
            uniform(&mut rng, 0.001, 3.0),
            uniform(&mut rng, 0.001, 3.0),
        );
        if case % 3 == 0 {
            size[(case / 3 % 3) as usize] = 0.0;
        }
        let bounds = Aabb {
            min: centre - size,
            max: centre + size,
        };
        let Some(camera) = random_camera(&mut rng, case, centre) else {
            continue;
        };
        let cull = FrustumCull::new(&camera, &[bounds]).expect("a finite box");
        let (a, b) = random_rectangle(&mut rng, &camera);
        if !misses(&cull, (a, b)) {
            kept += 1;
            continue;
        }
        culled += 1;
        let (lo, hi) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
        let corners = [(a.x, a.y), (b.x, a.y), (a.x, b.y), (b.x, b.y)];
        let inside: Vec<Vec2> = (0..60)
            .map(|_| Vec2::new(uniform(&mut rng, a.x, b.x), uniform(&mut rng, a.y, b.y)))
            .collect();
        for p in corners
            .map(|(x, y)| Vec2::new(x, y))
            .into_iter()
            .chain(inside)
        {
            let ray = camera.ray(p);
            assert!(
                !ray_meets_box(ray.o.as_dvec3(), ray.d.as_dvec3(), lo, hi),
                "case {case}: the ray through {p} meets a box the rectangle {a}–{b} culled"
            );
        }
    }
    assert!(culled > 1000 && kept > 1000, "culled {culled}, kept {kept}");
}

/// A box that a ray through the edge or corner of a rectangle meets (a point box on
/// that ray, the tightest case: its projection is the edge itself, up to rounding) is
/// never culled with the rectangle. Without the margins about half the cases fail.
#[test]
fn boxes_met_on_a_rectangle_edge_are_kept() {
    let mut rng = Rng32::new(13);
    let mut tested = 0;
    for case in 0..4000 {
        let centre = place(&mut rng, case);
        let Some(camera) = random_camera(&mut rng, case, centre) else {
            continue;
        };
        let (a, b) = random_rectangle(&mut rng, &camera);
        // A point of the rectangle's boundary: a corner, or on one of its edges.
        let t = uniform(&mut rng, 0.0, 1.0);
        let p = match case % 5 {
            0 => Vec2::new(a.x, a.y + (b.y - a.y) * t),
            1 => Vec2::new(b.x, a.y + (b.y - a.y) * t),
            2 => Vec2::new(a.x + (b.x - a.x) * t, a.y),
            3 => Vec2::new(a.x + (b.x - a.x) * t, b.y),
            _ => Vec2::new(b.x, b.y),
        };
        let ray = camera.ray(p);
        let q = ray.o + ray.d * uniform(&mut rng, 0.01, 50.0);
        let cull = FrustumCull::new(&camera, &[Aabb { min: q, max: q }]).expect("finite");
        assert!(
            !misses(&cull, (a, b)),
            "case {case}: the point {q} on the ray through {p} is culled with {a}–{b}"
        );
        tested += 1;
    }
    assert!(tested > 3500, "{tested} cases");
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
    let nan = Aabb {
        min: Vec3::new(0.0, f32::NAN, 0.0),
        max: Vec3::ONE,
    };
    assert!(FrustumCull::new(&camera, &[nan]).is_none());
}
