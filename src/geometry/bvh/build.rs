//! The binary build: top-down binned SAH (Wald 2007, "On fast Construction of SAH-based
//! Bounding Volume Hierarchies"). Primitives are binned by centroid into [`BIN_COUNT`]
//! bins per axis; the split with the lowest surface area heuristic cost
//! (Goldsmith & Salmon 1987; MacDonald & Booth 1990) is taken, or a leaf when that is
//! cheaper. Large subtrees are built in parallel with `rayon::join`.
//!
//! Nodes live in one array where a subtree over `m` primitives owns exactly `2m − 1`
//! consecutive slots, so parallel subtrees write to disjoint slices and nothing is
//! copied afterwards. Slots a subtree does not need stay unused; only the wide collapse
//! reads this tree, by following child links.

use super::huge_pages;
use super::node::MAX_LEAF_SIZE;
use super::prim_ref::{Binning, BuildBox, PrimRef, bounds_of, boxes_of};
use crate::geometry::Aabb;
use rayon::prelude::*;

/// Centroid bins per axis.
pub(super) const BIN_COUNT: usize = 16;
/// SAH cost of one traversal step, relative to one primitive test.
const TRAVERSAL_COST: f32 = 1.0;
/// Subtrees with fewer primitives than this are built on the current thread.
const PARALLEL_THRESHOLD: usize = 4096;
/// SAH cost of testing one block of up to [`MAX_LEAF_SIZE`] primitives at once
/// ([`LeafKind::Blocks`]), relative to one traversal step.
const BLOCK_COST: f32 = 1.0;
/// Below this depth SAH chooses splits; deeper nodes split at the object median, which
/// bounds the tree depth (and so the traversal stack) for any input.
const MAX_SAH_DEPTH: usize = 40;

/// How leaves will be tested, which sets what the SAH charges for them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LeafKind {
    /// One primitive at a time: a leaf of n primitives costs n tests.
    Single,
    /// Up to [`MAX_LEAF_SIZE`] primitives in one SIMD test: counts enter the SAH rounded
    /// up to whole blocks, as in Embree's builders for its Triangle4 leaves, so leaves
    /// fill up.
    Blocks,
}

impl LeafKind {
    /// SAH cost of intersecting `count` primitives in leaves.
    #[inline]
    fn cost(self, count: u32) -> f32 {
        match self {
            LeafKind::Single => count as f32,
            LeafKind::Blocks => count.div_ceil(MAX_LEAF_SIZE as u32) as f32 * BLOCK_COST,
        }
    }
}

/// A node of the binary tree, 32 bytes aligned to 32 so a node never straddles two
/// cache lines (the collapse reads them scattered). A leaf has `count > 0` primitives at
/// `first_or_right ..` in the primitive order; an inner node at slot i has `count == 0`,
/// its left child at slot i + 1 (see [`BinaryNode::children`]) and its right child at
/// `first_or_right`.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct BinaryNode {
    /// Box of everything below.
    pub bounds: Aabb,
    /// First primitive (leaf) or right child (inner node).
    pub first_or_right: u32,
    /// Primitive count; 0 for an inner node.
    pub count: u32,
}

impl BinaryNode {
    /// The (left, right) children of the inner node at slot `index`.
    #[inline]
    pub fn children(&self, index: u32) -> (u32, u32) {
        (index + 1, self.first_or_right)
    }
}

/// A binary BVH: nodes (root at 0) and primitive indices in leaf order.
pub struct BinaryBvh {
    /// Nodes; a subtree over m primitives owns 2m − 1 slots (some may be unused).
    pub nodes: Vec<BinaryNode>,
    /// Primitive indices in leaf order.
    pub order: Vec<u32>,
}

/// Builds the binary tree over `bounds` (which must be non-empty). Primitives with empty
/// or non-finite boxes are kept: boxes with a NaN count as empty, and centroids that are
/// not finite are replaced by a finite stand-in for binning.
pub fn build_binary(bounds: &[Aabb], kind: LeafKind) -> BinaryBvh {
    let has_nan = |b: &Aabb| b.min.is_nan() || b.max.is_nan();
    let sanitized: Vec<Aabb>;
    let bounds = if bounds.iter().any(has_nan) {
        sanitized = bounds
            .iter()
            .map(|b| if has_nan(b) { Aabb::EMPTY } else { *b })
            .collect();
        &sanitized[..]
    } else {
        bounds
    };
    // The set-up passes touch every primitive (and 2n − 1 node slots): in parallel.
    let mut refs: Vec<PrimRef> = huge_pages::with_capacity(bounds.len());
    refs.par_extend(
        bounds
            .par_iter()
            .enumerate()
            .map(|(id, b)| PrimRef::new(BuildBox::from(b), id as u32)),
    );
    let unused = BinaryNode {
        bounds: Aabb::EMPTY,
        first_or_right: 0,
        count: 0,
    };
    let mut nodes = huge_pages::with_capacity(2 * bounds.len() - 1);
    nodes.par_extend(rayon::iter::repeat_n(unused, 2 * bounds.len() - 1));
    let input = Input { kind };
    let (b, c) = refs.par_chunks(PARALLEL_THRESHOLD).map(boxes_of).reduce(
        || (BuildBox::EMPTY, BuildBox::EMPTY),
        |x, y| (x.0.union(y.0), x.1.union(y.1)),
    );
    let boxes = (b.aabb(), c.aabb());
    build_subtree(&input, &mut nodes, 0, &mut refs, boxes, 0, 0);
    let order: Vec<u32> = refs.par_iter().map(|r| r.id()).collect();
    BinaryBvh { nodes, order }
}

