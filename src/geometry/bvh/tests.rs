//! Agreement of BVH queries with brute force over every primitive, on random triangle
//! and sphere soups of several sizes, with random, inside-the-box and axis-parallel rays.

use glam::{Vec2, Vec3};

use super::Bvh;
use crate::geometry::triangle::intersect_triangle;
use crate::geometry::{Aabb, Ray};
use crate::sampling::Rng32;
use crate::sampling::warp::sphere::square_to_uniform_sphere;

/// A test primitive: what a scene enum of mixed shapes looks like to the BVH.
#[derive(Clone, Copy, Debug)]
enum Shape {
    Triangle([Vec3; 3]),
    Sphere { centre: Vec3, radius: f32 },
}

impl Shape {
    fn bounds(&self) -> Aabb {
        match *self {
            Shape::Triangle(p) => Aabb::from_points(&p),
            Shape::Sphere { centre, radius } => Aabb {
                min: centre - radius,
                max: centre + radius,
            },
        }
    }

    /// Hit distance in (0, t_max).
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        match *self {
            Shape::Triangle([p0, p1, p2]) => {
                intersect_triangle(ray, p0, p1 - p0, p2 - p0, t_max).map(|h| h.t)
            }
            Shape::Sphere { centre, radius } => {
                // |o + t·d − c|² = r²: a t² + 2 b t + c = 0.
                let oc = ray.o - centre;
                let (a, b, c) = (
                    ray.d.length_squared(),
                    oc.dot(ray.d),
                    oc.length_squared() - radius * radius,
                );
                let disc = b * b - a * c;
                if disc < 0.0 || a == 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                [(-b - root) / a, (-b + root) / a]
                    .into_iter()
                    .find(|&t| t > 0.0 && t < t_max)
            }
        }
    }
}

fn point(rng: &mut Rng32, scale: f32) -> Vec3 {
    Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * scale
}

fn direction(rng: &mut Rng32) -> Vec3 {
    square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32())).0
}

/// `n` random shapes in [0, 10]³: small triangles, some flat in an axis plane, or spheres.
fn soup(n: usize, spheres: bool, rng: &mut Rng32) -> Vec<Shape> {
    (0..n)
        .map(|i| {
            let centre = point(rng, 10.0);
            if spheres {
                Shape::Sphere {
                    centre,
                    radius: 0.05 + rng.next_f32(),
                }
            } else {
                let mut p = [
                    centre,
                    centre + point(rng, 2.0) - 1.0,
                    centre + point(rng, 2.0) - 1.0,
                ];
                if i % 3 == 0 {
                    // Flat along z: a degenerate box.
                    p.iter_mut().for_each(|q| q.z = centre.z);
                }
                Shape::Triangle(p)
            }
        })
        .collect()
}

/// Random rays: from outside the soup, from inside primitive boxes, and axis-parallel
/// ones with exact zero (and −0) direction components.
fn rays(shapes: &[Shape], count: usize, rng: &mut Rng32) -> Vec<Ray> {
    (0..count)
        .map(|i| match i % 4 {
            0 => Ray::new(point(rng, 14.0) - 2.0, direction(rng)),
            1 if !shapes.is_empty() => {
                let b = shapes[i % shapes.len()].bounds();
                Ray::new(b.min + b.extent() * point(rng, 1.0), direction(rng))
            }
            2 => {
                let mut d = Vec3::ZERO;
                d[i % 3] = if i % 8 < 4 { 1.0 } else { -1.0 };
                d[(i + 1) % 3] = -0.0;
                Ray::new(point(rng, 10.0), d)
            }
            _ => Ray::new(point(rng, 10.0), direction(rng) * (0.5 + rng.next_f32())),
        })
        .collect()
}

/// Closest hit over every primitive.
fn brute_closest(shapes: &[Shape], ray: &Ray, t_max: f32) -> Option<f32> {
    shapes
        .iter()
        .filter_map(|s| s.intersect(ray, t_max))
        .min_by(f32::total_cmp)
}

#[test]
fn queries_agree_with_brute_force() {
    for spheres in [false, true] {
        for n in [0usize, 1, 2, 5, 33, 1000] {
            let mut rng = Rng32::new(1000 * n as u64 + spheres as u64);
            let shapes = soup(n, spheres, &mut rng);
            let bounds: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
            for bvh in [Bvh::build(&bounds), Bvh::build_blocks(&bounds)] {
                check_queries(&bvh, &shapes, &mut rng);
            }
        }
    }
}

/// Checks a tree's closest-hit and any-hit answers against brute force.
fn check_queries(bvh: &Bvh, shapes: &[Shape], rng: &mut Rng32) {
    let n = shapes.len();
    let spheres = matches!(shapes.first(), Some(Shape::Sphere { .. }));
    // Padding slots of a block build hold a primitive nothing hits.
    let nothing = Shape::Triangle([Vec3::ZERO; 3]);
    let ordered: Vec<Shape> = bvh
        .primitive_order()
        .iter()
        .map(|&i| shapes.get(i as usize).copied().unwrap_or(nothing))
        .collect();
    for ray in rays(shapes, 2000, rng) {
        for t_max in [f32::INFINITY, 3.0] {
            let expected = brute_closest(shapes, &ray, t_max);
            let got = bvh.closest_hit(&ray, t_max, |p, r, t| ordered[p as usize].intersect(r, t));
            assert_eq!(
                got.map(|h| h.1),
                expected,
                "n {n} spheres {spheres} ray {ray:?} t_max {t_max}"
            );
            if let Some((p, t)) = got {
                assert_eq!(
                    shapes[bvh.primitive_order()[p as usize] as usize].intersect(&ray, t_max),
                    Some(t)
                );
            }
            let occluded = bvh.any_hit(&ray, t_max, |p, r, t| {
                ordered[p as usize].intersect(r, t).is_some()
            });
            assert_eq!(occluded, expected.is_some(), "any-hit, n {n} ray {ray:?}");
            if let Some(t) = expected {
                // A shadow ray that stops short of the closest hit sees nothing.
                let short = bvh.any_hit(&ray, t * 0.999, |p, r, t| {
                    ordered[p as usize].intersect(r, t).is_some()
                });
                assert!(!short, "n {n} ray {ray:?} t {t}");
            }
        }
    }
}

