//! The binary build's trees and its block-leaf shortcut.

use super::*;
use glam::Vec3;

/// Checks every reachable node: leaves cover the primitive order once, boxes nest.
fn check(tree: &BinaryBvh, bounds: &[Aabb]) {
    let mut seen = vec![false; bounds.len()];
    let mut stack = vec![0u32];
    while let Some(i) = stack.pop() {
        let node = tree.nodes[i as usize];
        if node.count > 0 {
            assert!(node.count as usize <= MAX_LEAF_SIZE.max(1));
            for k in node.first_or_right..node.first_or_right + node.count {
                let p = tree.order[k as usize] as usize;
                assert!(!seen[p]);
                seen[p] = true;
                assert_eq!(node.bounds.union(bounds[p]), node.bounds);
            }
        } else {
            let (left, right) = node.children(i);
            for child in [left, right] {
                assert_eq!(
                    node.bounds.union(tree.nodes[child as usize].bounds),
                    node.bounds
                );
                stack.push(child);
            }
        }
    }
    assert!(seen.iter().all(|&s| s));
}

#[test]
fn nodes_skipped_as_certain_leaves_are_leaves_by_the_sah_too() {
    let mut rng = crate::sampling::Rng32::new(5);
    let mut u = || rng.next_f32();
    let input = Input {
        kind: LeafKind::Blocks,
    };
    let mut checked = 0;
    for round in 0..20_000 {
        let n = 2 + round % (2 * MAX_LEAF_SIZE - 1);
        // Boxes of every shape: spread, tiny, flat, points, nested, far apart.
        let scale = [1e-6, 1.0, 1e3, 1e30][round % 4];
        let bounds: Vec<Aabb> = (0..n)
            .map(|_| {
                let p = Vec3::new(u(), u(), u()) * scale;
                let mut size = Vec3::new(u(), u(), u()) * scale * u();
                size[round % 3] *= (round % 5 == 0) as u32 as f32;
                Aabb::EMPTY.grow(p).grow(p + size)
            })
            .collect();
        let prims: Vec<PrimRef> = (bounds.iter().enumerate())
            .map(|(i, b)| PrimRef::new(BuildBox::from(b), i as u32))
            .collect();
        let (all, centroids) = bounds_of(&prims);
        if certain_leaf(input.kind, n, &all) {
            checked += 1;
            let split = sah_split(&input, &prims, &all, &centroids);
            assert!(matches!(split, Some(Split::Leaf) | None), "round {round}");
        }
    }
    assert!(checked > 5_000, "{checked}");
}

#[test]
fn trees_are_valid_for_spread_identical_and_flat_boxes() {
    let spread: Vec<Aabb> = (0..5000)
        .map(|i| Aabb::EMPTY.grow(Vec3::new((i * 7919 % 5000) as f32, (i % 13) as f32, 0.0)))
        .collect();
    let identical = vec![
        Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE
        };
        1000
    ];
    let flat: Vec<Aabb> = (0..100)
        .map(|i| Aabb::EMPTY.grow(Vec3::X * i as f32).grow(Vec3::Y))
        .collect();
    let with_empty = vec![
        Aabb::EMPTY,
        Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        },
        Aabb::EMPTY,
    ];
    for bounds in [spread, identical, flat, with_empty] {
        for kind in [LeafKind::Single, LeafKind::Blocks] {
            check(&build_binary(&bounds, kind), &bounds);
        }
    }
}