/// Read-only build input shared by all threads.
struct Input {
    kind: LeafKind,
}

/// Builds the subtree over `prims` (the primitive order from position `first`) into
/// `nodes`, whose slot 0 is global index `node_base`.
fn build_subtree(
    input: &Input,
    nodes: &mut [BinaryNode],
    node_base: u32,
    prims: &mut [PrimRef],
    (bounds, centroid_bounds): (Aabb, Aabb),
    first: u32,
    depth: usize,
) {
    let split = if certain_leaf(input.kind, prims.len(), &bounds) {
        Some(Split::Leaf)
    } else if depth < MAX_SAH_DEPTH {
        sah_split(input, prims, &bounds, &centroid_bounds)
    } else {
        None
    };
    // The children's boxes come out of the partition that separates them.
    let (left_count, left_boxes, right_boxes) = match split {
        Some(Split::Leaf) => (0, EMPTY_BOXES, EMPTY_BOXES),
        Some(Split::At { axis, bin }) => partition(prims, &centroid_bounds, axis, bin),
        None if prims.len() <= MAX_LEAF_SIZE => (0, EMPTY_BOXES, EMPTY_BOXES),
        None => {
            let mid = median_split(prims, &centroid_bounds);
            (mid, bounds_of(&prims[..mid]), bounds_of(&prims[mid..]))
        }
    };
    if left_count == 0 {
        nodes[0] = BinaryNode {
            bounds,
            first_or_right: first,
            count: prims.len() as u32,
        };
        return;
    }
    // The left subtree owns slots 1 .. 2·left_count, the right one the rest.
    let left_slots = 2 * left_count - 1;
    let left = node_base + 1;
    let right = left + left_slots as u32;
    nodes[0] = BinaryNode {
        bounds,
        first_or_right: right,
        count: 0,
    };
    let (left_nodes, right_nodes) = nodes[1..].split_at_mut(left_slots);
    let (left_prims, right_prims) = prims.split_at_mut(left_count);
    let right_first = first + left_count as u32;
    let parallel = left_count.min(right_prims.len()) >= PARALLEL_THRESHOLD;
    let build_left = move || {
        build_subtree(
            input,
            left_nodes,
            left,
            left_prims,
            left_boxes,
            first,
            depth + 1,
        )
    };
    let build_right = move || {
        build_subtree(
            input,
            right_nodes,
            right,
            right_prims,
            right_boxes,
            right_first,
            depth + 1,
        )
    };
    if parallel {
        rayon::join(build_left, build_right);
    } else {
        run_in_turn(build_left, build_right);
    }
}

/// The boxes of no primitives.
const EMPTY_BOXES: (Aabb, Aabb) = (Aabb::EMPTY, Aabb::EMPTY);

/// Runs `a` then `b` on this thread (the serial counterpart of `rayon::join`).
fn run_in_turn(a: impl FnOnce(), b: impl FnOnce()) {
    a();
    b();
}

/// The outcome of the SAH evaluation.
enum Split {
    /// Making a leaf is cheapest.
    Leaf,
    /// Split before centroid bin `bin` along `axis`.
    At { axis: usize, bin: usize },
}

/// True when a node of `n` primitives in `bounds` is a leaf whatever its split: a block
/// leaf holds up to MAX_LEAF_SIZE for the cost of one traversal step, which no split
/// beats, C(leaf) = 1 ≤ C_trav + (A_L·C_L + A_R·C_R)/A. Only an infinite parent area
/// (∞/∞) could make [`sah_split`]'s comparison fail, so such nodes are left to it; for
/// all others the binning is skipped: about half the nodes of a block tree.
fn certain_leaf(kind: LeafKind, n: usize, bounds: &Aabb) -> bool {
    kind == LeafKind::Blocks
        && n <= MAX_LEAF_SIZE
        && BLOCK_COST <= TRAVERSAL_COST
        && bounds.surface_area() != f32::INFINITY
}

