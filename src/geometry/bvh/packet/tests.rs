//! Packets against single rays, and the traversal's own rules.

use glam::Vec3;

use super::*;
use crate::geometry::TriangleSet;
use crate::geometry::triangle::intersect_triangle;
use crate::sampling::Rng32;

/// A leaf test as the masked traversal calls it.
type LeafTest<'a> = dyn FnMut(u32, u32, u32, &mut Lanes) + 'a;

/// A soup of random triangles over shared vertices (rays meet shared edges) and the
/// vertices, indices.
fn soup(rng: &mut Rng32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut point = || Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
    let positions: Vec<Vec3> = (0..300).map(|_| point()).collect();
    let indices = (0..2000u32)
        .map(|i| [i % 300, (i * 7 + 1) % 300, (i * 13 + 5) % 300])
        .collect();
    (positions, indices)
}

/// Packets of several kinds: coherent (one origin, nearby directions), incoherent,
/// axis-parallel with ±0 components, and with lanes that take no part.
fn packets(rng: &mut Rng32, count: usize) -> Vec<([Ray; PACKET], Lanes)> {
    let mut u = || rng.next_f32();
    (0..count)
        .map(|k| {
            let o = Vec3::new(u(), u(), u()) * 14.0 - Vec3::splat(2.0);
            let aim = (Vec3::new(u(), u(), u()) * 10.0 - o).normalize();
            let rays: [Ray; PACKET] = std::array::from_fn(|_| match k % 4 {
                0 => Ray::new(o, aim + Vec3::new(u(), u(), u()) * 0.05),
                1 => {
                    let o = Vec3::new(u(), u(), u()) * 14.0 - Vec3::splat(2.0);
                    Ray::new(o, Vec3::new(u(), u(), u()) * 10.0 - o)
                }
                2 => {
                    let axis = (u() * 3.0) as usize % 3;
                    let sign = if u() < 0.5 { -1.0 } else { 1.0 };
                    let mut d = Vec3::splat(if u() < 0.5 { -0.0 } else { 0.0 });
                    d[axis] = sign;
                    Ray::new(Vec3::new(u(), u(), u()) * 10.0, d)
                }
                _ => Ray::new(o, aim - Vec3::new(u(), u(), u()) * 0.3),
            });
            let mut t_max: Lanes =
                std::array::from_fn(|_| if u() < 0.5 { f32::INFINITY } else { 8.0 * u() });
            let mut rays = rays;
            if k % 4 == 3 {
                // Lanes out of the packet: a NaN ray, an empty or NaN interval.
                rays[1].d = Vec3::new(f32::NAN, 1.0, 0.0);
                t_max[2] = 0.0;
                t_max[5] = -1.0;
                t_max[6] = f32::NAN;
            }
            (rays, t_max)
        })
        .collect()
}

#[test]
fn packets_find_the_single_ray_hits() {
    let mut rng = Rng32::new(7);
    let (positions, indices) = soup(&mut rng);
    let set = TriangleSet::new(&positions, &indices);
    let (mut hits, mut ties) = (0, 0);
    for (rays, t_max) in packets(&mut rng, 1500) {
        let got = set.closest_hit_packet(&rays, &t_max);
        for lane in 0..PACKET {
            let takes_part = rays[lane].d.is_finite() && t_max[lane] > 0.0;
            let single = takes_part
                .then(|| set.closest_hit(&rays[lane], t_max[lane]))
                .flatten();
            let (g, s) = (got[lane], single);
            assert_eq!(g.map(|h| h.1.t.to_bits()), s.map(|h| h.1.t.to_bits()));
            if let (Some((gi, gh)), Some((si, _))) = (g, s) {
                hits += 1;
                if gi != si {
                    // Only a tie: the packet's triangle is hit at the same distance.
                    ties += 1;
                    let [a, b, c] = indices[gi as usize].map(|i| positions[i as usize]);
                    let again = intersect_triangle(&rays[lane], a, b - a, c - a, t_max[lane]);
                    assert_eq!(again.map(|h| h.t), Some(gh.t));
                }
            }
        }
    }
    assert!(hits > 3000 && ties < hits / 100, "{hits} hits, {ties} ties");
}

