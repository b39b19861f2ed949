//! The blocks against the scalar tests, and a flat scene against its BVH.

use glam::{Vec2, Vec3};

use super::*;
use crate::geometry::bvh::PACKET;
use crate::geometry::scene_geometry::Along;
use crate::geometry::shape::{Disk, Rectangle, Sphere, Triangle};
use crate::geometry::{Geometry, Mesh, NO_LIGHT};
use crate::sampling::rng::Rng32;

/// A random point in [−1, 1]³.
fn point(rng: &mut Rng32) -> Vec3 {
    Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - Vec3::ONE
}

/// A random shape of kind `kind` (0 triangle, 1 sphere, 2 rectangle, 3 disk) near the
/// origin; some degenerate.
fn shape(rng: &mut Rng32, kind: usize) -> Shape {
    let (p, a, b) = (point(rng), point(rng), point(rng));
    match kind {
        0 => Shape::Triangle(Triangle {
            p0: p,
            e1: a,
            e2: if rng.next_f32() < 0.1 { a * 2.0 } else { b },
            mesh: 0,
            index: 0,
        }),
        1 => Shape::Sphere(Sphere::new(p, 0.05 + a.x.abs())),
        2 => {
            let eb = a.cross(b).cross(a).normalize_or(Vec3::Y) * (0.2 + b.y.abs());
            Shape::Rectangle(
                Rectangle::new(p, a, eb)
                    .unwrap_or_else(|| Rectangle::new(p, Vec3::X, Vec3::Z).expect("a unit square")),
            )
        }
        _ => Shape::Disk(Disk::new(p, a.normalize_or(Vec3::Z), 0.1 + b.z.abs())),
    }
}

/// A ray from around the shapes towards them; a few not finite or without direction.
fn ray(rng: &mut Rng32, k: usize) -> Ray {
    let o = point(rng) * 3.0;
    let d = match k % 41 {
        0 => Vec3::ZERO,
        1 => Vec3::new(f32::NAN, 0.0, 1.0),
        2 => (point(rng) - o) * 1e-20,
        _ => point(rng) - o,
    };
    Ray::new(
        o,
        if k.is_multiple_of(2) {
            d.normalize_or(d)
        } else {
            d
        },
    )
}

/// (hit, t bits, uv bits) of the scalar test.
fn scalar(shape: &Shape, ray: &Ray, t_max: f32) -> (bool, u32, [u32; 2]) {
    match shape.intersect(ray, t_max) {
        Some(ShapeHit {
            t,
            uv: Vec2 { x, y },
        }) => (true, t.to_bits(), [x.to_bits(), y.to_bits()]),
        None => (false, 0, [0, 0]),
    }
}

/// The block of kind `S` made of `shapes`' shapes of that kind, against `ray`.
fn hits_of<S: ShapeBlock>(shapes: &[Shape], ray: &Ray, t_max: f32) -> Hits4 {
    let picked: Vec<S::Shape> = shapes.iter().filter_map(S::pick).collect();
    S::new(&picked).hits(ray, t_max)
}

/// The block of `shapes` (one to four of one analytic kind) against `ray`.
fn block_hits(shapes: &[Shape], ray: &Ray, t_max: f32) -> Hits4 {
    match shapes[0] {
        Shape::Sphere(_) => hits_of::<Sphere4>(shapes, ray, t_max),
        Shape::Rectangle(_) => hits_of::<Rect4>(shapes, ray, t_max),
        _ => hits_of::<Disk4>(shapes, ray, t_max),
    }
}

#[test]
fn every_lane_of_every_block_is_the_scalar_test_bit_for_bit() {
    let mut rng = Rng32::new(11);
    // Per kind (sphere, rectangle, disk): lanes hit, missed, and hit only without t_max.
    let (mut hits, mut misses, mut cut) = ([0; 3], [0; 3], [0; 3]);
    for round in 0..12_000 {
        let kind = 1 + round % 3;
        let count = 1 + round / 3 % 4;
        let shapes: Vec<Shape> = (0..count).map(|_| shape(&mut rng, kind)).collect();
        let ray = ray(&mut rng, round);
        let t_max = [f32::INFINITY, 1.5, 0.0][round / 12 % 3];
        let h = block_hits(&shapes, &ray, t_max);
        for lane in 0..blocks::LANES {
            let some = h.some.bitmask() >> lane & 1 == 1;
            let Some(s) = shapes.get(lane) else {
                assert!(!some, "an unused lane is never hit");
                continue;
            };
            let (hit, t, uv) = scalar(s, &ray, t_max);
            assert_eq!(some, hit, "{s:?} {ray:?} {t_max}");
            if hit && f32::from_bits(t).is_nan() {
                // Which NaN an operation returns is not fixed; that it is NaN is.
                assert!(h.t[lane].is_nan(), "{s:?} {ray:?}");
            } else if hit {
                assert_eq!(h.t[lane].to_bits(), t, "{s:?} {ray:?}");
                if kind == 2 {
                    assert_eq!([h.u[lane].to_bits(), h.v[lane].to_bits()], uv);
                }
                hits[kind - 1] += 1;
            } else {
                misses[kind - 1] += 1;
                cut[kind - 1] += scalar(s, &ray, f32::INFINITY).0 as u32;
            }
        }
    }
    for kind in 0..3 {
        let (h, m, c) = (hits[kind], misses[kind], cut[kind]);
        assert!(
            h > 200 && m > 5_000 && c > 200,
            "kind {kind}: {h} hits, {m} misses, {c} cut"
        );
    }
}