#[test]
fn block_builds_lay_leaves_out_in_full_blocks_of_four() {
    let mut rng = Rng32::new(77);
    for spheres in [false, true] {
        let shapes = soup(5000, spheres, &mut rng);
        let bounds: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
        let (single, blocks) = (Bvh::build(&bounds), Bvh::build_blocks(&bounds));
        let order = blocks.primitive_order();
        assert_eq!(order.len() % super::BLOCK, 0);
        let mut seen = vec![0; shapes.len()];
        for block in order.chunks(super::BLOCK) {
            let used = block.iter().take_while(|&&i| i != super::PADDING).count();
            assert!(used > 0 && block[used..].iter().all(|&i| i == super::PADDING));
            block[..used].iter().for_each(|&i| seen[i as usize] += 1);
        }
        assert!(seen.iter().all(|&k| k == 1));
        // The block SAH fills leaves: on average at least three of four slots, and the
        // tree has well under the one-primitive-leaf tree's nodes.
        let fill = shapes.len() as f32 / order.len() as f32;
        assert!(fill > 0.75, "fill {fill}");
        assert!(
            (blocks.node_count() as f32) < 0.7 * single.node_count() as f32,
            "{} vs {} nodes",
            blocks.node_count(),
            single.node_count()
        );
    }
}

#[test]
fn empty_and_degenerate_inputs_build_and_answer() {
    let ray = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::Z);
    let empty = Bvh::build(&[]);
    assert!(
        empty
            .closest_hit(&ray, f32::INFINITY, |_, _, _| Some(1.0))
            .is_none()
    );
    assert!(!empty.any_hit(&ray, f32::INFINITY, |_, _, _| true));
    assert!(empty.bounds().is_empty() && empty.node_count() == 0);

    // Identical boxes, a point box, a NaN box and an empty box.
    let unit = Aabb {
        min: Vec3::ZERO,
        max: Vec3::ONE,
    };
    let nan = Aabb {
        min: Vec3::splat(f32::NAN),
        max: Vec3::ONE,
    };
    let mut bounds = vec![unit; 100];
    bounds.extend([Aabb::EMPTY.grow(Vec3::splat(0.5)), nan, Aabb::EMPTY]);
    let bvh = Bvh::build(&bounds);
    let mut offered = vec![false; bounds.len()];
    bvh.closest_hit(&ray, f32::INFINITY, |p, _, _| {
        offered[bvh.primitive_order()[p as usize] as usize] = true;
        None
    });
    assert!(
        offered[..101].iter().all(|&o| o),
        "every box on the ray is offered"
    );
    assert!(bvh.depth() > 0 && bvh.sah_cost(1.0).is_finite());
}

#[test]
fn a_ray_with_nan_finds_nothing_and_does_not_panic() {
    let bvh = Bvh::build(&[Aabb {
        min: Vec3::ZERO,
        max: Vec3::ONE,
    }]);
    for ray in [
        Ray::new(Vec3::splat(f32::NAN), Vec3::Z),
        Ray::new(Vec3::ZERO, Vec3::ZERO),
    ] {
        let hit = bvh.closest_hit(&ray, f32::INFINITY, |_, _, _| None);
        assert!(hit.is_none());
    }
}

/// A cut of the tree holds every primitive in one of its boxes, has no more boxes than
/// asked (or than the root's children, where those are more), and refines a deep tree
/// towards the count: for trees of single primitives and of leaf blocks.
#[test]
fn cut_boxes_hold_every_primitive() {
    let mut rng = Rng32::new(11);
    for n in [1usize, 3, 4, 17, 500] {
        let boxes: Vec<Aabb> = (0..n)
            .map(|_| {
                let c = point(&mut rng, 10.0);
                Aabb {
                    min: c,
                    max: c + point(&mut rng, 0.3),
                }
            })
            .collect();
        for bvh in [Bvh::build(&boxes), Bvh::build_blocks(&boxes)] {
            for max in [1, 4, 16, 64] {
                let cut = bvh.cut(max);
                assert!(
                    !cut.is_empty() && cut.len() <= max.max(4),
                    "n {n} max {max}"
                );
                for b in &boxes {
                    assert!(
                        cut.iter()
                            .any(|c| c.min.cmple(b.min).all() && c.max.cmpge(b.max).all()),
                        "n {n} max {max}: a primitive outside the cut"
                    );
                }
                if n == 500 && max == 64 {
                    assert!(cut.len() > 32, "a deep tree refines: {}", cut.len());
                }
            }
        }
    }
    assert!(Bvh::build(&[]).cut(16).is_empty());
}
