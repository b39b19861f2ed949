//! Collapsing the binary tree into 4-wide nodes: each wide node takes the children of a
//! binary node and repeatedly opens the inner child with the largest surface area until
//! it has four (the greedy collapse of Wald et al. 2008, "Getting Rid of Packets", and
//! of Embree's BVH4 builders). Opening the largest box first removes the boxes rays are
//! most likely to enter.

use super::build::BinaryBvh;
use super::node::{ChildRef, WIDTH, WideNode};
use super::{BLOCK, PADDING, huge_pages};
use rayon::prelude::*;

/// Wide nodes (root at 0) and the depth of the deepest one (the root has depth 1).
pub struct WideTree {
    /// The nodes, parents before children.
    pub nodes: Vec<WideNode>,
    /// Number of wide nodes on the longest root-to-leaf path.
    pub depth: usize,
}

/// Subtrees the collapse hands to parallel tasks, about.
const TASKS: usize = 64;

/// An inner binary node whose wide node is still to be made, and where its reference
/// goes: lane `lane` of wide node `parent`, which is at depth `level − 1`.
#[derive(Clone, Copy)]
struct Pending {
    binary: u32,
    parent: usize,
    lane: usize,
    level: usize,
}

/// Collapses `tree` into 4-wide nodes. Leaves keep their primitive ranges.
///
/// The top of the tree is collapsed breadth-first on this thread until about [`TASKS`]
/// subtrees are left; those are collapsed in parallel, each into its own nodes, and
/// appended in order with their inner references shifted. The result depends on the
/// tree alone, not on the threads.
pub fn collapse(tree: &BinaryBvh) -> WideTree {
    let mut nodes = vec![WideNode::empty()];
    let mut depth = 1;
    let mut queue: std::collections::VecDeque<Pending> = fill(tree, 0, 0, 1, &mut nodes)
        .into_iter()
        .flatten()
        .collect();
    while queue.len() < TASKS {
        let Some(p) = queue.pop_front() else { break };
        let index = adopt(&mut nodes, &p);
        depth = depth.max(p.level);
        queue.extend(
            fill(tree, p.binary, index, p.level, &mut nodes)
                .into_iter()
                .flatten(),
        );
    }
    let tasks: Vec<Pending> = queue.into();
    let subtrees: Vec<WideTree> = tasks
        .par_iter()
        .map(|p| collapse_from(tree, p.binary))
        .collect();
    // Each subtree is appended after the top nodes and the subtrees before it.
    let top = nodes.len();
    let mut starts = Vec::with_capacity(subtrees.len());
    let mut total = top;
    for (p, sub) in tasks.iter().zip(&subtrees) {
        nodes[p.parent].children[p.lane] = ChildRef::inner(total as u32);
        depth = depth.max(p.level + sub.depth - 1);
        starts.push(total as u32);
        total += sub.nodes.len();
    }
    nodes.resize(total, WideNode::empty());
    let mut slices = Vec::with_capacity(subtrees.len());
    let mut rest = &mut nodes[top..];
    for sub in &subtrees {
        let (head, tail) = rest.split_at_mut(sub.nodes.len());
        slices.push(head);
        rest = tail;
    }
    slices
        .into_par_iter()
        .zip(subtrees.par_iter().zip(starts))
        .for_each(|(to, (sub, start))| {
            for (to, node) in to.iter_mut().zip(&sub.nodes) {
                *to = *node;
                // Inner children of used lanes (an unused lane's box is empty: lower
                // bound +∞) move with their subtree.
                for lane in 0..WIDTH {
                    let child = &mut to.children[lane];
                    if to.planes[0][lane] != f32::INFINITY && !child.is_leaf() {
                        *child = ChildRef::inner(child.0 + start);
                    }
                }
            }
        });
    WideTree { nodes, depth }
}

/// Collapses the subtree under inner binary node `binary` on this thread, depth first:
/// its wide node at 0, inner references local to the returned nodes.
fn collapse_from(tree: &BinaryBvh, binary: u32) -> WideTree {
    let mut nodes = vec![WideNode::empty()];
    let mut depth = 1;
    let mut work = vec![(binary, 0usize, 1usize)];
    while let Some((binary, wide, level)) = work.pop() {
        depth = depth.max(level);
        for p in fill(tree, binary, wide, level, &mut nodes)
            .into_iter()
            .flatten()
        {
            work.push((p.binary, adopt(&mut nodes, &p), p.level));
        }
    }
    WideTree { nodes, depth }
}

/// Appends the wide node for `p` and links it from its parent; returns its index.
fn adopt(nodes: &mut Vec<WideNode>, p: &Pending) -> usize {
    let index = nodes.len();
    nodes.push(WideNode::empty());
    nodes[p.parent].children[p.lane] = ChildRef::inner(index as u32);
    index
}

/// Fills wide node `wide` (at depth `level`) with the children of binary node `binary`
/// (see [`open_children`]): leaves directly, inner children as boxes whose references
/// the returned [`Pending`]s complete.
fn fill(
    tree: &BinaryBvh,
    binary: u32,
    wide: usize,
    level: usize,
    nodes: &mut [WideNode],
) -> [Option<Pending>; WIDTH] {
    let mut pending = [None; WIDTH];
    let kids = open_children(tree, binary);
    for (lane, &kid) in kids.iter().take(kids_len(&kids)).enumerate() {
        let node = &tree.nodes[kid as usize];
        let child = if node.count > 0 {
            ChildRef::leaf(node.first_or_right, node.count)
        } else {
            pending[lane] = Some(Pending {
                binary: kid,
                parent: wide,
                lane,
                level: level + 1,
            });
            ChildRef::inner(0)
        };
        nodes[wide].set_child(lane, &node.bounds, child);
    }
    pending
}

