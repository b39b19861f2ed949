//! Building the light BVH top-down with the surface area orientation heuristic (SAOH,
//! Conty Estevez & Kulla 2018, §4.2; pbrt-v4 `BVHLightSampler::buildBVH`): split where
//! Σ φ · M_Ω · K_r · area over both sides is least, one light per leaf.

use glam::Vec3;

use super::Node;
use crate::geometry::Aabb;
use crate::light::LightBounds;
use crate::math::PI;

/// Centroid buckets per axis.
const BUCKETS: usize = 12;

/// Below this depth the SAOH chooses splits; deeper ranges are halved by count, so the
/// depth stays under 64 (the selector's path buffer) for any light count up to 2³¹.
const SAOH_MAX_DEPTH: u32 = 32;

/// A light entering the build: its index in the scene, bounds and centroid.
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildLight {
    pub index: usize,
    pub bounds: LightBounds,
    pub centroid: Vec3,
}

/// Light counts from which the two halves of a split are built on two threads (each into
/// its own array, appended afterwards with its inner nodes' indices shifted): the tree is
/// the same node for node as the sequential build's.
const PARALLEL_MIN_LIGHTS: usize = 4096;

/// The binary tree under construction (collapsed into 4-wide nodes afterwards).
pub(super) struct Builder {
    pub nodes: Vec<Node>,
}

impl Builder {
    /// Builds the subtree of `lights` (non-empty), placing its root at the next node
    /// index and its first child right after it; returns the subtree's bounds.
    pub fn build(&mut self, lights: &mut [BuildLight], depth: u32) -> LightBounds {
        build_into(&mut self.nodes, lights, depth, PARALLEL_MIN_LIGHTS)
    }
}

/// [`Builder::build`] into `nodes`, splitting the work over threads from `parallel_min`
/// lights up.
fn build_into(
    nodes: &mut Vec<Node>,
    lights: &mut [BuildLight],
    depth: u32,
    parallel_min: usize,
) -> LightBounds {
    if lights.len() == 1 {
        let l = lights[0];
        nodes.push(Node {
            bounds: l.bounds,
            second_or_light: l.index as u32,
            leaf: true,
        });
        return l.bounds;
    }
    let parallel = lights.len() >= parallel_min;
    let mid = split(lights, depth);
    let at = nodes.len();
    nodes.push(Node {
        bounds: lights[0].bounds,
        second_or_light: 0,
        leaf: false,
    });
    let (left, right) = lights.split_at_mut(mid);
    let (a, second, b) = if parallel {
        let subtree = |part: &mut [BuildLight]| {
            let mut sub = Vec::with_capacity(2 * part.len());
            let bounds = build_into(&mut sub, part, depth + 1, parallel_min);
            (sub, bounds)
        };
        let ((first_nodes, a), (second_nodes, b)) =
            rayon::join(|| subtree(left), || subtree(right));
        append_shifted(nodes, first_nodes);
        let second = nodes.len() as u32;
        append_shifted(nodes, second_nodes);
        (a, second, b)
    } else {
        let a = build_into(nodes, left, depth + 1, parallel_min);
        let second = nodes.len() as u32;
        let b = build_into(nodes, right, depth + 1, parallel_min);
        (a, second, b)
    };
    nodes[at].bounds = a.union(&b);
    nodes[at].second_or_light = second;
    nodes[at].bounds
}

/// Appends a subtree built in its own array: its inner nodes name their second child by
/// index in that array, so they move by where it starts now.
fn append_shifted(nodes: &mut Vec<Node>, subtree: Vec<Node>) {
    let offset = nodes.len() as u32;
    nodes.extend(subtree.into_iter().map(|mut n| {
        if !n.leaf {
            n.second_or_light += offset;
        }
        n
    }));
}

