//! Light BVH selection (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights
//! with Adaptive Tree Splitting"; the design of pbrt-v4's `BVHLightSampler`, §12.6.3):
//! a tree over the lights whose nodes carry [`LightBounds`]. The SAOH builds it binary;
//! it is then collapsed to 4-wide nodes ([`wide`]), whose four importances are computed
//! in one SIMD pass. Selection walks from the root, choosing each child with probability
//! proportional to its importance at the shading point and reusing the one random number;
//! the pmf is the product of the choices. `pmf` re-walks the same path, found from the
//! light's slot and the nodes' parents, and so returns exactly the probability `select`
//! used. O(depth) = O(log n) for both.
//!
//! On `mesh_ply_serialized` (256 emitting triangles) the binary tree's descent was a third
//! of the render; the 4-wide one descends half as many levels with one importance pass
//! per level (BENCHMARKS.md, session 8).
//!
//! A renderer that shades in stages walks up to eight shading points' trees together,
//! level by level ([`BvhSelector::select_lanes`], in `lanes`), two walks per AVX2
//! importance pass where the processor has it; each step of a level is [`descend`]'s.

mod build;
mod descend;
mod lanes;
mod saoh;
mod wide;

use build::BuildLight;
use descend::{Search, Step, Walk, descend, usable_total};
use wide::{NOT_IN_TREE, Slot, WideNode, collapse};

use super::{LightSelector, PreparedBounds, Selection};
use crate::light::{Light, LightBounds, ShadingPoint};
use crate::sampling::sampler::ONE_MINUS_EPSILON;

/// A node of the binary tree the SAOH builds: its bounds and either its second child
/// (the first follows it in the array) or, in a leaf, the light.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: LightBounds,
    second_or_light: u32,
    leaf: bool,
}

impl Node {
    /// What a slot holds before the build fills it: an inner node whose second child is
    /// out of range, so a slot left unfilled fails loudly instead of naming light 0.
    const PLACEHOLDER: Node = Node {
        bounds: LightBounds::EMPTY,
        second_or_light: u32::MAX,
        leaf: false,
    };
}

/// The light BVH selector.
#[derive(Clone, Debug)]
pub struct BvhSelector {
    /// The 4-wide nodes, root first; empty when the tree holds fewer than two lights.
    nodes: Vec<WideNode>,
    /// Each node's slot in its parent (the root's is unused).
    parent: Vec<Slot>,
    /// Each light's slot ([`NOT_IN_TREE`] for lights outside the tree).
    leaf_of: Vec<Slot>,
    /// The one light of a one-light tree, with its prepared bounds.
    single: Option<(usize, PreparedBounds)>,
    /// Depth of the deepest leaf.
    depth: usize,
    /// Lights at infinity (environments), outside the tree: chosen with probability
    /// n_inf / (n_inf + 1) — the tree counts as one more choice — as pbrt-v4 does.
    infinite: Vec<usize>,
}

impl BvhSelector {
    /// Builds the tree over `lights` with the SAOH; lights with zero power stay out of
    /// it (pmf 0).
    pub fn new(lights: &[Light]) -> BvhSelector {
        let mut items: Vec<BuildLight> = lights
            .iter()
            .enumerate()
            .map(|(index, l)| {
                let bounds = l.bounds();
                BuildLight {
                    index,
                    bounds,
                    centroid: bounds.aabb.centroid(),
                }
            })
            .filter(|l| l.bounds.phi > 0.0 && l.centroid.is_finite())
            .collect();
        let nodes = if items.is_empty() {
            Vec::new()
        } else {
            build::build(&mut items)
        };
        let prepared: Vec<PreparedBounds> = nodes
            .iter()
            .map(|n| PreparedBounds::new(&n.bounds))
            .collect();
        let infinite = lights
            .iter()
            .enumerate()
            .filter(|(_, l)| l.is_infinite())
            .map(|(i, _)| i)
            .collect();
        let mut selector = BvhSelector {
            nodes: Vec::new(),
            parent: Vec::new(),
            leaf_of: vec![NOT_IN_TREE; lights.len()],
            single: None,
            depth: 0,
            infinite,
        };
        match nodes.first() {
            None => {}
            Some(root) if root.leaf => {
                selector.single = Some((root.second_or_light as usize, prepared[0]));
            }
            Some(_) => {
                let tree = collapse(&nodes, &prepared, lights.len());
                selector.nodes = tree.nodes;
                selector.parent = tree.parent;
                selector.leaf_of = tree.leaf_of;
                selector.depth = tree.depth;
            }
        }
        selector
    }

