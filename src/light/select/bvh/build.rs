//! Building the light BVH top-down with the surface area orientation heuristic (SAOH,
//! Conty Estevez & Kulla 2018, §4.2; pbrt-v4 `BVHLightSampler::buildBVH`): split where
//! Σ φ · M_Ω · K_r · area over both sides is least, one light per leaf.

use glam::{Vec3, Vec3A};

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

/// Light counts from which the two halves of a split are built on two threads: the
/// tree is the same node for node as the sequential build's.
const PARALLEL_MIN_LIGHTS: usize = 4096;

/// Builds the binary tree over `lights` (non-empty): 2n − 1 nodes, root first, each inner
/// node's first child right after it.
pub(super) fn build(lights: &mut [BuildLight]) -> Vec<Node> {
    let mut nodes = vec![Node::PLACEHOLDER; 2 * lights.len() - 1];
    build_into(&mut nodes, 0, lights, 0, PARALLEL_MIN_LIGHTS);
    nodes
}

/// Builds the subtree of `lights` into `nodes`, which has exactly its 2n − 1 slots and
/// starts at index `base` of the whole array; the halves of a split of at least
/// `parallel_min` lights are built on two threads. A subtree's size follows from its
/// light count, so each half's slots are known before it is built: no copies.
/// Returns the subtree's bounds.
fn build_into(
    nodes: &mut [Node],
    base: u32,
    lights: &mut [BuildLight],
    depth: u32,
    parallel_min: usize,
) -> LightBounds {
    debug_assert_eq!(nodes.len(), 2 * lights.len() - 1);
    if lights.len() == 1 {
        let l = lights[0];
        nodes[0] = Node {
            bounds: l.bounds,
            second_or_light: l.index as u32,
            leaf: true,
        };
        return l.bounds;
    }
    let parallel = lights.len() >= parallel_min;
    let mid = split(lights, depth);
    let (root, children) = nodes.split_first_mut().expect("a split node has children");
    let (first_nodes, second_nodes) = children.split_at_mut(2 * mid - 1);
    let (left, right) = lights.split_at_mut(mid);
    let second = base + 2 * mid as u32;
    let (a, b) = if parallel {
        rayon::join(
            || build_into(first_nodes, base + 1, left, depth + 1, parallel_min),
            || build_into(second_nodes, second, right, depth + 1, parallel_min),
        )
    } else {
        (
            build_into(first_nodes, base + 1, left, depth + 1, parallel_min),
            build_into(second_nodes, second, right, depth + 1, parallel_min),
        )
    };
    let bounds = a.union(&b);
    *root = Node {
        bounds,
        second_or_light: second,
        leaf: false,
    };
    bounds
}