/// Partitions `lights` (≥ 2) and returns the index where the second part starts
/// (strictly inside the slice).
fn split(lights: &mut [BuildLight], depth: u32) -> usize {
    let half = lights.len() / 2;
    if depth >= SAOH_MAX_DEPTH {
        return half;
    }
    let bounds = lights
        .iter()
        .fold(Aabb::EMPTY, |b, l| b.union(l.bounds.aabb));
    let centroids = lights.iter().fold(Aabb::EMPTY, |b, l| b.grow(l.centroid));
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, first bucket above)
    for axis in 0..3 {
        let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
        if hi <= lo {
            continue;
        }
        let mut buckets = [None::<LightBounds>; BUCKETS];
        let mut counts = [0usize; BUCKETS];
        for l in lights.iter() {
            let b = bucket(l.centroid[axis], lo, hi);
            counts[b] += 1;
            buckets[b] = Some(match buckets[b] {
                Some(x) => x.union(&l.bounds),
                None => l.bounds,
            });
        }
        // The bounds below and above every candidate split by one sweep each way, not
        // by merging the buckets again for each of the BUCKETS − 1 candidates (that was
        // O(BUCKETS²) unions per node, most of the build on 10⁵ lights).
        let mut below = [None::<LightBounds>; BUCKETS + 1];
        let mut above = [None::<LightBounds>; BUCKETS + 1];
        for k in 0..BUCKETS {
            below[k + 1] = union(below[k], buckets[k]);
            above[BUCKETS - 1 - k] = union(buckets[BUCKETS - 1 - k], above[BUCKETS - k]);
        }
        let total: usize = counts.iter().sum();
        let mut n_below = 0;
        for s in 1..BUCKETS {
            n_below += counts[s - 1];
            if n_below == 0 || n_below == total {
                continue;
            }
            let cost = below[s].map_or(0.0, |b| cost(&b, &bounds, axis))
                + above[s].map_or(0.0, |b| cost(&b, &bounds, axis));
            if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, s));
            }
        }
    }
    let Some((_, axis, s)) = best else {
        return half;
    };
    let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
    let mut mid = 0;
    for i in 0..lights.len() {
        if bucket(lights[i].centroid[axis], lo, hi) < s {
            lights.swap(i, mid);
            mid += 1;
        }
    }
    if mid == 0 || mid == lights.len() {
        half
    } else {
        mid
    }
}

/// Bucket of coordinate `x` in [lo, hi].
fn bucket(x: f32, lo: f32, hi: f32) -> usize {
    (((x - lo) / (hi - lo) * BUCKETS as f32) as usize).min(BUCKETS - 1)
}

/// The union of two optional clusters.
fn union(a: Option<LightBounds>, b: Option<LightBounds>) -> Option<LightBounds> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.union(&b)),
        (a, None) => a,
        (None, b) => b,
    }
}

/// SAOH cost of one side: φ · M_Ω · K_r · surface area, where M_Ω is the solid-angle
/// measure of the normal cone widened by the emission angle,
/// M_Ω = 2π(1 − cos θ_o) + π/2·(2θ_w sin θ_o − cos(θ_o − 2θ_w) − 2θ_o sin θ_o + cos θ_o)
/// with θ_w = min(θ_o + θ_e, π) (Conty Estevez & Kulla 2018, eq. 1), and K_r the
/// parent box's longest extent over its extent along the split axis (penalises thin
/// slices).
fn cost(b: &LightBounds, parent: &Aabb, axis: usize) -> f32 {
    let theta_o = b.cos_theta_o.clamp(-1.0, 1.0).acos();
    let theta_e = b.cos_theta_e.clamp(-1.0, 1.0).acos();
    let theta_w = (theta_o + theta_e).min(PI);
    let sin_o = theta_o.sin().max(0.0);
    let m_omega = 2.0 * PI * (1.0 - b.cos_theta_o)
        + 0.5
            * PI
            * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                + b.cos_theta_o);
    let extent = parent.extent();
    let k_r = if extent[axis] > 0.0 {
        extent.max_element() / extent[axis]
    } else {
        1.0
    };
    // A point light's box has no area: give it a tiny one so its power still counts.
    let area = b.aabb.surface_area().max(1e-12);
    b.phi * m_omega * k_r * area
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_parallel_build_is_the_sequential_tree_node_for_node() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let lights: Vec<BuildLight> = (0..3000)
            .map(|index| {
                let lo = Vec3::new(next(), next(), next()) * 20.0;
                let bounds = LightBounds {
                    aabb: Aabb {
                        min: lo,
                        max: lo + Vec3::new(next(), next(), next()) * 0.3,
                    },
                    phi: 0.1 + next() * 5.0,
                    w: Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize_or(Vec3::Y),
                    cos_theta_o: next(),
                    cos_theta_e: 0.0,
                    two_sided: index % 3 == 0,
                };
                BuildLight {
                    index,
                    bounds,
                    centroid: bounds.aabb.centroid(),
                }
            })
            .collect();
        let build = |parallel_min: usize| {
            let mut nodes = Vec::new();
            build_into(&mut nodes, &mut lights.clone(), 0, parallel_min);
            nodes
        };
        let (sequential, parallel) = (build(usize::MAX), build(64));
        assert_eq!(sequential.len(), 2 * lights.len() - 1);
        assert_eq!(sequential.len(), parallel.len());
        for (k, (s, p)) in sequential.iter().zip(&parallel).enumerate() {
            assert!(
                s.bounds == p.bounds && s.second_or_light == p.second_or_light && s.leaf == p.leaf,
                "node {k}: {s:?} vs {p:?}"
            );
        }
    }
}
