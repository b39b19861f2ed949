//! Packet traversal: eight rays walk the 4-wide tree together (Wald, Slusallek, Benthin
//! & Wagner 2001, "Interactive Rendering with Coherent Ray Tracing"; the "hybrid" packets
//! of Embree's `rtcIntersect8`). Each child box is tested against all eight rays at once,
//! one ray per SIMD lane (AVX2 where the CPU has it, chosen at run time; two SSE halves
//! otherwise), and a subtree is entered when any ray still reaches it. Coherent rays (a
//! pixel's samples, neighbouring camera rays) share most of their path, so one node test
//! serves eight rays; leaves are tested one active ray at a time by the caller.
//!
//! Every lane runs the single-ray slab test of [`WideNode::intersect`] with the same
//! operations in the same order (the near plane picked by the sign of 1/d, the same
//! `max`/`min` nesting, the same robust exit scale), and a ray takes part in a box's
//! children or leaf only if it entered that box, and, for a box taken from the stack,
//! no farther than its closest hit so far (the single-ray traversal's rules). So each ray
//! finds the closest hit the single-ray query finds, at the same distance. The visiting
//! order differs, so between two hits at exactly the same distance the other one may
//! win; and, as the single-ray query's own answer there depends on its order, between
//! hits within the slab test's rounding margin (a few ulps) of a box's entry face.

use std::mem::MaybeUninit;

use glam::Vec4;

use super::node::{ChildRef, ROBUST_EXIT_SCALE, RayData, WIDTH, WideNode, max, min};
use crate::geometry::Ray;

/// Rays per packet.
pub const PACKET: usize = 8;

/// One f32 per ray of a packet.
type Lanes = [f32; PACKET];

/// A stack entry: a child and each ray's entry distance into its box (+∞ for a ray that
/// misses it).
type Entry = (ChildRef, Lanes);

/// Entries of the fixed-size stack; deeper trees get a heap stack. (The single-ray
/// traversal's `Stack`, made generic over its entry, cost this traversal 24 % more
/// instructions: its pops return the 36-byte entry through an `Option`.)
const STACK_SIZE: usize = 64;

/// What the slab test needs of the packet, structure-of-arrays: origins, reciprocal
/// directions and, per axis, an all-ones mask in lanes whose 1/d is negative (there the
/// upper plane is the near one).
struct PacketData {
    o: [Lanes; 3],
    inv_d: [Lanes; 3],
    negative: [[u32; PACKET]; 3],
    /// Where the rays taking part agree in the sign of 1/d along every axis (camera rays
    /// through neighbouring pixels almost always do): the planes they all meet first
    /// (x, y, z) and last, as indices into [`WideNode::planes`].
    uniform: Option<[usize; 6]>,
}

impl PacketData {
    /// The packet's data; `valid[lane]` false gives a harmless placeholder ray (the
    /// traversal keeps such a lane out of every box).
    fn new(rays: &[Ray; PACKET], valid: &[bool; PACKET]) -> PacketData {
        let mut data = PacketData {
            o: [[0.0; PACKET]; 3],
            inv_d: [[1.0; PACKET]; 3],
            negative: [[0; PACKET]; 3],
            uniform: None,
        };
        for (lane, ray) in rays.iter().enumerate() {
            if !valid[lane] {
                continue;
            }
            let inv_d = ray.d.recip();
            for axis in 0..3 {
                data.o[axis][lane] = ray.o[axis];
                data.inv_d[axis][lane] = inv_d[axis];
                // As in `RayData::new`: the sign of 1/d (so −0 counts as negative).
                data.negative[axis][lane] = if inv_d[axis] < 0.0 { u32::MAX } else { 0 };
            }
        }
        let first = valid.iter().position(|&v| v).unwrap_or(0);
        let agree = |axis: usize| {
            (0..PACKET).all(|l| !valid[l] || data.negative[axis][l] == data.negative[axis][first])
        };
        if (0..3).all(agree) {
            // Every ray's planes are then the first valid ray's, as `RayData` picks them.
            data.uniform = RayData::new(&rays[first]).map(|r| {
                let [n0, n1, n2] = r.near;
                let [f0, f1, f2] = r.far;
                [n0, n1, n2, f0, f1, f2]
            });
        }
        data
    }

