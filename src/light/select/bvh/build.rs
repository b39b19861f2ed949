//! Building the light BVH top-down, one light per leaf: each node is split where the
//! SAOH says ([`super::saoh`]), and the tree is laid out in one array of 2n − 1 nodes.

use glam::Vec3;

use super::Node;
use super::saoh::split;
use crate::light::LightBounds;

/// A light entering the build: its index in the scene, bounds and centroid.
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildLight {
    pub index: usize,
    pub bounds: LightBounds,
    pub centroid: Vec3,
}

/// Light counts from which the two halves of a split are built on two threads: the
/// tree is the same node for node as the sequential build's.
const PARALLEL_MIN_LIGHTS: usize = 4096;

/// Builds the binary tree over `lights` (non-empty, each with φ > 0 and a finite centroid,
/// as [`super::BvhSelector::new`] keeps them): 2n − 1 nodes, root first, each inner node's
/// first child right after it.
pub(super) fn build(lights: &mut [BuildLight]) -> Vec<Node> {
    debug_assert!(
        lights
            .iter()
            .all(|l| l.bounds.phi > 0.0 && l.centroid.is_finite())
    );
    let mut nodes = vec![Node::PLACEHOLDER; 2 * lights.len() - 1];
    build_into(&mut nodes, 0, lights, 0, PARALLEL_MIN_LIGHTS);
    nodes
}

/// Builds the subtree of `lights` into `nodes`, which has exactly its 2n − 1 slots and
/// starts at index `base` of the whole array; the halves of a split of at least
/// `parallel_min` lights are built on two threads. A subtree's size follows from its
/// light count, so each half's slots are known before it is built: no copies.
/// Returns the subtree's bounds.
fn build_into(
    nodes: &mut [Node],
    base: u32,
    lights: &mut [BuildLight],
    depth: u32,
    parallel_min: usize,
) -> LightBounds {
    debug_assert_eq!(nodes.len(), 2 * lights.len() - 1);
    if lights.len() == 1 {
        let l = lights[0];
        nodes[0] = Node {
            bounds: l.bounds,
            second_or_light: l.index as u32,
            leaf: true,
        };
        return l.bounds;
    }
    let parallel = lights.len() >= parallel_min;
    let mid = split(lights, depth);
    let (root, children) = nodes.split_first_mut().expect("a split node has children");
    let (first_nodes, second_nodes) = children.split_at_mut(2 * mid - 1);
    let (left, right) = lights.split_at_mut(mid);
    let second = base + 2 * mid as u32;
    let (a, b) = if parallel {
        rayon::join(
            || build_into(first_nodes, base + 1, left, depth + 1, parallel_min),
            || build_into(second_nodes, second, right, depth + 1, parallel_min),
        )
    } else {
        (
            build_into(first_nodes, base + 1, left, depth + 1, parallel_min),
            build_into(second_nodes, second, right, depth + 1, parallel_min),
        )
    };
    let bounds = a.union(&b);
    *root = Node {
        bounds,
        second_or_light: second,
        leaf: false,
    };
    bounds
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::select::bvh::saoh::tests::random_lights;

    #[test]
    fn the_parallel_build_is_the_sequential_tree_node_for_node() {
        let lights = random_lights(3000, 20.0, 0x2545_f491_4f6c_dd1d);
        let build = |parallel_min: usize| {
            let mut nodes = vec![Node::PLACEHOLDER; 2 * lights.len() - 1];
            build_into(&mut nodes, 0, &mut lights.clone(), 0, parallel_min);
            nodes
        };
        let (sequential, parallel) = (build(usize::MAX), build(64));
        assert_eq!(sequential.len(), 2 * lights.len() - 1);
        // Every inner node bounds its two children, whose slots follow the layout, and
        // every light is in exactly one leaf.
        let mut seen = vec![0; lights.len()];
        for (k, node) in sequential.iter().enumerate() {
            if node.leaf {
                seen[node.second_or_light as usize] += 1;
            } else {
                let (first, second) = (
                    &sequential[k + 1],
                    &sequential[node.second_or_light as usize],
                );
                assert!(node.second_or_light as usize > k + 1, "node {k}");
                assert_eq!(node.bounds, first.bounds.union(&second.bounds), "node {k}");
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        assert_eq!(sequential.len(), parallel.len());
        for (k, (s, p)) in sequential.iter().zip(&parallel).enumerate() {
            assert!(
                s.bounds == p.bounds && s.second_or_light == p.second_or_light && s.leaf == p.leaf,
                "node {k}: {s:?} vs {p:?}"
            );
        }
    }
}