    /// The same selector giving the lights at infinity marked in `excluded` probability
    /// zero (the tree's lights stay: only environments draw no samples under a strategy,
    /// see [`Light::draws_no_samples`]).
    pub fn excluding(mut self, excluded: &[bool]) -> BvhSelector {
        self.infinite.retain(|&i| excluded.get(i) != Some(&true));
        self
    }

    /// Number of (4-wide) nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Depth of the deepest leaf (levels of 4-wide nodes).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// True when the tree holds at least one light.
    fn has_tree(&self) -> bool {
        self.single.is_some() || !self.nodes.is_empty()
    }
}

impl BvhSelector {
    /// Probability of choosing one given light at infinity, and of entering the tree.
    #[inline]
    fn split(&self) -> (f32, f32) {
        let tree = self.has_tree() as usize;
        let choices = (self.infinite.len() + tree) as f32;
        (1.0 / choices, tree as f32 / choices)
    }

    /// `select`'s first choice, by `u`: a light at infinity (`Err`), or the tree, with
    /// `u` rescaled to walk it (`Ok`); the tree's selection then has its probability
    /// multiplied by [`BvhSelector::tree_share`].
    #[inline(always)]
    fn entry(&self, u: f32) -> Result<f32, Selection> {
        if self.infinite.is_empty() {
            return Ok(u);
        }
        let (p_one, p_tree) = self.split();
        let u = u.clamp(0.0, ONE_MINUS_EPSILON);
        let p_infinite = 1.0 - p_tree;
        if u < p_infinite {
            let x = u / p_one;
            let k = (x as usize).min(self.infinite.len() - 1);
            return Err(Selection {
                index: self.infinite[k],
                pmf: p_one,
                u_reused: (x - k as f32).clamp(0.0, ONE_MINUS_EPSILON),
            });
        }
        Ok(((u - p_infinite) / p_tree).clamp(0.0, ONE_MINUS_EPSILON))
    }

    /// The probability of entering the tree (1 without lights at infinity).
    #[inline(always)]
    fn tree_share(&self) -> f32 {
        if self.infinite.is_empty() {
            1.0
        } else {
            self.split().1
        }
    }

    /// Selection within the tree (one light, or the walk of [`descend`] from the root).
    fn tree_select(&self, at: &ShadingPoint, u: f32) -> Option<Selection> {
        if let Some((light, bounds)) = &self.single {
            // One light: take it if it can contribute at all.
            return (bounds.importance(at) > 0.0).then_some(Selection {
                index: *light,
                pmf: 1.0,
                u_reused: u.clamp(0.0, ONE_MINUS_EPSILON),
            });
        }
        self.nodes.first()?;
        let mut walk = Walk::from_root(u);
        loop {
            let node = &self.nodes[walk.node as usize];
            match descend(node, &node.importance(at), walk, Search::Linear) {
                Step::Inner(next) => walk = next,
                Step::Light(selection) => return Some(selection),
                Step::Dead => return None,
            }
        }
    }

    fn tree_pmf(&self, at: &ShadingPoint, index: usize) -> f32 {
        if let Some((light, bounds)) = &self.single {
            return if *light == index && bounds.importance(at) > 0.0 {
                1.0
            } else {
                0.0
            };
        }
        let Some(&leaf) = self.leaf_of.get(index).filter(|s| **s != NOT_IN_TREE) else {
            return 0.0;
        };
        self.path_pmf(at, leaf)
    }

    /// The probability of taking `slot` from the root: the parents' choices multiplied
    /// root first, in the order `tree_select` multiplied them (a dead end anywhere gives 0).
    fn path_pmf(&self, at: &ShadingPoint, slot: Slot) -> f32 {
        let importance = self.nodes[slot.node as usize].importance(at);
        let Some(total) = usable_total(&importance) else {
            return 0.0;
        };
        let above = if slot.node == 0 {
            1.0
        } else {
            self.path_pmf(at, self.parent[slot.node as usize])
        };
        above * (importance[slot.lane as usize] / total)
    }
}

impl LightSelector for BvhSelector {
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection> {
        match self.entry(u) {
            Err(infinite) => Some(infinite),
            Ok(u) => {
                let mut s = self.tree_select(at, u)?;
                s.pmf *= self.tree_share();
                Some(s)
            }
        }
    }

    fn pmf(&self, at: &ShadingPoint, index: usize) -> f32 {
        if self.infinite.is_empty() {
            return self.tree_pmf(at, index);
        }
        let (p_one, p_tree) = self.split();
        if self.infinite.contains(&index) {
            p_one
        } else {
            p_tree * self.tree_pmf(at, index)
        }
    }
}