    /// Entry distance of each ray of `live` into child `c` of `node`, +∞ where the ray
    /// misses the box within its `t_closest` or is not live: the single-ray slab test,
    /// lane by lane. With `UNIFORM` (only where [`PacketData::uniform`] is set) the near
    /// and far planes are the same for every ray, so no lane picks between them: the
    /// same values, fewer instructions.
    #[inline(always)]
    fn entry<const UNIFORM: bool>(
        &self,
        node: &WideNode,
        c: usize,
        t_closest: &Lanes,
        live: &[bool; PACKET],
    ) -> Lanes {
        let lo = [node.planes[0][c], node.planes[1][c], node.planes[2][c]];
        let hi = [node.planes[3][c], node.planes[4][c], node.planes[5][c]];
        let order = self.uniform.unwrap_or([0, 1, 2, 3, 4, 5]);
        let (first, last): ([f32; 3], [f32; 3]) = (
            std::array::from_fn(|axis| node.planes[order[axis]][c]),
            std::array::from_fn(|axis| node.planes[order[axis + 3]][c]),
        );
        let mut entry = [0.0f32; PACKET];
        for lane in 0..PACKET {
            let mut near = [0.0f32; 3];
            let mut far = [0.0f32; 3];
            for axis in 0..3 {
                let (o, inv) = (self.o[axis][lane], self.inv_d[axis][lane]);
                if UNIFORM {
                    near[axis] = (first[axis] - o) * inv;
                    far[axis] = (last[axis] - o) * inv;
                } else {
                    let to_lo = (lo[axis] - o) * inv;
                    let to_hi = (hi[axis] - o) * inv;
                    let m = self.negative[axis][lane];
                    near[axis] = f32::from_bits((to_hi.to_bits() & m) | (to_lo.to_bits() & !m));
                    far[axis] = f32::from_bits((to_lo.to_bits() & m) | (to_hi.to_bits() & !m));
                }
            }
            // The same nesting as `WideNode::intersect`, so the same bits.
            let t0 = max(near[0], max(near[1], max(near[2], 0.0)));
            let t1 = min(far[0], min(far[1], min(far[2], t_closest[lane]))) * ROBUST_EXIT_SCALE;
            entry[lane] = if t0 <= t1 && live[lane] {
                t0
            } else {
                f32::INFINITY
            };
        }
        entry
    }
}

/// Bit `lane` set where the ray entered a box (`entry[lane]` finite) no farther than its
/// closest hit so far: the rays for which a waiting box is still worth visiting, as the
/// single-ray traversal decides when it pops a box.
#[inline(always)]
fn reaching(entry: &Lanes, t_closest: &Lanes) -> u32 {
    let half = |h: usize| {
        let e = Vec4::from_slice(&entry[4 * h..4 * h + 4]);
        let t = Vec4::from_slice(&t_closest[4 * h..4 * h + 4]);
        (e.cmplt(Vec4::INFINITY) & e.cmple(t)).bitmask()
    };
    half(0) | half(1) << 4
}

/// Bit `lane` set where `entry[lane]` is finite: the rays that entered a box just tested.
#[inline(always)]
fn entered(entry: &Lanes) -> u32 {
    let half = |h: usize| {
        Vec4::from_slice(&entry[4 * h..4 * h + 4])
            .cmplt(Vec4::INFINITY)
            .bitmask()
    };
    half(0) | half(1) << 4
}

/// The smallest lane of `entry` (the packet's nearest entry, for ordering children).
#[inline(always)]
fn nearest(entry: &Lanes) -> f32 {
    // Halves first, then across one register (entries are never NaN, so `minps` here
    // picks what the scalar `min` would).
    let (a, b) = (Vec4::from_slice(&entry[..4]), Vec4::from_slice(&entry[4..]));
    a.min(b).min_element()
}

/// Closest hits of a packet; see [`super::Bvh::closest_hit_packet`]. `nodes` must be
/// non-empty.
#[inline(always)]
pub fn closest_hit<F: FnMut(usize, u32, u32, &Ray, f32) -> Option<(u32, f32)>>(
    nodes: &[WideNode],
    depth: usize,
    rays: &[Ray; PACKET],
    t_max: &Lanes,
    mut leaf: F,
) -> [Option<(u32, f32)>; PACKET] {
    let mut best: [Option<u32>; PACKET] = [None; PACKET];
    let t = closest_hit_masked(
        nodes,
        depth,
        rays,
        t_max,
        |first, count, active, t_closest| {
            let mut active = active;
            while active != 0 {
                let lane = active.trailing_zeros() as usize;
                active &= active - 1;
                let t = t_closest[lane];
                if let Some((id, hit)) =
                    leaf(lane, first, count, &rays[lane], t).filter(|h| h.1 < t)
                {
                    t_closest[lane] = hit;
                    best[lane] = Some(id);
                }
            }
        },
    );
    std::array::from_fn(|l| best[l].map(|id| (id, t[l])))
}

/// The traversal with a leaf test for the whole packet: `leaf(first, count, active,
/// t_closest)` tests the leaf at leaf-order positions `first .. first + count` for the
/// rays of lane mask `active` and lowers `t_closest[lane]` to each nearer hit, keeping
/// what it hit itself. Returns each lane's final t_closest (its t_max where nothing was
/// hit, −∞ for a lane that takes no part). `nodes` must be non-empty.
#[inline]
pub fn closest_hit_masked<F: FnMut(u32, u32, u32, &mut Lanes)>(
    nodes: &[WideNode],
    depth: usize,
    rays: &[Ray; PACKET],
    t_max: &Lanes,
    leaf: F,
) -> Lanes {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, checked just above.
        return unsafe { closest_hit_avx2(nodes, depth, rays, t_max, leaf) };
    }
    closest_hit_lanes(nodes, depth, rays, t_max, leaf)
}

