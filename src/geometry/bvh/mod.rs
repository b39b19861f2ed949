//! A bounding volume hierarchy over primitives known only by their boxes, so a scene can
//! keep mixed shapes (triangles, spheres, rectangles, disks) in one enum and intersect
//! them through a closure.
//!
//! Build: binary binned SAH (Wald 2007), collapsed into 4-wide nodes whose child boxes
//! are stored structure-of-arrays (Wald et al. 2008; Embree's BVH4), see [`node`].
//! Queries: nearest-first closest-hit and any-hit traversal with a fixed-size stack
//! and the robust slab test of Ize 2013, a primitive or a whole leaf at a time.
//!
//! Leaves: one primitive at a time ([`Bvh::build`]), or blocks of up to four that the
//! caller tests at once in SIMD lanes ([`Bvh::build_blocks`]: the SAH counts whole
//! blocks, as Embree's builders do for its Triangle4 leaves, and leaves are laid out at
//! multiples of four). Blocks fill leaves, so the tree has about half the nodes.
//!
//! The module leaves shading data (normals, uv) and the primitives themselves to the
//! caller; [`TriangleSet`] is the ready-made fast path for triangle meshes.

mod build;
mod collapse;
pub(crate) mod huge_pages;
pub mod node;
mod packet;
mod prim_ref;
mod traverse;

pub mod bench_mesh;
pub mod triangle_set;

#[cfg(test)]
mod tests;

pub use packet::PACKET;
pub use triangle_set::TriangleSet;

use crate::geometry::{Aabb, Ray};
use build::LeafKind;
use node::{MAX_PRIMITIVES, WideNode};

/// Primitives per leaf block of [`Bvh::build_blocks`]: leaves start at multiples of it.
pub const BLOCK: usize = node::MAX_LEAF_SIZE;

/// The [`Bvh::primitive_order`] entry of an unused slot in a leaf block.
pub const PADDING: u32 = u32::MAX;

/// A 4-wide BVH over primitives given by their boxes.
///
/// The tree stores primitive *positions in leaf order*, not the caller's indices: the
/// callbacks of [`Bvh::closest_hit`] and [`Bvh::any_hit`] receive `prim`, a position in
/// [`Bvh::primitive_order`], and `primitive_order()[prim]` is the caller's original index
/// (never [`PADDING`] for a position a callback receives). Callers that reorder their primitive arrays by `primitive_order` (as [`TriangleSet`]
/// does) can use `prim` directly.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<WideNode>,
    order: Vec<u32>,
    bounds: Aabb,
    depth: usize,
}