/// Partitions `lights` (≥ 2) and returns the index where the second part starts
/// (strictly inside the slice).
///
/// Every light is binned along the three axes in one pass, and candidate splits are
/// swept over occupied buckets only: between two occupied buckets every candidate has the
/// same lights below and above it, hence the same cost, and the strict `<` keeps the first
/// of them. So this finds the split a sweep over all `BUCKETS − 1` candidates finds, with
/// at most min(n, BUCKETS) − 1 cost evaluations per axis (most nodes of a large tree hold
/// a handful of lights).
fn split(lights: &mut [BuildLight], depth: u32) -> usize {
    let half = lights.len() / 2;
    if depth >= SAOH_MAX_DEPTH {
        return half;
    }
    let bounds = lights
        .iter()
        .fold(Aabb::EMPTY, |b, l| b.union(l.bounds.aabb));
    let centroids = lights.iter().fold(Aabb::EMPTY, |b, l| b.grow(l.centroid));
    let (lo, hi) = (centroids.min, centroids.max);
    let mut axes = [0usize; 3];
    let mut n_axes = 0;
    for axis in 0..3 {
        if hi[axis] > lo[axis] {
            axes[n_axes] = axis;
            n_axes += 1;
        }
    }
    let axes = &axes[..n_axes];
    let mut buckets = [[LightBounds::EMPTY; BUCKETS]; 3];
    let mut counts = [[0usize; BUCKETS]; 3];
    let (lo3, span3) = (Vec3A::from(lo), Vec3A::from(hi - lo));
    for l in lights.iter() {
        // The three axes' positions in one SIMD pass: `bucket`'s operations, lane by lane.
        let t = ((Vec3A::from(l.centroid) - lo3) / span3 * BUCKETS as f32).to_array();
        for &axis in axes {
            // t ∈ [0, BUCKETS]: truncating through i32 is `as usize` there, and cheaper.
            let b = (t[axis] as i32 as usize).min(BUCKETS - 1);
            counts[axis][b] += 1;
            // An empty bucket has φ = 0, which `union` treats as no bounds at all.
            buckets[axis][b] = buckets[axis][b].union(&l.bounds);
        }
    }
    let mut measure = ConeMeasure::default();
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, first bucket above)
    for &axis in axes {
        let mut occupied = [0usize; BUCKETS];
        let mut m = 0;
        for (k, &count) in counts[axis].iter().enumerate() {
            if count > 0 {
                occupied[m] = k;
                m += 1;
            }
        }
        // The bounds below and above every gap between occupied buckets, by one sweep
        // each way (O(BUCKETS) unions per node, not O(BUCKETS²)).
        let mut below = [LightBounds::EMPTY; BUCKETS + 1];
        let mut above = [LightBounds::EMPTY; BUCKETS + 1];
        for i in 0..m {
            below[i + 1] = below[i].union(&buckets[axis][occupied[i]]);
            let j = m - 1 - i;
            above[j] = buckets[axis][occupied[j]].union(&above[j + 1]);
        }
        // Gap i follows the i-th occupied bucket; its first candidate is that bucket + 1.
        for i in 1..m {
            let cost = cost(&below[i], &bounds, axis, &mut measure)
                + cost(&above[i], &bounds, axis, &mut measure);
            if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, occupied[i - 1] + 1));
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