/// Lays the leaves out in blocks for [`super::Bvh::build_blocks`]: every leaf's
/// primitives move to the next multiple of [`BLOCK`] in a new primitive order, the rest of
/// the block holding [`PADDING`], and the leaf references are rewritten to match. Leaves
/// are laid out in node order, so a node's leaves sit together in memory. Returns the
/// new order.
pub fn lay_out_blocks(nodes: &mut [WideNode], order: &[u32]) -> Vec<u32> {
    // Every leaf takes one block, so the k-th leaf in node order starts at k · BLOCK:
    // the leaves' old ranges in that order give the new order, and each node's first
    // leaf number (a running count, the one serial pass) its new references.
    let ranges: Vec<(u32, u32)> = nodes
        .par_iter()
        .flat_map_iter(|node| leaves(node).map(|c| c.leaf_range()))
        .collect();
    let mut laid = huge_pages::with_capacity(ranges.len() * BLOCK);
    laid.par_extend(ranges.par_iter().flat_map_iter(|&(first, count)| {
        let slots = &order[first as usize..(first + count) as usize];
        let padding = std::iter::repeat_n(PADDING, BLOCK - count as usize);
        slots.iter().copied().chain(padding)
    }));
    let mut first_leaf = Vec::with_capacity(nodes.len());
    let mut leaf_count = 0u32;
    for node in nodes.iter() {
        first_leaf.push(leaf_count);
        leaf_count += leaves(node).count() as u32;
    }
    nodes
        .par_iter_mut()
        .zip(first_leaf)
        .for_each(|(node, mut k)| {
            for child in node.children.iter_mut().filter(|c| c.is_leaf()) {
                *child = ChildRef::leaf(k * BLOCK as u32, child.leaf_range().1);
                k += 1;
            }
        });
    laid
}

/// The leaf references of a wide node, in lane order.
fn leaves(node: &WideNode) -> impl Iterator<Item = ChildRef> + '_ {
    node.children.iter().copied().filter(|c| c.is_leaf())
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
    (kids[0], kids[1]) = root.children(binary);
    let mut len = 2;
    while len < WIDTH {
        let largest_inner = (0..len)
            .filter(|&i| tree.nodes[kids[i] as usize].count == 0)
            .max_by(|&a, &b| area(tree, kids[a]).total_cmp(&area(tree, kids[b])));
        let Some(i) = largest_inner else { break };
        let opened = tree.nodes[kids[i] as usize];
        (kids[i], kids[len]) = opened.children(kids[i]);
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

    /// Every lane of the tree's nodes, depth first in lane order from the root, as its
    /// box's bits and, for a leaf, its primitives' indices through `order` (empty for
    /// an inner child, a marker for an unused lane): what traversal sees, whatever the
    /// node order in memory.
    fn walk(tree: &WideTree, order: &[u32]) -> Vec<([u32; 6], Vec<u32>)> {
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let node = &tree.nodes[i as usize];
            let mut inner = Vec::new();
            for lane in 0..WIDTH {
                let planes = std::array::from_fn(|k| node.planes[k][lane].to_bits());
                let child = node.children[lane];
                let prims = if node.planes[0][lane] > node.planes[3][lane] {
                    vec![u32::MAX - 1]
                } else if child.is_leaf() {
                    let (first, count) = child.leaf_range();
                    order[first as usize..(first + count) as usize].to_vec()
                } else {
                    inner.push(child.0);
                    vec![]
                };
                out.push((planes, prims));
            }
            stack.extend(inner.into_iter().rev());
        }
        out
    }

    #[test]
    fn parallel_collapse_and_layout_match_the_serial_ones() {
        // Enough primitives that the collapse hands out TASKS subtrees.
        let bounds: Vec<Aabb> = (0..20_000u32)
            .map(|i| {
                let p = Vec3::new(
                    (i.wrapping_mul(2_654_435_761) % 1000) as f32,
                    (i % 97) as f32,
                    (i / 97) as f32,
                );
                Aabb::EMPTY.grow(p).grow(p + Vec3::splat(0.7))
            })
            .collect();
        for kind in [LeafKind::Single, LeafKind::Blocks] {
            let binary = build_binary(&bounds, kind);
            let serial = collapse_from(&binary, 0);
            let mut parallel = collapse(&binary);
            assert!(parallel.nodes.len() > TASKS && serial.nodes.len() == parallel.nodes.len());
            assert_eq!(serial.depth, parallel.depth);
            assert_eq!(walk(&serial, &binary.order), walk(&parallel, &binary.order));
            if kind == LeafKind::Blocks {
                // The one-leaf-one-block layout, leaf by leaf in node order.
                let mut expected = Vec::new();
                for node in &parallel.nodes {
                    for (first, count) in leaves(node).map(|c| c.leaf_range()) {
                        expected.extend(&binary.order[first as usize..(first + count) as usize]);
                        expected.resize(expected.len().next_multiple_of(BLOCK), PADDING);
                    }
                }
                let walked = walk(&parallel, &binary.order);
                let laid = lay_out_blocks(&mut parallel.nodes, &binary.order);
                assert_eq!(laid, expected);
                assert_eq!(walk(&parallel, &laid), walked);
            }
        }
    }

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
