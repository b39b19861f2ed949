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

/// A uniform point of the box from `lo` of extent `size` (x, then y, then z drawn).
fn point_in(rng: &mut Rng32, lo: Vec3, size: Vec3) -> Vec3 {
    let x = rng.next_f32() * size.x + lo.x;
    let y = rng.next_f32() * size.y + lo.y;
    let z = rng.next_f32() * size.z + lo.z;
    Vec3::new(x, y, z)
}

/// A ray from a uniform point of the box `(lo, size)` along a direction drawn in the
/// unit cube from `d_lo`, normalised.
fn random_ray(rng: &mut Rng32, (lo, size): (Vec3, Vec3), d_lo: Vec3) -> Ray {
    let o = point_in(rng, lo, size);
    let d = point_in(rng, d_lo, Vec3::ONE);
    Ray::new(o, d.normalize())
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
        let origins = (Vec3::new(-5.0, 0.01, -1.0), Vec3::new(10.0, 3.0, 6.0));
        for _ in 0..20_000 {
            let ray = random_ray(&mut rng, origins, Vec3::splat(-0.5));
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

/// A scene small enough to be tested without a tree: six spheres (the first emitting
/// when `sphere_emits`), a floor, a rectangle light that a sphere half hides, and a
/// shelf below part of the light.
fn small_scene(sphere_emits: bool) -> Geometry {
    let mut prims: Vec<Primitive> = (0..4)
        .map(|i| Primitive {
            shape: Shape::Sphere(Sphere::new(
                Vec3::new(i as f32 - 1.5, 0.6 + 0.2 * i as f32, 0.5 * (i % 2) as f32),
                0.35,
            )),
            material: 0,
            light: if sphere_emits && i == 0 { 1 } else { NO_LIGHT },
        })
        .collect();
    let floor = Rectangle::new(Vec3::new(-5.0, 0.0, -5.0), Vec3::X * 10.0, Vec3::Z * 10.0);
    let panel = Rectangle::new(Vec3::new(-1.0, 2.0, 0.0), Vec3::X * 2.0, Vec3::Z * 1.0);
    let shelf = Rectangle::new(Vec3::new(-0.3, 1.7, 0.2), Vec3::X * 0.6, Vec3::Z * 0.4);
    for (rect, light) in [(floor, NO_LIGHT), (panel, 0), (shelf, NO_LIGHT)] {
        prims.push(Primitive {
            shape: Shape::Rectangle(rect.expect("rectangle")),
            material: 0,
            light,
        });
    }
    // Two more spheres: a second block of them, so that the scene's three blocks
    // outnumber the emitters' two when a sphere emits, and the emitters stay at most a
    // quarter of the primitives (the rule for the tree this scene is compared with).
    for i in 0..2 {
        prims.push(Primitive {
            shape: Shape::Sphere(Sphere::new(Vec3::new(3.0 + i as f32, 0.3, -2.0), 0.3)),
            material: 0,
            light: NO_LIGHT,
        });
    }
    Geometry::new(prims, Vec::new())
}

/// In a scene tested without a tree, the emitters-first query finds what the closest
/// hit finds, and what the same scene's tree finds: the same primitive at the same
/// distance, or nothing, for rays that meet a light, miss every light, or meet one
/// behind something else; with an escape to tell, the closest hit decides.
#[test]
fn flat_emitter_hits_are_the_closest_hits_on_emitters() {
    for sphere_emits in [false, true] {
        let g = small_scene(sphere_emits);
        assert!(g.is_flat() && g.flat_emitters.is_some());
        let tree = small_scene(sphere_emits).without_flat();
        assert!(
            tree.emitters.is_some(),
            "the tree tests its emitters first too"
        );
        let mut rng = Rng32::new(29);
        let (mut seen, mut hidden, mut missed, mut shelved) = (0, 0, 0, 0);
        // Origins below the light, directions rising.
        let origins = (Vec3::new(-3.0, 0.01, -2.0), Vec3::new(6.0, 1.8, 4.0));
        let rising = Vec3::new(-0.5, 0.0, -0.5);
        for _ in 0..40_000 {
            let ray = random_ray(&mut rng, origins, rising);
            let closest = g.intersect(&ray, f32::INFINITY);
            let expected = match closest {
                Some(y) if y.light != NO_LIGHT => Some((y.prim, y.t)),
                _ => None,
            };
            let got = |g: &Geometry, tell_escape| match g.first_emitter(&ray, tell_escape) {
                Along::Emitter(y) => Some((y.prim, y.t)),
                Along::Escapes | Along::Blocked => None,
            };
            assert_eq!(got(&g, false), expected, "{ray:?}");
            // With an escape to tell, the closest hit decides: the escape is reported.
            let escapes = matches!(g.first_emitter(&ray, true), Along::Escapes);
            assert_eq!(escapes, closest.is_none(), "{ray:?}");
            assert_eq!(got(&tree, false), expected, "{ray:?}");
            let on_light = g
                .flat_emitters
                .as_ref()
                .and_then(|e| e.closest_hit(&ray, 1e30));
            seen += expected.is_some() as u32;
            hidden += (on_light.is_some() && expected.is_none()) as u32;
            missed += on_light.is_none() as u32;
            // Lights hidden by a rectangle (the shelf: these rays rise, so not the floor).
            let by_rect = closest.is_some_and(|y| {
                y.light == NO_LIGHT && matches!(g.prims[y.prim as usize].shape, Shape::Rectangle(_))
            });
            shelved += (on_light.is_some() && by_rect) as u32;
        }
        assert!(
            seen > 2_000 && hidden > 200 && missed > 10_000 && shelved > 50,
            "{seen} lights seen, {hidden} hidden ({shelved} by the shelf), {missed} rays \
             missing every light"
        );
    }
}
