//! The geometry's queries on small scenes.

use super::*;
use crate::geometry::shape::{Rectangle, Sphere};
use crate::sampling::rng::Rng32;

/// Spheres on a grid (every `emit_every`-th one emitting) above a floor, and a
/// rectangle light that a sphere half hides (with `emit_every` 0, nothing emits).
fn scene(emit_every: usize) -> Geometry {
    let mut prims = Vec::new();
    let mut light = 0;
    for i in 0..40 {
        let c = Vec3::new(
            (i % 8) as f32 - 3.5,
            0.5 + (i / 8) as f32 * 0.3,
            (i / 8) as f32,
        );
        let emits = emit_every > 0 && i % emit_every == 0;
        prims.push(Primitive {
            shape: Shape::Sphere(Sphere::new(c, 0.3 + 0.02 * (i % 5) as f32)),
            material: 0,
            light: if emits { light } else { NO_LIGHT },
        });
        light += emits as u32;
    }
    let floor = Rectangle::new(Vec3::new(-5.0, 0.0, -5.0), Vec3::X * 10.0, Vec3::Z * 10.0);
    let panel = Rectangle::new(Vec3::new(-1.0, 2.0, 1.0), Vec3::X * 2.0, Vec3::Z * 2.0);
    prims.push(Primitive {
        shape: Shape::Rectangle(floor.expect("rectangle")),
        material: 0,
        light: NO_LIGHT,
    });
    prims.push(Primitive {
        shape: Shape::Rectangle(panel.expect("rectangle")),
        material: 0,
        light: if emit_every > 0 { light } else { NO_LIGHT },
    });
    Geometry::new(prims, Vec::new())
}

#[test]
fn emitter_hits_are_the_closest_hits_on_emitters() {
    // Emitters first (with and without escapes to tell), the closest hit (more than a
    // quarter of the primitives emit), and the any-hit escape test (none emit).
    for (emit_every, emitters_first) in [(7, true), (2, false), (0, true)] {
        let g = scene(emit_every);
        assert_eq!(g.emitters.is_some(), emitters_first);
        let mut rng = Rng32::new(17);
        let (mut seen, mut blocked, mut escaped) = (0, 0, 0);
        for _ in 0..20_000 {
            let o = Vec3::new(
                rng.next_f32() * 10.0 - 5.0,
                rng.next_f32() * 3.0 + 0.01,
                rng.next_f32() * 6.0 - 1.0,
            );
            let d = Vec3::new(
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
            );
            let ray = Ray::new(o, d.normalize());
            let closest = g.intersect(&ray, f32::INFINITY);
            let expected = match closest {
                Some(y) if y.light != NO_LIGHT => Some((y.prim, y.t)),
                _ => None,
            };
            let (got, escapes) = match g.first_emitter(&ray, true) {
                Along::Emitter(y) => (Some((y.prim, y.t)), false),
                Along::Escapes => (None, true),
                Along::Blocked => (None, false),
            };
            assert_eq!(got, expected);
            assert_eq!(escapes, closest.is_none());
            match g.first_emitter(&ray, false) {
                Along::Emitter(y) => assert_eq!(Some((y.prim, y.t)), expected),
                Along::Escapes => panic!("an escape reported without being asked"),
                Along::Blocked => assert_eq!(None, expected),
            }
            escaped += escapes as u32;
            seen += got.is_some() as u32;
            // Rays whose first emitter along them lies behind something else.
            let first_emitter = g.emitters.as_ref().and_then(|e| {
                e.bvh.closest_hit(&ray, f32::INFINITY, |k, r, t| {
                    g.prims[e.prims[k as usize] as usize]
                        .shape
                        .intersect(r, t)
                        .map(|h| h.t)
                })
            });
            blocked += (first_emitter.is_some() && got.is_none()) as u32;
        }
        assert!(
            (seen > 500 || emit_every == 0) && escaped > 500,
            "{seen} emitter hits, {escaped} escapes"
        );
        assert!(
            !emitters_first || emit_every == 0 || blocked > 100,
            "{blocked} hidden emitters"
        );
    }
}