/// A scene of `n` random primitives of three kinds (all but kind `skip`), some
/// emitting: at most [`FLAT_MAX`] of them fill at most [`FLAT_BLOCKS`] blocks.
fn scene(rng: &mut Rng32, n: usize, skip: usize) -> Vec<Primitive> {
    (0..n)
        .map(|i| Primitive {
            shape: shape(rng, (skip + 1 + i % 3) % 4),
            material: i as u32,
            light: if i % 5 == 0 { i as u32 } else { NO_LIGHT },
        })
        .collect()
}

#[test]
fn a_flat_scene_answers_as_its_bvh_does() {
    let mut rng = Rng32::new(12);
    let (mut hits, mut ties, mut blocked, mut open) = (0, 0, 0, 0);
    let (mut lit, mut hidden) = (0, 0);
    for n in [1, 3, 4, 7, FLAT_MAX] {
        for round in 0..24 {
            // Three kinds in turn, or (every fourth scene) one kind alone, up to three
            // blocks of it: a closest hit carried from block to block of one kind.
            let prims = if round % 4 == 3 {
                let kind = round / 4 % 4;
                scene(&mut rng, n.max(5), 4)
                    .into_iter()
                    .map(|p| Primitive {
                        shape: shape(&mut rng, kind),
                        ..p
                    })
                    .collect()
            } else {
                scene(&mut rng, n, round % 4)
            };
            let flat = Geometry::new(prims.clone(), vec![Mesh::default()]);
            let tree = Geometry::new(prims, vec![Mesh::default()]).without_flat();
            assert!(flat.is_flat() && !tree.is_flat());
            assert!(!Geometry::new(scene(&mut rng, FLAT_MAX + 1, 0), vec![]).is_flat());
            for k in 0..400 {
                let ray = ray(&mut rng, k);
                if ray.d == Vec3::ZERO {
                    // The tree tests the shapes whose boxes hold the origin of such a
                    // ray (where a sphere reports a NaN hit), the blocks none: no
                    // renderer's ray has no direction.
                    continue;
                }
                let t_max = if k % 3 == 0 { 2.0 } else { f32::INFINITY };
                let (a, b) = (flat.intersect(&ray, t_max), tree.intersect(&ray, t_max));
                assert_eq!(
                    a.map(|h| h.t.to_bits()),
                    b.map(|h| h.t.to_bits()),
                    "{ray:?}"
                );
                if let (Some(a), Some(b)) = (a, b) {
                    hits += 1;
                    let (pa, pb) = (
                        &flat.primitives()[a.prim as usize],
                        &tree.primitives()[b.prim as usize],
                    );
                    if pa.material != pb.material {
                        // Only an exact tie may go the other way.
                        assert_eq!(
                            pa.shape.intersect(&ray, f32::INFINITY).map(|h| h.t),
                            Some(a.t)
                        );
                        ties += 1;
                    } else {
                        assert_eq!(
                            (a.p, a.ng, a.shape_uv, a.light),
                            (b.p, b.ng, b.shape_uv, b.light)
                        );
                    }
                }
                // A packet in a flat scene is its rays one at a time (lanes whose t_max
                // is not positive take no part).
                let lanes: [f32; PACKET] = std::array::from_fn(|l| [t_max, 0.0][l % 2]);
                let packet = flat.intersect_packet(&[ray; PACKET], &lanes);
                assert_eq!(packet[0].map(|h| h.t.to_bits()), a.map(|h| h.t.to_bits()));
                assert!(packet[1].is_none());
                let shadow = flat.occluded(&ray, t_max);
                assert_eq!(shadow, tree.occluded(&ray, t_max), "{ray:?} {t_max}");
                (blocked, open) = (blocked + shadow as u32, open + !shadow as u32);
                // A BSDF ray's first emitter (the emitters' blocks first where they are
                // fewer than the scene's) is the closest hit where it emits.
                let (seen, closest) = first_emitter_and_closest(&flat, &ray);
                assert_eq!(seen, closest, "{ray:?}");
                lit += seen.is_some() as u32;
                hidden += (seen.is_none() && flat.occluded(&ray, f32::INFINITY)) as u32;
            }
        }
    }
    assert!(hits > 5_000 && ties < hits / 50, "{hits} hits, {ties} ties");
    assert!(
        lit > 1_000 && hidden > 1_000,
        "{lit} emitters seen, {hidden} not"
    );
    assert!(
        blocked > 3_000 && open > 3_000,
        "{blocked} blocked, {open} open"
    );
}

/// An emitter met: its primitive and the bits of its distance.
type Met = Option<(u32, u32)>;

/// What `first_emitter` (no escape asked) reports of `ray`, and the closest hit where it
/// emits.
fn first_emitter_and_closest(g: &Geometry, ray: &Ray) -> (Met, Met) {
    let seen = match g.first_emitter(ray, false) {
        Along::Emitter(y) => Some((y.prim, y.t.to_bits())),
        Along::Escapes => panic!("an escape reported without being asked"),
        Along::Blocked => None,
    };
    let closest = g
        .intersect(ray, f32::INFINITY)
        .filter(|y| y.light != NO_LIGHT)
        .map(|y| (y.prim, y.t.to_bits()));
    (seen, closest)
}