impl Bvh {
    /// Builds over primitives given by their bounding boxes: binned SAH (Wald 2007, "On
    /// fast Construction of SAH-based Bounding Volume Hierarchies"), then collapsed to a
    /// 4-wide BVH. Empty input gives a tree that nothing hits. Boxes may be flat; a box
    /// with a NaN coordinate counts as empty (its primitive is never offered to the
    /// callbacks).
    ///
    /// # Panics
    /// With more than [`node::MAX_PRIMITIVES`] (2²⁹) primitives.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        Bvh::build_with(bounds, LeafKind::Single)
    }

    /// Builds for leaves tested a block of up to [`node::MAX_LEAF_SIZE`] primitives at once
    /// (as [`TriangleSet`] tests four triangles in SIMD lanes): the SAH counts leaves in
    /// whole blocks (so leaves fill up), and every leaf starts at a multiple of
    /// [`BLOCK`] in [`Bvh::primitive_order`], whose unused slots hold [`PADDING`].
    ///
    /// # Panics
    /// With more than [`node::MAX_PRIMITIVES`] / [`BLOCK`] primitives.
    pub fn build_blocks(bounds: &[Aabb]) -> Bvh {
        Bvh::build_with(bounds, LeafKind::Blocks)
    }

    fn build_with(bounds: &[Aabb], kind: LeafKind) -> Bvh {
        let limit = match kind {
            LeafKind::Single => MAX_PRIMITIVES,
            LeafKind::Blocks => MAX_PRIMITIVES / BLOCK,
        };
        assert!(
            bounds.len() <= limit,
            "Bvh holds at most {limit} primitives, got {}",
            bounds.len()
        );
        if bounds.is_empty() {
            return Bvh {
                nodes: Vec::new(),
                order: Vec::new(),
                bounds: Aabb::EMPTY,
                depth: 0,
            };
        }
        let binary = build::build_binary(bounds, kind);
        let root_bounds = binary.nodes[0].bounds;
        let mut wide = collapse::collapse(&binary);
        let order = match kind {
            LeafKind::Single => binary.order,
            LeafKind::Blocks => collapse::lay_out_blocks(&mut wide.nodes, &binary.order),
        };
        Bvh {
            nodes: wide.nodes,
            order,
            bounds: root_bounds,
            depth: wide.depth,
        }
    }

    /// Primitive indices in leaf order: `primitive_order()[prim]` is the original index
    /// (into the `bounds` given to [`Bvh::build`]) of the primitive the callbacks call
    /// `prim`. Reorder primitive arrays by it to index them with `prim` directly. After
    /// [`Bvh::build_blocks`] the unused slots of leaf blocks hold [`PADDING`]
    /// (`u32::MAX`), which is no index: skip or replace those entries.
    pub fn primitive_order(&self) -> &[u32] {
        &self.order
    }

    /// Closest hit in (0, t_max). `intersect(prim, ray, t_closest)` gets a leaf-order
    /// position `prim` (see [`Bvh::primitive_order`]) and the closest distance so far, and
    /// returns `Some(t)` only for a hit with t < t_closest. Returns (prim, t) of the
    /// closest hit, `prim` again in leaf order.
    #[inline]
    pub fn closest_hit<F: FnMut(u32, &Ray, f32) -> Option<f32>>(
        &self,
        ray: &Ray,
        t_max: f32,
        mut intersect: F,
    ) -> Option<(u32, f32)> {
        self.closest_hit_leaf(ray, t_max, |first, count, ray, mut t_closest| {
            let mut best = None;
            for prim in first..first + count {
                if let Some(t) = intersect(prim, ray, t_closest).filter(|&t| t < t_closest) {
                    t_closest = t;
                    best = Some((prim, t));
                }
            }
            best
        })
    }

    /// Closest hit in (0, t_max), a leaf at a time: `leaf(first, count, ray, t_closest)`
    /// tests the primitives at leaf-order positions `first .. first + count` and returns
    /// (id, t) of the closest with t < t_closest, `id` being whatever the caller wants
    /// reported. Returns (id, t) of the closest hit.
    #[inline]
    pub fn closest_hit_leaf<F: FnMut(u32, u32, &Ray, f32) -> Option<(u32, f32)>>(
        &self,
        ray: &Ray,
        t_max: f32,
        leaf: F,
    ) -> Option<(u32, f32)> {
        if self.nodes.is_empty() {
            return None;
        }
        traverse::closest_hit(&self.nodes, self.depth, ray, t_max, leaf)
    }

    /// Closest hits of a packet of [`PACKET`] rays, traversed together (see the `packet`
    /// module): ray `lane` is sought in (0, `t_max[lane]`); a lane whose ray is not finite
    /// or whose t_max is not positive takes no part (its answer is `None`).
    /// `leaf(lane, first, count, ray, t_closest)` tests one ray against a leaf as
    /// [`Bvh::closest_hit_leaf`]'s callback does. Each answer has the distance of the
    /// single-ray query's, except where the visiting order decides: between primitives
    /// hit at exactly the same distance, or within the slab test's rounding margin of a
    /// box's entry face (see the `packet` module).
    #[inline]
    pub fn closest_hit_packet<F: FnMut(usize, u32, u32, &Ray, f32) -> Option<(u32, f32)>>(
        &self,
        rays: &[Ray; PACKET],
        t_max: &[f32; PACKET],
        leaf: F,
    ) -> [Option<(u32, f32)>; PACKET] {
        if self.nodes.is_empty() {
            return [None; PACKET];
        }
        packet::closest_hit(&self.nodes, self.depth, rays, t_max, leaf)
    }

    /// Any hit in (0, t_max), for shadow rays: `occludes(prim, ray, t_max)` (with `prim` in
    /// leaf order, see [`Bvh::primitive_order`]) reports a hit in (0, t_max); traversal
    /// stops at the first primitive for which it returns true.
    #[inline]
    pub fn any_hit<F: FnMut(u32, &Ray, f32) -> bool>(
        &self,
        ray: &Ray,
        t_max: f32,
        mut occludes: F,
    ) -> bool {
        self.any_hit_leaf(ray, t_max, |first, count, ray, t_max| {
            (first..first + count).any(|prim| occludes(prim, ray, t_max))
        })
    }

    /// Any hit in (0, t_max), a leaf at a time: `leaf(first, count, ray, t_max)` reports
    /// whether a primitive at leaf-order positions `first .. first + count` blocks the ray.
    #[inline]
    pub fn any_hit_leaf<F: FnMut(u32, u32, &Ray, f32) -> bool>(
        &self,
        ray: &Ray,
        t_max: f32,
        leaf: F,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        traverse::any_hit(&self.nodes, self.depth, ray, t_max, leaf)
    }

    /// At most `max` boxes (but at least the root's children) that together hold every
    /// primitive: the root's children, then the inner child of largest area replaced by
    /// its own children, again and again until the next replacement would pass `max`.
    /// For telling where whole bundles of rays can meet nothing (`render::frustum`).
    /// Empty for an empty tree.
    pub fn cut(&self, max: usize) -> Vec<Aabb> {
        let Some(root) = self.nodes.first() else {
            return Vec::new();
        };
        let children = |node: &WideNode| {
            (0..node::WIDTH)
                .map(|lane| (node.child_bounds(lane), node.children[lane]))
                .filter(|(b, _)| !b.is_empty())
                .collect::<Vec<_>>()
        };
        let mut cut = children(root);
        loop {
            let largest = (0..cut.len())
                .filter(|&i| !cut[i].1.is_leaf())
                .max_by(|&a, &b| {
                    let area = |i: usize| cut[i].0.surface_area();
                    area(a).total_cmp(&area(b))
                });
            let Some(i) = largest else { break };
            let inner = children(&self.nodes[cut[i].1.0 as usize]);
            if cut.len() - 1 + inner.len() > max {
                break;
            }
            cut.swap_remove(i);
            cut.extend(inner);
        }
        cut.into_iter().map(|(b, _)| b).collect()
    }

    /// The box of all primitives (empty for an empty tree).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of 4-wide nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of primitive slots in leaf order (with a block build's padding).
    pub fn primitive_count(&self) -> usize {
        self.order.len()
    }

    /// Number of wide nodes on the longest root-to-leaf path.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Bytes used by nodes and the primitive order.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<WideNode>() + self.order.len() * 4
    }

    /// SAH cost of the wide tree relative to one primitive test, with node traversal
    /// costing `traversal_cost` (MacDonald & Booth 1990): Σ A(node)/A(root) · C_trav +
    /// Σ A(leaf)/A(root) · N(leaf). Lower is better; useful to compare builds.
    pub fn sah_cost(&self, traversal_cost: f32) -> f32 {
        traverse::sah_cost(&self.nodes, &self.bounds, traversal_cost)
    }
}
