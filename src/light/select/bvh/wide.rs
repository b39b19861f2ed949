//! The light BVH's 4-wide nodes. The SAOH build makes a binary tree; collapsing it puts
//! up to four clusters under every node (a node's children, inner children replaced by
//! theirs, breadth first), so a selection descends about half as many levels and chooses
//! among four importances at each. The four children's prepared bounds are stored
//! structure-of-arrays and their importances computed as one pass over `[f32; 4]` lanes,
//! which the compiler turns into SSE instructions: the multi-branching layout of the
//! geometry BVH (`geometry::bvh::node`, after Wald et al. 2008) applied to the light tree
//! of Conty Estevez & Kulla 2018.
//!
//! Each lane computes exactly what [`PreparedBounds::importance`] computes for the same
//! bounds and point (the same operations in the same order, branches turned into
//! selects), bit for bit; the tests (`wide/tests.rs`) check it. A node of point lights
//! takes a shorter formula with the same results (`WideNode::point_importance`).

use glam::{BVec4A, Vec4};

use super::Node;
use crate::light::ShadingPoint;
use crate::light::select::PreparedBounds;

/// Children per node.
pub(super) const LANES: usize = 4;

/// Up to four clusters' prepared bounds, lane by lane; unused lanes have φ = 0, which
/// gives them importance 0.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct WideNode {
    centre: [[f32; LANES]; 3],
    half: [[f32; LANES]; 3],
    radius2: [f32; LANES],
    d2_floor: [f32; LANES],
    phi: [f32; LANES],
    w: [[f32; LANES]; 3],
    cos_o: [f32; LANES],
    sin_o: [f32; LANES],
    cos_e: [f32; LANES],
    /// 1 where the lane's emitters emit on both sides, else 0.
    two_sided: [f32; LANES],
    /// Lane `l`'s child: a wide node's index, or a light's index when `leaf[l]`.
    pub child: [u32; LANES],
    /// Which lanes hold a single light.
    pub leaf: [bool; LANES],
    /// Whether every used lane's bounds are a point light's
    /// ([`PreparedBounds::is_point`]), whose importance needs no cones.
    points: bool,
}

impl WideNode {
    /// A node with every lane unused.
    fn empty() -> WideNode {
        WideNode {
            centre: [[0.0; LANES]; 3],
            half: [[0.0; LANES]; 3],
            radius2: [0.0; LANES],
            d2_floor: [0.0; LANES],
            phi: [0.0; LANES],
            w: [[0.0; LANES]; 3],
            cos_o: [1.0; LANES],
            sin_o: [0.0; LANES],
            cos_e: [1.0; LANES],
            two_sided: [0.0; LANES],
            child: [0; LANES],
            leaf: [false; LANES],
            points: false,
        }
    }

    /// Stores `b` in lane `l`.
    fn set_bounds(&mut self, l: usize, b: &PreparedBounds) {
        for axis in 0..3 {
            self.centre[axis][l] = b.centre[axis];
            self.half[axis][l] = b.half[axis];
            self.w[axis][l] = b.w[axis];
        }
        self.radius2[l] = b.radius2;
        self.d2_floor[l] = b.d2_floor;
        self.phi[l] = b.phi;
        self.cos_o[l] = b.cos_theta_o;
        self.sin_o[l] = b.sin_theta_o;
        self.cos_e[l] = b.cos_theta_e;
        self.two_sided[l] = b.two_sided as u8 as f32;
    }

