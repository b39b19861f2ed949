//! A bounding volume hierarchy over primitives known only by their boxes, so a scene can
//! keep mixed shapes (triangles, spheres, rectangles, disks) in one enum and intersect
//! them through a closure.
//!
//! Build: binary binned SAH (Wald 2007), collapsed into 4-wide nodes whose child boxes
//! are stored structure-of-arrays (Wald et al. 2008; Embree's BVH4), see [`node`].
//! Queries: nearest-first closest-hit and any-hit traversal with a fixed-size stack
//! and the robust slab test of Ize 2013.
//!
//! The module leaves shading data (normals, uv) and the primitives themselves to the
//! caller; [`TriangleSet`] is the ready-made fast path for triangle meshes.

mod build;
mod collapse;
pub mod node;
mod traverse;

pub mod bench_mesh;
pub mod triangle_set;

#[cfg(test)]
mod tests;

pub use triangle_set::TriangleSet;

use crate::geometry::{Aabb, Ray};
use node::{MAX_PRIMITIVES, WideNode};

/// A 4-wide BVH over primitives given by their boxes.
///
/// The tree stores primitive *positions in leaf order*, not the caller's indices: the
/// callbacks of [`Bvh::closest_hit`] and [`Bvh::any_hit`] receive `prim`, a position in
/// [`Bvh::primitive_order`], and `primitive_order()[prim]` is the caller's original index.
/// Callers that reorder their primitive arrays by `primitive_order` (as [`TriangleSet`]
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
        assert!(
            bounds.len() <= MAX_PRIMITIVES,
            "Bvh holds at most 2^29 primitives, got {}",
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
        let binary = build::build_binary(bounds);
        let root_bounds = binary.nodes[0].bounds;
        let wide = collapse::collapse(&binary);
        Bvh {
            nodes: wide.nodes,
            order: binary.order,
            bounds: root_bounds,
            depth: wide.depth,
        }
    }

    /// Primitive indices in leaf order: `primitive_order()[prim]` is the original index
    /// (into the `bounds` given to [`Bvh::build`]) of the primitive the callbacks call
    /// `prim`. Reorder primitive arrays by it to index them with `prim` directly.
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
        intersect: F,
    ) -> Option<(u32, f32)> {
        if self.nodes.is_empty() {
            return None;
        }
        traverse::closest_hit(&self.nodes, self.depth, ray, t_max, intersect)
    }

    /// Any hit in (0, t_max), for shadow rays: `occludes(prim, ray, t_max)` (with `prim` in
    /// leaf order, see [`Bvh::primitive_order`]) reports a hit in (0, t_max); traversal
    /// stops at the first primitive for which it returns true.
    #[inline]
    pub fn any_hit<F: FnMut(u32, &Ray, f32) -> bool>(
        &self,
        ray: &Ray,
        t_max: f32,
        occludes: F,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        traverse::any_hit(&self.nodes, self.depth, ray, t_max, occludes)
    }

    /// The box of all primitives (empty for an empty tree).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of 4-wide nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of primitives.
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