/// SAOH cost of one side: φ · M_Ω · K_r · surface area, with M_Ω from [`ConeMeasure`]
/// and K_r the parent box's longest extent over its extent along the split axis
/// (penalises thin slices).
fn cost(b: &LightBounds, parent: &Aabb, axis: usize, measure: &mut ConeMeasure) -> f32 {
    let m_omega = measure.get(b.cos_theta_o, b.cos_theta_e);
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

/// The solid-angle measure of a normal cone widened by the emission angle,
/// M_Ω = 2π(1 − cos θ_o) + π/2·(2θ_w sin θ_o − cos(θ_o − 2θ_w) − 2θ_o sin θ_o + cos θ_o)
/// with θ_w = min(θ_o + θ_e, π) (Conty Estevez & Kulla 2018, eq. 1), remembering the last
/// cone it measured: a split's candidates mostly share one (in a large tree, the whole
/// sphere), and each measure costs two `acos`, a `sin` and a `cos`.
#[derive(Default)]
struct ConeMeasure {
    last: Option<((u32, u32), f32)>,
}

impl ConeMeasure {
    fn get(&mut self, cos_theta_o: f32, cos_theta_e: f32) -> f32 {
        let key = (cos_theta_o.to_bits(), cos_theta_e.to_bits());
        match self.last {
            Some((k, m)) if k == key => m,
            _ => {
                let m = cone_measure(cos_theta_o, cos_theta_e);
                self.last = Some((key, m));
                m
            }
        }
    }
}

/// M_Ω of [`ConeMeasure`], computed.
fn cone_measure(cos_theta_o: f32, cos_theta_e: f32) -> f32 {
    let theta_o = cos_theta_o.clamp(-1.0, 1.0).acos();
    let theta_e = cos_theta_e.clamp(-1.0, 1.0).acos();
    let theta_w = (theta_o + theta_e).min(PI);
    let sin_o = theta_o.sin().max(0.0);
    2.0 * PI * (1.0 - cos_theta_o)
        + 0.5
            * PI
            * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                + cos_theta_o)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `count` random lights in a box of side `side` (xorshift from `seed`): a third of
    /// them face every way (spheres), the rest one direction.
    fn random_lights(count: usize, side: f32, seed: u64) -> Vec<BuildLight> {
        let mut state = seed;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..count)
            .map(|index| {
                let lo = Vec3::new(next(), next(), next()) * side;
                let bounds = LightBounds {
                    aabb: Aabb {
                        min: lo,
                        max: lo + Vec3::new(next(), next(), next()) * 0.3,
                    },
                    phi: 0.1 + next() * 5.0,
                    w: Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize_or(Vec3::Y),
                    cos_theta_o: if index % 3 == 1 { -1.0 } else { next() },
                    cos_theta_e: 0.0,
                    two_sided: index % 3 == 0,
                };
                BuildLight {
                    index,
                    bounds,
                    centroid: bounds.aabb.centroid(),
                }
            })
            .collect()
    }

    /// The SAOH split as the lecture would write it: every candidate of every axis, each
    /// side's bounds merged afresh (in the order the sweeps merge them), M_Ω computed each
    /// time; same partition rule.
    fn split_reference(lights: &mut [BuildLight]) -> usize {
        let bounds = lights
            .iter()
            .fold(Aabb::EMPTY, |b, l| b.union(l.bounds.aabb));
        let centroids = lights.iter().fold(Aabb::EMPTY, |b, l| b.grow(l.centroid));
        let mut best: Option<(f32, usize, usize)> = None;
        for axis in 0..3 {
            let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
            if hi <= lo {
                continue;
            }
            let mut buckets = [LightBounds::EMPTY; BUCKETS];
            for l in lights.iter() {
                let b = bucket(l.centroid[axis], lo, hi);
                buckets[b] = buckets[b].union(&l.bounds);
            }
            for s in 1..BUCKETS {
                let below = buckets[..s]
                    .iter()
                    .fold(LightBounds::EMPTY, |acc, b| acc.union(b));
                let above = buckets[s..]
                    .iter()
                    .rev()
                    .fold(LightBounds::EMPTY, |acc, b| b.union(&acc));
                if below.phi == 0.0 || above.phi == 0.0 {
                    continue;
                }
                let side = |b: &LightBounds| {
                    let extent = bounds.extent();
                    let k_r = extent.max_element() / extent[axis];
                    let m = cone_measure(b.cos_theta_o, b.cos_theta_e);
                    b.phi * m * k_r * b.aabb.surface_area().max(1e-12)
                };
                let cost = side(&below) + side(&above);
                if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, s));
                }
            }
        }
        let Some((_, axis, s)) = best else {
            return lights.len() / 2;
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
            lights.len() / 2
        } else {
            mid
        }
    }

    #[test]
    fn splits_match_the_sweep_over_every_candidate() {
        // Small clusters (most of a tree's nodes, and most buckets empty), clusters whose
        // centroids coincide along some axes, and large ones.
        let mut differing_axes = 0;
        for (k, count) in (2..40).chain([100, 1000]).enumerate() {
            for side in [0.5, 20.0] {
                let mut lights = random_lights(count, side, 0x9e37_79b9 + k as u64);
                if k % 4 == 0 {
                    for l in &mut lights {
                        l.centroid.y = 1.0;
                    }
                    differing_axes += 1;
                }
                let mut reference = lights.clone();
                let mid = split(&mut lights, 0);
                assert_eq!(mid, split_reference(&mut reference), "{count} lights");
                let order = |v: &[BuildLight]| v.iter().map(|l| l.index).collect::<Vec<_>>();
                assert_eq!(order(&lights), order(&reference), "{count} lights");
            }
        }
        assert!(differing_axes > 0);
    }

    #[test]
    fn the_parallel_build_is_the_sequential_tree_node_for_node() {
        let lights = random_lights(3000, 20.0, 0x2545_f491_4f6c_dd1d);
        let build = |parallel_min: usize| {
            let mut nodes = vec![Node::PLACEHOLDER; 2 * lights.len() - 1];
            build_into(&mut nodes, 0, &mut lights.clone(), 0, parallel_min);
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
