//! Collapsing the binary tree into 4-wide nodes: each wide node takes the children of a
//! binary node and repeatedly opens the inner child with the largest surface area until
//! it has four (the greedy collapse of Wald et al. 2008, "Getting Rid of Packets", and
//! of Embree's BVH4 builders). Opening the largest box first removes the boxes rays are
//! most likely to enter.

use super::build::BinaryBvh;
use super::node::{ChildRef, WIDTH, WideNode};
use super::{BLOCK, PADDING};

/// Wide nodes (root at 0) and the depth of the deepest one (the root has depth 1).
pub struct WideTree {
    /// The nodes, parents before children.
    pub nodes: Vec<WideNode>,
    /// Number of wide nodes on the longest root-to-leaf path.
    pub depth: usize,
}

/// Collapses `tree` into 4-wide nodes. Leaves keep their primitive ranges.
pub fn collapse(tree: &BinaryBvh) -> WideTree {
    let mut nodes = vec![WideNode::empty()];
    let mut depth = 1;
    // (binary node, wide node it becomes, depth of that wide node)
    let mut work = vec![(0u32, 0usize, 1usize)];
    while let Some((binary, wide, level)) = work.pop() {
        depth = depth.max(level);
        let kids = open_children(tree, binary);
        for (lane, &kid) in kids.iter().take(kids_len(&kids)).enumerate() {
            let node = &tree.nodes[kid as usize];
            let child = if node.count > 0 {
                ChildRef::leaf(node.first_or_left, node.count)
            } else {
                let index = nodes.len();
                nodes.push(WideNode::empty());
                work.push((kid, index, level + 1));
                ChildRef::inner(index as u32)
            };
            nodes[wide].set_child(lane, &node.bounds, child);
        }
    }
    WideTree { nodes, depth }
}

/// Lays the leaves out in blocks for [`super::Bvh::build_blocks`]: every leaf's
/// primitives move to the next multiple of [`BLOCK`] in a new primitive order, the rest of
/// the block holding [`PADDING`], and the leaf references are rewritten to match. Leaves
/// are laid out in node order, so a node's leaves sit together in memory. Returns the
/// new order.
pub fn lay_out_blocks(nodes: &mut [WideNode], order: &[u32]) -> Vec<u32> {
    let mut laid = Vec::with_capacity(order.len() + order.len() / 2);
    for node in nodes.iter_mut() {
        for child in node.children.iter_mut().filter(|c| c.is_leaf()) {
            let (first, count) = child.leaf_range();
            let start = laid.len() as u32;
            laid.extend_from_slice(&order[first as usize..(first + count) as usize]);
            laid.resize(start as usize + BLOCK, PADDING);
            *child = ChildRef::leaf(start, count);
        }
    }
    laid
}

/// Marks unused entries of a child list.
const NONE: u32 = u32::MAX;

/// Number of used entries in a child list.
fn kids_len(kids: &[u32; WIDTH]) -> usize {
    kids.iter().take_while(|&&k| k != NONE).count()
}

/// The up-to-four binary nodes that become the children of the wide node made from
/// `binary`: its two children, with the largest inner ones opened in turn. A binary leaf
/// (only possible at the root) becomes a wide node with one leaf child.
fn open_children(tree: &BinaryBvh, binary: u32) -> [u32; WIDTH] {
    let mut kids = [NONE; WIDTH];
    let root = &tree.nodes[binary as usize];
    if root.count > 0 {
        kids[0] = binary;
        return kids;
    }
    kids[0] = root.first_or_left;
    kids[1] = root.right;
    let mut len = 2;
    while len < WIDTH {
        let largest_inner = (0..len)
            .filter(|&i| tree.nodes[kids[i] as usize].count == 0)
            .max_by(|&a, &b| area(tree, kids[a]).total_cmp(&area(tree, kids[b])));
        let Some(i) = largest_inner else { break };
        let opened = tree.nodes[kids[i] as usize];
        kids[i] = opened.first_or_left;
        kids[len] = opened.right;
        len += 1;
    }
    kids
}

/// Surface area of binary node `i`.
fn area(tree: &BinaryBvh, i: u32) -> f32 {
    tree.nodes[i as usize].bounds.surface_area()
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::super::build::{LeafKind, build_binary};
    use super::*;
    use crate::geometry::Aabb;

    #[test]
    fn wide_tree_covers_every_primitive_once() {
        for n in [1usize, 2, 5, 37, 1000] {
            let bounds: Vec<Aabb> = (0..n)
                .map(|i| {
                    Aabb::EMPTY
                        .grow(Vec3::splat(i as f32))
                        .grow(Vec3::splat(i as f32 + 0.5))
                })
                .collect();
            let binary = build_binary(&bounds, LeafKind::Single);
            let wide = collapse(&binary);
            let mut covered = vec![0; n];
            for node in &wide.nodes {
                for lane in 0..WIDTH {
                    if node.planes[0][lane] <= node.planes[3][lane] && node.children[lane].is_leaf()
                    {
                        let (first, count) = node.children[lane].leaf_range();
                        for k in first..first + count {
                            covered[binary.order[k as usize] as usize] += 1;
                        }
                    }
                }
            }
            assert!(covered.iter().all(|&c| c == 1), "n = {n}");
            assert!(
                wide.depth <= 2 + n.ilog2() as usize,
                "n = {n}, depth {}",
                wide.depth
            );
        }
    }
}