    /// Marks the node as one of point lights where the bounds of its used lanes, `used`,
    /// all are.
    fn mark_points<'a>(&mut self, used: impl IntoIterator<Item = &'a PreparedBounds>) {
        self.points = used.into_iter().all(PreparedBounds::is_point);
    }

    /// The four lanes' importances at `at`: [`PreparedBounds::importance`] of each
    /// lane's bounds (see there for the formula), 0 for unused lanes. `glam::Vec4` is
    /// four SSE lanes on x86-64 (NEON on aarch64, scalar elsewhere).
    #[inline(always)]
    pub fn importance(&self, at: &ShadingPoint) -> [f32; LANES] {
        if self.points {
            return self.point_importance(at);
        }
        let v4 = Vec4::from_array;
        let splat = Vec4::splat;
        let (zero, one) = (Vec4::ZERO, Vec4::ONE);
        let safe_sqrt = |x: Vec4| x.max(zero).sqrt();
        let Sight {
            dist2,
            d2,
            w: [wx, wy, wz],
            cos_i,
            above,
        } = self.sight(at);
        let cos_w_signed = v4(self.w[0]) * wx + v4(self.w[1]) * wy + v4(self.w[2]) * wz;
        let two_sided = v4(self.two_sided).cmpne(zero);
        let cos_w = Vec4::select(two_sided, cos_w_signed.abs(), cos_w_signed);
        let sin_w = safe_sqrt(one - cos_w * cos_w);
        // The cone the bounding sphere subtends.
        let r2 = v4(self.radius2);
        let around = dist2.cmple(r2) | dist2.cmpeq(zero);
        let cos_b = Vec4::select(around, splat(-1.0), safe_sqrt(one - r2 / dist2));
        let sin_b = safe_sqrt(one - cos_b * cos_b);
        // θ' = max(0, θ_w − θ_o − θ_b), with cone::cos_sub_clamped / sin_sub_clamped.
        let (cos_o, sin_o) = (v4(self.cos_o), v4(self.sin_o));
        let inside_cone = cos_w.cmpgt(cos_o);
        let cos_x = Vec4::select(inside_cone, one, cos_w * cos_o + sin_w * sin_o);
        let sin_x = Vec4::select(inside_cone, zero, sin_w * cos_o - cos_w * sin_o);
        let cos_p = Vec4::select(cos_x.cmpgt(cos_b), one, cos_x * cos_b + sin_x * sin_b);
        // θ'_i = max(0, θ_i − θ_b).
        let sin_i = safe_sqrt(one - cos_i * cos_i);
        let cos_pi = Vec4::select(cos_i.cmpgt(cos_b), one, cos_i * cos_b + sin_i * sin_b);
        // The box's highest point above the shading point's tangent plane.
        let n_abs = at.n.abs();
        let highest = above
            + (splat(n_abs.x) * v4(self.half[0])
                + splat(n_abs.y) * v4(self.half[1])
                + splat(n_abs.z) * v4(self.half[2]));
        let phi = v4(self.phi);
        let importance = phi * cos_p / d2 * cos_pi;
        let lit = !cos_p.cmple(v4(self.cos_e));
        self.kept(importance, lit, d2, cos_pi, highest)
    }

    /// [`WideNode::importance`] of a node of point lights, bit for bit. With no extent,
    /// no floor and θ_o = π, the cones reduce to constants where a lane can contribute:
    /// the sphere subtends θ_b = 0 (cos 1, sin 0; d² = 0 contributes nothing), θ' = 0
    /// (cos θ' = 1 > cos θ_e), and cos θ'_i = cos θ_i · 1 + sin θ_i · 0 clamped at 1,
    /// which is cos θ_i (or +0 for −0, which contributes nothing either way); the
    /// highest point of the box is its centre. What is left is φ/d² · min(cos θ_i, 1):
    /// one square root and two divisions where the cones take five and three.
    #[inline]
    fn point_importance(&self, at: &ShadingPoint) -> [f32; LANES] {
        let one = Vec4::ONE;
        let Sight {
            d2, cos_i, above, ..
        } = self.sight(at);
        let cos_pi = Vec4::select(cos_i.cmpgt(one), one, cos_i);
        let importance = Vec4::from_array(self.phi) / d2 * cos_pi;
        self.kept(importance, BVec4A::splat(true), d2, cos_pi, above)
    }

    /// What both formulas derive from the shading point and the lanes' centres.
    #[inline(always)]
    fn sight(&self, at: &ShadingPoint) -> Sight {
        let v4 = Vec4::from_array;
        let splat = Vec4::splat;
        let zero = Vec4::ZERO;
        let (p, n) = (at.p, at.n);
        let (px, py, pz) = (splat(p.x), splat(p.y), splat(p.z));
        let (nx, ny, nz) = (splat(n.x), splat(n.y), splat(n.z));
        let (cx, cy, cz) = (v4(self.centre[0]), v4(self.centre[1]), v4(self.centre[2]));
        let (vx, vy, vz) = (px - cx, py - cy, pz - cz);
        let dist2 = vx * vx + vy * vy + vz * vz;
        let rcp = dist2.sqrt().recip();
        // wi: from the cluster towards the shading point, zero where it has no length.
        let unit = rcp.is_finite_mask() & rcp.cmpgt(zero);
        let wx = Vec4::select(unit, vx * rcp, zero);
        let wy = Vec4::select(unit, vy * rcp, zero);
        let wz = Vec4::select(unit, vz * rcp, zero);
        Sight {
            dist2,
            d2: dist2.max(v4(self.d2_floor)),
            w: [wx, wy, wz],
            cos_i: nx * -wx + ny * -wy + nz * -wz,
            above: nx * (cx - px) + ny * (cy - py) + nz * (cz - pz),
        }
    }

    /// `importance` in the lanes that pass every test (φ > 0, d² > 0, `lit`, θ'_i
    /// below π/2, the box partly above the horizon, a finite result), 0 elsewhere: the
    /// scalar version's early returns, as one mask.
    #[inline(always)]
    fn kept(
        &self,
        importance: Vec4,
        lit: BVec4A,
        d2: Vec4,
        cos_pi: Vec4,
        highest: Vec4,
    ) -> [f32; LANES] {
        let zero = Vec4::ZERO;
        let contributes = Vec4::from_array(self.phi).cmpgt(zero)
            & !d2.cmple(zero)
            & lit
            & !cos_pi.cmple(zero)
            & !highest.cmple(zero)
            & importance.is_finite_mask();
        Vec4::select(contributes, importance.max(zero), zero).to_array()
    }
}