#[test]
fn deep_trees_and_every_instruction_set_walk_the_same_way() {
    let mut rng = Rng32::new(8);
    let (positions, indices) = soup(&mut rng);
    let set = TriangleSet::new(&positions, &indices);
    let bvh = set.bvh();
    let (mut visited, mut uniform) = (0, 0);
    for (rays, t_max) in packets(&mut rng, 200) {
        // A leaf that shortens every ray reaching it a little: the walk (leaves in
        // order, with the rays reaching each) and the final distances must agree.
        let walk = |run: &dyn Fn(&mut LeafTest) -> Lanes| {
            let mut visits = Vec::new();
            let t = run(&mut |first, _, active, t: &mut Lanes| {
                visits.push((first, active));
                for (lane, t) in t.iter_mut().enumerate() {
                    if active & (1 << lane) != 0 {
                        *t *= 0.99;
                    }
                }
            });
            (visits, t.map(f32::to_bits))
        };
        let (nodes, depth) = (&bvh.nodes, bvh.depth);
        let dispatched = walk(&|leaf| closest_hit_masked(nodes, depth, &rays, &t_max, leaf));
        let heap = walk(&|leaf| closest_hit_masked(nodes, 100, &rays, &t_max, leaf));
        let plain = walk(&|leaf| closest_hit_lanes(nodes, depth, &rays, &t_max, leaf));
        visited += dispatched.0.len();
        assert_eq!(dispatched, heap);
        assert_eq!(dispatched, plain);
        // Packets whose rays share their octant walk with one near plane per axis; the
        // general slab test (a near plane per ray) must walk them the same way.
        let valid: [bool; PACKET] = std::array::from_fn(|l| {
            rays[l].o.is_finite() && rays[l].d.is_finite() && t_max[l] > 0.0
        });
        if valid.contains(&true) {
            let data = PacketData::new(&rays, &valid);
            if data.uniform.is_some() {
                uniform += 1;
                // Entry by entry, every child of every node, bit for bit.
                let live = valid;
                for node in nodes.iter() {
                    for c in 0..WIDTH {
                        let bits = |e: Lanes| e.map(f32::to_bits);
                        assert_eq!(
                            bits(data.entry::<true>(node, c, &t_max, &live)),
                            bits(data.entry::<false>(node, c, &t_max, &live))
                        );
                    }
                }
                let general = walk(&|leaf| {
                    super::walk::<false, _>(nodes, depth, &data, &valid, &t_max, leaf)
                });
                assert_eq!(dispatched, general);
            }
        }
    }
    assert!(visited > 2000, "{visited} leaves visited");
    assert!(uniform >= 40, "{uniform} packets of one octant");
}

#[test]
fn rays_that_miss_a_box_never_test_what_is_inside() {
    let mut rng = Rng32::new(9);
    let (positions, indices) = soup(&mut rng);
    let set = TriangleSet::new(&positions, &indices);
    let bvh = set.bvh();
    let mut tested = 0;
    for k in 0..300 {
        // Lanes 0..4 aim into the soup (0..10)³; lanes 4..8 start beside it and look
        // away from it, with t_max = ∞: they enter no box at all.
        let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0 - 2.0;
        let rays: [Ray; PACKET] = std::array::from_fn(|l| {
            let jitter = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            if l < 4 {
                Ray::new(o, Vec3::splat(5.0) + jitter - o)
            } else {
                Ray::new(o - Vec3::splat(3.0), -Vec3::ONE - jitter)
            }
        });
        let t_max = [f32::INFINITY; PACKET];
        closest_hit_masked(&bvh.nodes, bvh.depth, &rays, &t_max, |_, _, active, _| {
            assert_eq!(active & 0xf0, 0, "packet {k}: a ray that misses took part");
            tested += active.count_ones();
        });
    }
    assert!(tested > 1000, "{tested} leaf tests");
}
