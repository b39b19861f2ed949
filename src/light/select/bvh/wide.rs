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
//! selects), bit for bit; the tests below check it.

use glam::Vec4;

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

    /// The four lanes' importances at `at`: [`PreparedBounds::importance`] of each
    /// lane's bounds (see there for the formula), 0 for unused lanes. `glam::Vec4` is
    /// four SSE lanes on x86-64 (NEON on aarch64, scalar elsewhere).
    #[inline]
    pub fn importance(&self, at: &ShadingPoint) -> [f32; LANES] {
        let v4 = Vec4::from_array;
        let splat = Vec4::splat;
        let (zero, one) = (Vec4::ZERO, Vec4::ONE);
        let safe_sqrt = |x: Vec4| x.max(zero).sqrt();
        let (p, n) = (at.p, at.n);
        let (px, py, pz) = (splat(p.x), splat(p.y), splat(p.z));
        let (nx, ny, nz) = (splat(n.x), splat(n.y), splat(n.z));
        let (cx, cy, cz) = (v4(self.centre[0]), v4(self.centre[1]), v4(self.centre[2]));
        let (vx, vy, vz) = (px - cx, py - cy, pz - cz);
        let dist2 = vx * vx + vy * vy + vz * vz;
        let d2 = dist2.max(v4(self.d2_floor));
        let rcp = dist2.sqrt().recip();
        // wi: from the cluster towards the shading point, zero where it has no length.
        let unit = rcp.is_finite_mask() & rcp.cmpgt(zero);
        let wx = Vec4::select(unit, vx * rcp, zero);
        let wy = Vec4::select(unit, vy * rcp, zero);
        let wz = Vec4::select(unit, vz * rcp, zero);
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
        let cos_i = nx * -wx + ny * -wy + nz * -wz;
        let sin_i = safe_sqrt(one - cos_i * cos_i);
        let cos_pi = Vec4::select(cos_i.cmpgt(cos_b), one, cos_i * cos_b + sin_i * sin_b);
        // The box's highest point above the shading point's tangent plane.
        let n_abs = n.abs();
        let highest = (nx * (cx - px) + ny * (cy - py) + nz * (cz - pz))
            + (splat(n_abs.x) * v4(self.half[0])
                + splat(n_abs.y) * v4(self.half[1])
                + splat(n_abs.z) * v4(self.half[2]));
        let phi = v4(self.phi);
        let importance = phi * cos_p / d2 * cos_pi;
        // The scalar version's early returns, as one mask.
        let contributes = phi.cmpgt(zero)
            & !d2.cmple(zero)
            & !cos_p.cmple(v4(self.cos_e))
            & !cos_pi.cmple(zero)
            & !highest.cmple(zero)
            & importance.is_finite_mask();
        Vec4::select(contributes, importance.max(zero), zero).to_array()
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use crate::light::LightBounds;
    use glam::Vec3;

    #[test]
    fn every_lane_equals_the_scalar_importance_bit_for_bit() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let mut nonzero = 0;
        for i in 0..50_000 {
            let mut node = WideNode::empty();
            let mut scalar = Vec::new();
            // 1 to 4 lanes used: flat, point-like and solid boxes.
            for l in 0..1 + i % LANES {
                let lo = Vec3::new(next(), next(), next()) * 4.0;
                let size = match (i + l) % 3 {
                    0 => Vec3::new(next().abs(), 0.0, next().abs()),
                    1 => Vec3::ZERO,
                    _ => Vec3::new(next(), next(), next()).abs() * 3.0,
                };
                let b = PreparedBounds::new(&LightBounds {
                    aabb: Aabb {
                        min: lo,
                        max: lo + size,
                    },
                    phi: next().abs() * 10.0,
                    w: Vec3::new(next(), next(), next()).normalize_or(Vec3::Z),
                    cos_theta_o: next(),
                    cos_theta_e: if l % 2 == 0 { 0.0 } else { next() },
                    two_sided: (i + l) % 5 == 0,
                });
                node.set_bounds(l, &b);
                scalar.push(b);
            }
            let p = if i % 7 == 0 {
                scalar[0].centre
            } else {
                Vec3::new(next(), next(), next()) * 6.0
            };
            let at = ShadingPoint {
                p,
                ng: Vec3::Y,
                n: Vec3::new(next(), next(), next()).normalize_or(Vec3::Y),
            };
            let lanes = node.importance(&at);
            for (l, lane) in lanes.iter().enumerate() {
                let expected = scalar.get(l).map_or(0.0, |b| b.importance(&at));
                assert_eq!(lane.to_bits(), expected.to_bits(), "case {i} lane {l}");
                nonzero += (expected > 0.0) as u32;
            }
        }
        assert!(nonzero > 25_000, "only {nonzero} lanes with importance");
    }
}