/// The best SAH split (Wald 2007, §3), `Leaf` when a leaf costs less, or `None` when the
/// centroids cannot be separated by binning.
fn sah_split(
    input: &Input,
    prims: &[PrimRef],
    bounds: &Aabb,
    centroid_bounds: &Aabb,
) -> Option<Split> {
    let n = prims.len();
    if n == 1 {
        return Some(Split::Leaf);
    }

    let extent = centroid_bounds.extent();
    let binning = Binning::new(centroid_bounds);
    let mut bins = [[(BuildBox::EMPTY, 0u32); BIN_COUNT]; 3];
    for p in prims {
        let bounds = p.bounds();
        let at = binning.bins(bounds.centroid());
        for (axis, axis_bins) in bins.iter_mut().enumerate() {
            if extent[axis] > 0.0 {
                let bin = &mut axis_bins[at[axis]];
                *bin = (bin.0.union(bounds), bin.1 + 1);
            }
        }
    }
    // Cost relative to one primitive test per unit of parent area:
    // C = C_trav + (A_L·C(N_L) + A_R·C(N_R)) / A, C(N) = N or whole blocks (`LeafKind`).
    let leaf_cost = |count: u32| input.kind.cost(count);
    let mut best: Option<(f32, usize, usize)> = None;
    for (axis, axis_bins) in bins.iter().enumerate() {
        if extent[axis] <= 0.0 {
            continue;
        }
        // Only the occupied bins matter: a split between two of them is the same split
        // wherever it falls in the empty bins between, and the first such place wins a
        // tie, so sweeping the occupied bins alone chooses exactly what sweeping all
        // would (most nodes are small, and most of their bins empty).
        let mut used = [0usize; BIN_COUNT];
        let mut m = 0;
        for (bin, b) in axis_bins.iter().enumerate() {
            if b.1 > 0 {
                used[m] = bin;
                m += 1;
            }
        }
        // Sweep from the right storing A_R·C(N_R), then from the left evaluating the cost
        // of splitting just above each occupied bin.
        let mut right_cost = [0.0f32; BIN_COUNT];
        let (mut acc, mut count) = (BuildBox::EMPTY, 0u32);
        for j in (1..m).rev() {
            acc = acc.union(axis_bins[used[j]].0);
            count += axis_bins[used[j]].1;
            right_cost[j] = acc.aabb().surface_area() * leaf_cost(count);
        }
        let (mut acc, mut count) = (BuildBox::EMPTY, 0u32);
        for j in 1..m {
            let below = used[j - 1];
            acc = acc.union(axis_bins[below].0);
            count += axis_bins[below].1;
            let cost = acc.aabb().surface_area() * leaf_cost(count) + right_cost[j];
            if cost < best.map_or(f32::INFINITY, |b| b.0) {
                best = Some((cost, axis, below + 1));
            }
        }
    }
    let (cost, axis, bin) = best?;
    let area = bounds.surface_area();
    let split_cost = TRAVERSAL_COST + if area > 0.0 { cost / area } else { 0.0 };
    if n <= MAX_LEAF_SIZE && leaf_cost(n as u32) <= split_cost {
        Some(Split::Leaf)
    } else {
        Some(Split::At { axis, bin })
    }
}

/// Moves primitives whose centroid bin is below `bin` to the front; returns their count
/// and the boxes (of the primitives and of their centroids) of both sides.
fn partition(
    prims: &mut [PrimRef],
    centroid_bounds: &Aabb,
    axis: usize,
    bin: usize,
) -> (usize, (Aabb, Aabb), (Aabb, Aabb)) {
    let binning = Binning::new(centroid_bounds);
    let (mut below, mut above) = ([BuildBox::EMPTY; 2], [BuildBox::EMPTY; 2]);
    let mut left = 0;
    for i in 0..prims.len() {
        let p = prims[i];
        let c = p.bounds().centroid();
        let side = if binning.bins(c)[axis] < bin {
            prims.swap(i, left);
            left += 1;
            &mut below
        } else {
            &mut above
        };
        *side = [side[0].union(p.bounds()), side[1].grow(c)];
    }
    let boxes = |[b, c]: [BuildBox; 2]| (b.aabb(), c.aabb());
    (left, boxes(below), boxes(above))
}

/// Splits at the object median along the widest centroid axis; returns the left count.
fn median_split(prims: &mut [PrimRef], centroid_bounds: &Aabb) -> usize {
    let extent = centroid_bounds.extent();
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |a, b| {
        a.bounds().centroid()[axis].total_cmp(&b.bounds().centroid()[axis])
    });
    mid
}

#[cfg(test)]
mod tests;