/// [`closest_hit_lanes`] compiled for AVX2: the eight lanes are one 256-bit register.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn closest_hit_avx2<F: FnMut(u32, u32, u32, &mut Lanes)>(
    nodes: &[WideNode],
    depth: usize,
    rays: &[Ray; PACKET],
    t_max: &Lanes,
    leaf: F,
) -> Lanes {
    closest_hit_lanes(nodes, depth, rays, t_max, leaf)
}

/// The traversal itself, written over eight-lane arrays for the compiler to vectorise.
/// Returns each lane's closest distance (its t_max where nothing was hit, −∞ for a lane
/// that takes no part).
#[inline(always)]
fn closest_hit_lanes<F: FnMut(u32, u32, u32, &mut Lanes)>(
    nodes: &[WideNode],
    depth: usize,
    rays: &[Ray; PACKET],
    t_max: &Lanes,
    leaf: F,
) -> Lanes {
    let valid: [bool; PACKET] =
        std::array::from_fn(|l| rays[l].o.is_finite() && rays[l].d.is_finite() && t_max[l] > 0.0);
    if !valid.contains(&true) {
        return std::array::from_fn(|_| f32::NEG_INFINITY);
    }
    let data = PacketData::new(rays, &valid);
    if data.uniform.is_some() {
        walk::<true, F>(nodes, depth, &data, &valid, t_max, leaf)
    } else {
        walk::<false, F>(nodes, depth, &data, &valid, t_max, leaf)
    }
}

/// The walk of [`closest_hit_lanes`], with the slab test of [`PacketData::entry`].
#[inline(always)]
fn walk<const UNIFORM: bool, F: FnMut(u32, u32, u32, &mut Lanes)>(
    nodes: &[WideNode],
    depth: usize,
    data: &PacketData,
    valid: &[bool; PACKET],
    t_max: &Lanes,
    mut leaf: F,
) -> Lanes {
    // A lane takes part when its ray is finite and its interval (0, t_max) is not empty;
    // the others keep t_closest = −∞, which no box entry (≥ 0) reaches.
    let mut t_closest: Lanes = std::array::from_fn(|l| {
        if valid[l] {
            t_max[l]
        } else {
            f32::NEG_INFINITY
        }
    });
    let needed = (WIDTH - 1) * depth + 1;
    let mut fixed = [MaybeUninit::<Entry>::uninit(); STACK_SIZE];
    let mut heap = Vec::new();
    let slots: &mut [MaybeUninit<Entry>] = if needed <= STACK_SIZE {
        &mut fixed
    } else {
        heap.resize(needed, MaybeUninit::uninit());
        &mut heap
    };
    // Invariant: slots[..len] are written.
    let mut len = 0;
    // The box being visited and the rays in it: those that entered it when it was tested
    // (visited at once, nearest of its node's children) or still reach it (taken from the
    // stack). Only they test its children or its leaf, as each ray alone would.
    let mut current = ChildRef::inner(0);
    let mut active = valid
        .iter()
        .enumerate()
        .fold(0u32, |m, (l, &v)| m | (v as u32) << l);
    loop {
        if current.is_leaf() {
            let (first, count) = current.leaf_range();
            leaf(first, count, active, &mut t_closest);
        } else {
            let node = &nodes[current.0 as usize];
            let live: [bool; PACKET] = std::array::from_fn(|l| active >> l & 1 != 0);
            // The children some ray enters, with their entries and the nearest of them.
            let mut hits: [(ChildRef, Lanes, f32); WIDTH] =
                [(ChildRef(0), [0.0; PACKET], 0.0); WIDTH];
            let mut n = 0;
            for c in 0..WIDTH {
                // An unused lane holds the empty box (lower bound +∞), which no ray enters.
                if node.planes[0][c] == f32::INFINITY {
                    continue;
                }
                let e = data.entry::<UNIFORM>(node, c, &t_closest, &live);
                let near = nearest(&e);
                if near < f32::INFINITY {
                    // Insertion by the packet's nearest entry, farthest first.
                    let mut at = n;
                    while at > 0 && hits[at - 1].2 < near {
                        hits[at] = hits[at - 1];
                        at -= 1;
                    }
                    hits[at] = (node.children[c], e, near);
                    n += 1;
                }
            }
            if n > 0 {
                // The farther children wait on the stack; the nearest is visited next.
                for &(child, e, _) in &hits[..n - 1] {
                    slots[len] = MaybeUninit::new((child, e));
                    len += 1;
                }
                (current, active) = (hits[n - 1].0, entered(&hits[n - 1].1));
                continue;
            }
        }
        // Pop the next entry some ray still reaches before its closest hit.
        loop {
            if len == 0 {
                return t_closest;
            }
            len -= 1;
            // SAFETY: slot `len` is below the old length, so it was written.
            let (child, e) = unsafe { slots[len].assume_init() };
            let reach = reaching(&e, &t_closest);
            if reach != 0 {
                (current, active) = (child, reach);
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests;