/// What [`WideNode::importance`]'s two formulas share, lane by lane.
struct Sight {
    /// The squared distance from the shading point to the centre, and the same floored.
    dist2: Vec4,
    d2: Vec4,
    /// The unit direction from the centre towards the shading point (zero where the
    /// distance has no reciprocal).
    w: [Vec4; 3],
    /// cos θ_i: the shading normal against the direction into the centre.
    cos_i: Vec4,
    /// n·(c − p): the centre's height above the shading point's tangent plane.
    above: Vec4,
}

/// Where a light sits in the wide tree: its node and lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Slot {
    pub node: u32,
    pub lane: u8,
}

/// Marks a light outside the tree (it emits nothing and is never chosen).
pub(super) const NOT_IN_TREE: Slot = Slot {
    node: u32::MAX,
    lane: 0,
};

/// The collapsed tree: nodes (root first), each node's slot in its parent (the root's
/// is unused), each light's slot, and the depth of the deepest leaf.
pub(super) struct WideTree {
    pub nodes: Vec<WideNode>,
    pub parent: Vec<Slot>,
    pub leaf_of: Vec<Slot>,
    pub depth: usize,
}

/// Collapses the binary tree `binary` (root at 0, an inner node; a node's first child
/// follows it, `second_or_light` names the second) over `lights` lights.
pub(super) fn collapse(binary: &[Node], prepared: &[PreparedBounds], lights: usize) -> WideTree {
    let mut tree = WideTree {
        nodes: Vec::with_capacity(binary.len() / 2 + 1),
        parent: Vec::with_capacity(binary.len() / 2 + 1),
        leaf_of: vec![NOT_IN_TREE; lights],
        depth: 0,
    };
    add_node(&mut tree, binary, prepared, 0, NOT_IN_TREE, 1);
    tree
}

/// Adds the wide node for binary inner node `b` at depth `depth` (the root's children
/// are at depth 1) and its subtree; returns its index.
fn add_node(
    tree: &mut WideTree,
    binary: &[Node],
    prepared: &[PreparedBounds],
    b: usize,
    parent: Slot,
    depth: usize,
) -> u32 {
    let children = |i: usize| [i + 1, binary[i].second_or_light as usize];
    // Breadth first: expand the shallowest inner cluster (the first of equals) until four
    // lanes, so every inner lane lies two binary levels below `b` unless a leaf stopped it.
    let mut lanes: Vec<(usize, u32)> = children(b).map(|i| (i, 1)).to_vec();
    while lanes.len() < LANES {
        let Some(k) = (0..lanes.len())
            .filter(|&k| !binary[lanes[k].0].leaf)
            .min_by_key(|&k| lanes[k].1)
        else {
            break;
        };
        let (i, generation) = lanes[k];
        let [first, second] = children(i);
        lanes[k] = (first, generation + 1);
        lanes.insert(k + 1, (second, generation + 1));
    }
    let index = tree.nodes.len() as u32;
    tree.nodes.push(WideNode::empty());
    tree.parent.push(parent);
    tree.depth = tree.depth.max(depth);
    let mut node = WideNode::empty();
    node.mark_points(lanes.iter().map(|&(i, _)| &prepared[i]));
    for (l, &(i, _)) in lanes.iter().enumerate() {
        node.set_bounds(l, &prepared[i]);
        let slot = Slot {
            node: index,
            lane: l as u8,
        };
        if binary[i].leaf {
            node.leaf[l] = true;
            node.child[l] = binary[i].second_or_light;
            tree.leaf_of[binary[i].second_or_light as usize] = slot;
        } else {
            node.child[l] = add_node(tree, binary, prepared, i, slot, depth + 1);
        }
    }
    tree.nodes[index as usize] = node;
    index
}

#[cfg(target_arch = "x86_64")]
mod pair;

#[cfg(target_arch = "x86_64")]
pub(super) use pair::importance_pair;

#[cfg(test)]
mod tests;
