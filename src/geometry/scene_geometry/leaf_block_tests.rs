//! Leaf blocks against one-primitive leaves: the same scene built both ways answers
//! every query alike (hit distances bit for bit; the primitive may differ only where
//! two meet the ray at the same distance).

use glam::Vec3;

use super::*;
use crate::geometry::shape::{Rectangle, Sphere, Triangle};
use crate::sampling::rng::Rng32;

/// A triangulated height field (neighbouring triangles share edges, so rays meet
/// ties) with spheres and rectangles among the triangles, some of them emitting.
fn mixed_scene(use_blocks: bool) -> Geometry {
    let mut prims = Vec::new();
    let n = 24;
    let height = |i: usize, j: usize| 0.3 * ((i * 7 + j * 3) % 5) as f32 / 5.0;
    let vertex = |i: usize, j: usize| Vec3::new(i as f32 * 0.25, height(i, j), j as f32 * 0.25);
    for i in 0..n {
        for j in 0..n {
            let [a, b, c, d] = [
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i, j + 1),
                vertex(i + 1, j + 1),
            ];
            for (k, [p0, p1, p2]) in [[a, b, c], [b, d, c]].into_iter().enumerate() {
                let index = (2 * (i * n + j) + k) as u32;
                prims.push(Primitive {
                    shape: Shape::Triangle(Triangle {
                        p0,
                        e1: p1 - p0,
                        e2: p2 - p0,
                        mesh: 0,
                        index,
                    }),
                    material: 1,
                    light: if index.is_multiple_of(97) {
                        index
                    } else {
                        NO_LIGHT
                    },
                });
            }
        }
    }
    for k in 0..60 {
        let c = Vec3::new(
            (k % 10) as f32 * 0.6,
            0.5 + (k / 10) as f32 * 0.1,
            (k / 10) as f32,
        );
        prims.push(Primitive {
            shape: Shape::Sphere(Sphere::new(c, 0.15)),
            material: 2,
            light: if k % 4 == 0 { 5000 + k } else { NO_LIGHT },
        });
    }
    let panel = Rectangle::new(Vec3::new(1.0, 1.2, 1.0), Vec3::X * 2.0, Vec3::Z * 2.0);
    prims.push(Primitive {
        shape: Shape::Rectangle(panel.expect("rectangle")),
        material: 3,
        light: 9999,
    });
    Geometry::build(prims, vec![Mesh::default()], use_blocks)
}

#[test]
fn leaf_blocks_answer_as_single_primitive_leaves_do() {
    let (blocks, single) = (mixed_scene(true), mixed_scene(false));
    assert!(blocks.blocks.is_some() && single.blocks.is_none());
    assert!(wants_blocks(&single.prims));
    let mut rng = Rng32::new(5);
    let (mut hits, mut ties, mut blocked) = (0, 0, 0);
    for _ in 0..20_000 {
        let o = Vec3::new(
            rng.next_f32() * 6.0,
            rng.next_f32() * 2.0 - 0.2,
            rng.next_f32() * 6.0,
        );
        let d = Vec3::new(
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
        );
        let ray = Ray::new(o, d.normalize());
        let t_max = 0.5 + rng.next_f32() * 4.0;
        let (a, b) = (blocks.intersect(&ray, t_max), single.intersect(&ray, t_max));
        assert_eq!(a.map(|h| h.t.to_bits()), b.map(|h| h.t.to_bits()));
        if let (Some(a), Some(b)) = (a, b) {
            hits += 1;
            let (pa, pb) = (
                &blocks.prims[a.prim as usize],
                &single.prims[b.prim as usize],
            );
            if (pa.material, pa.light) != (pb.material, pb.light)
                || blocks.texture_uv(&a) != single.texture_uv(&b)
            {
                // Only a tie may be broken differently: the other primitive must meet
                // the ray at the very same distance.
                let other = pa.shape.intersect(&ray, f32::INFINITY).map(|h| h.t);
                assert_eq!(other, Some(a.t), "{pa:?} vs {pb:?}");
                ties += 1;
            }
            assert!(a.light == NO_LIGHT || blocks.is_emitter(a.prim));
        }
        let shadow = blocks.occluded(&ray, t_max);
        assert_eq!(shadow, single.occluded(&ray, t_max));
        blocked += shadow as u32;
        match (
            blocks.first_emitter(&ray, false),
            single.first_emitter(&ray, false),
        ) {
            (Along::Emitter(a), Along::Emitter(b)) => assert_eq!(a.t, b.t),
            (Along::Blocked, Along::Blocked) => {}
            (a, b) => panic!("{a:?} vs {b:?}"),
        }
    }
    assert!(
        hits > 4000 && blocked > 4000 && ties < hits / 50,
        "{hits} hits, {blocked} blocked, {ties} ties"
    );
}

#[test]
fn packets_answer_as_single_rays_do_in_both_layouts() {
    let mut rng = Rng32::new(6);
    for use_blocks in [true, false] {
        let scene = mixed_scene(use_blocks);
        let (mut hits, mut ties) = (0, 0);
        for k in 0..3000 {
            // Camera-like packets: one origin, directions in a narrow cone; every fifth
            // packet spread wide; some lanes out of the packet (t_max ≤ 0).
            let o = Vec3::new(
                rng.next_f32() * 6.0,
                2.0 + rng.next_f32(),
                rng.next_f32() * 6.0,
            );
            let aim = Vec3::new(rng.next_f32() * 6.0, 0.0, rng.next_f32() * 6.0) - o;
            let spread = if k % 5 == 0 { 3.0 } else { 0.05 };
            let rays: [Ray; PACKET] = std::array::from_fn(|_| {
                let jitter = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5;
                Ray::new(o, (aim.normalize() + jitter * spread).normalize())
            });
            let t_max: [f32; PACKET] = std::array::from_fn(|l| match (k % 3, l) {
                (0, 3 | 6) => 0.0,
                (1, _) => 1.0 + rng.next_f32() * 4.0,
                _ => f32::INFINITY,
            });
            let packet = scene.intersect_packet(&rays, &t_max);
            for lane in 0..PACKET {
                let single = (t_max[lane] > 0.0)
                    .then(|| scene.intersect(&rays[lane], t_max[lane]))
                    .flatten();
                let got = packet[lane];
                assert_eq!(got.map(|h| h.t.to_bits()), single.map(|h| h.t.to_bits()));
                if let (Some(a), Some(b)) = (got, single) {
                    hits += 1;
                    if a.prim != b.prim {
                        let other = scene.prims[a.prim as usize]
                            .shape
                            .intersect(&rays[lane], f32::INFINITY);
                        assert_eq!(other.map(|h| h.t), Some(a.t));
                        ties += 1;
                    } else {
                        assert_eq!(
                            (a.p, a.ng, a.shape_uv, a.material, a.light),
                            (b.p, b.ng, b.shape_uv, b.material, b.light)
                        );
                    }
                }
            }
        }
        assert!(
            hits > 10_000 && ties < hits / 50,
            "{hits} hits, {ties} ties"
        );
    }
}
