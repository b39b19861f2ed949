//! Where the light BVH splits a node: the surface area orientation heuristic (SAOH,
//! Conty Estevez & Kulla 2018, §4.2; pbrt-v4 `BVHLightSampler::buildBVH`) over centroid
//! buckets, the split where Σ φ · M_Ω · K_r · area over both sides is least.

use glam::{Vec3, Vec3A};

use super::build::BuildLight;
use crate::geometry::Aabb;
use crate::light::LightBounds;
use crate::math::PI;

/// Centroid buckets per axis.
const BUCKETS: usize = 12;

/// Below this depth the SAOH chooses splits; deeper ranges are halved by count, so the
/// depth stays under 64 (the selector's path buffer) for any light count up to 2³¹.
const SAOH_MAX_DEPTH: u32 = 32;

/// Partitions `lights` (≥ 2) and returns the index where the second part starts
/// (strictly inside the slice).
///
/// Every light is binned along the three axes in one pass, and candidate splits are
/// swept over occupied buckets only (see [`best_gap`]): this finds the split a sweep over
/// all `BUCKETS − 1` candidates of every axis finds, with at most min(n, BUCKETS) − 1
/// candidates per axis (most nodes of a large tree hold a handful of lights).
pub(super) fn split(lights: &mut [BuildLight], depth: u32) -> usize {
    let half = lights.len() / 2;
    if depth >= SAOH_MAX_DEPTH {
        return half;
    }
    let bounds = lights
        .iter()
        .fold(Aabb::EMPTY, |b, l| b.union(l.bounds.aabb));
    let centroids = lights.iter().fold(Aabb::EMPTY, |b, l| b.grow(l.centroid));
    let map = BucketMap::new(&centroids);
    let bins = Bins::of(lights, &map);
    let mut measure = ConeMeasure::default();
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, first bucket above)
    for &axis in map.axes() {
        best_gap(&bins, axis, &bounds, &mut measure, &mut best);
    }
    let Some((_, axis, s)) = best else {
        return half;
    };
    let mut mid = 0;
    for i in 0..lights.len() {
        if map.buckets(lights[i].centroid)[axis] < s {
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

/// Where centroids fall among a node's buckets: ⌊(c − lo)/(hi − lo) · BUCKETS⌋ per axis,
/// the three axes in SSE lanes (each lane the scalar operations). The binning and the
/// partition both use it, so they agree on every light.
struct BucketMap {
    lo: Vec3A,
    span: Vec3A,
    /// The axes along which the centroids spread (hi > lo), in order.
    axes: [usize; 3],
    axis_count: usize,
}

impl BucketMap {
    fn new(centroids: &Aabb) -> BucketMap {
        let (lo, hi) = (centroids.min, centroids.max);
        let mut axes = [0; 3];
        let mut axis_count = 0;
        for axis in 0..3 {
            if hi[axis] > lo[axis] {
                axes[axis_count] = axis;
                axis_count += 1;
            }
        }
        BucketMap {
            lo: lo.into(),
            span: (hi - lo).into(),
            axes,
            axis_count,
        }
    }

    fn axes(&self) -> &[usize] {
        &self.axes[..self.axis_count]
    }

    /// The buckets of centroid `c` (only meaningful along [`BucketMap::axes`]).
    #[inline]
    fn buckets(&self, c: Vec3) -> [usize; 3] {
        let t = (Vec3A::from(c) - self.lo) / self.span * BUCKETS as f32;
        // Along a spread axis t ∈ [0, BUCKETS] (lo ≤ c ≤ hi, rounding is monotone) or NaN
        // (hi − lo overflowed): `as i32` truncates the former and sends NaN to 0, as
        // `as usize` would, in fewer instructions.
        t.to_array().map(|x| (x as i32 as usize).min(BUCKETS - 1))
    }
}

/// The lights of a node binned along every spread axis: each bucket's merged bounds
/// (φ = 0 where empty, which [`LightBounds::union`] treats as no bounds) and count.
struct Bins {
    bounds: [[LightBounds; BUCKETS]; 3],
    counts: [[usize; BUCKETS]; 3],
}

impl Bins {
    fn of(lights: &[BuildLight], map: &BucketMap) -> Bins {
        let mut bins = Bins {
            bounds: [[LightBounds::EMPTY; BUCKETS]; 3],
            counts: [[0; BUCKETS]; 3],
        };
        for l in lights {
            let at = map.buckets(l.centroid);
            for &axis in map.axes() {
                let b = at[axis];
                bins.counts[axis][b] += 1;
                bins.bounds[axis][b] = bins.bounds[axis][b].union(&l.bounds);
            }
        }
        bins
    }
}

/// Updates `best` (cost, axis, first bucket above) with the SAOH's candidates along
/// `axis`. Only gaps between occupied buckets are candidates: every split inside one gap
/// has the same lights on each side, hence the same cost and the same partition, and a
/// sweep over all candidates would keep the first of them (strict `<`), which is the one
/// recorded here. The bounds below and above each gap come from one sweep each way.
fn best_gap(
    bins: &Bins,
    axis: usize,
    parent: &Aabb,
    measure: &mut ConeMeasure,
    best: &mut Option<(f32, usize, usize)>,
) {
    let mut occupied = [0usize; BUCKETS];
    let mut m = 0;
    for (k, &count) in bins.counts[axis].iter().enumerate() {
        if count > 0 {
            occupied[m] = k;
            m += 1;
        }
    }
    let bucket = |i: usize| &bins.bounds[axis][occupied[i]];
    let mut below = [LightBounds::EMPTY; BUCKETS + 1];
    let mut above = [LightBounds::EMPTY; BUCKETS + 1];
    for i in 0..m {
        below[i + 1] = below[i].union(bucket(i));
        let j = m - 1 - i;
        above[j] = bucket(j).union(&above[j + 1]);
    }
    // Gap i follows the i-th occupied bucket; its first candidate is that bucket + 1.
    for i in 1..m {
        let cost = cost(&below[i], parent, axis, measure) + cost(&above[i], parent, axis, measure);
        if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
            *best = Some((cost, axis, occupied[i - 1] + 1));
        }
    }
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
pub(super) mod tests {
    use super::*;

    /// `count` random lights in a box of side `side` (xorshift from `seed`): a third of
    /// them face every way (spheres), the rest one direction.
    pub(in crate::light::select::bvh) fn random_lights(
        count: usize,
        side: f32,
        seed: u64,
    ) -> Vec<BuildLight> {
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

    /// Bucket of coordinate `x` in [lo, hi], one axis at a time.
    fn bucket(x: f32, lo: f32, hi: f32) -> usize {
        (((x - lo) / (hi - lo) * BUCKETS as f32) as usize).min(BUCKETS - 1)
    }

    /// The SAOH split as the lecture would write it: every candidate of every axis, each
    /// side's bounds merged afresh (in the order the sweeps merge them), M_Ω computed each
    /// time, buckets one axis at a time; same partition rule.
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

    /// Runs `split` and the reference on copies of `lights`; both must give the same
    /// partition. Returns where the second part starts.
    fn check_split(lights: &[BuildLight]) -> usize {
        let (mut ours, mut reference) = (lights.to_vec(), lights.to_vec());
        let mid = split(&mut ours, 0);
        let n = lights.len();
        assert_eq!(mid, split_reference(&mut reference), "{n} lights");
        let order = |v: &[BuildLight]| v.iter().map(|l| l.index).collect::<Vec<_>>();
        assert_eq!(order(&ours), order(&reference), "{n} lights");
        mid
    }

    #[test]
    fn splits_match_the_sweep_over_every_candidate() {
        // Small clusters (most of a tree's nodes, and most buckets empty), clusters whose
        // centroids coincide along an axis, and large ones.
        for (k, count) in (2..40).chain([100, 1000]).enumerate() {
            for side in [0.5, 20.0] {
                let mut lights = random_lights(count, side, 0x9e37_79b9 + k as u64);
                if k % 4 == 0 {
                    for l in &mut lights {
                        l.centroid.y = 1.0;
                    }
                }
                check_split(&lights);
            }
        }
    }

    #[test]
    fn exact_ties_go_to_the_first_gap_and_infinite_costs_are_skipped() {
        // Three equal unit cubes at x = 0, 2, 4 facing every way: splitting after the
        // first or after the second costs exactly the same (the boxes' extents are exact),
        // and the first gap wins.
        let cube = |index: usize, x: f32| {
            let bounds = LightBounds {
                aabb: Aabb {
                    min: Vec3::new(x, 0.0, 0.0),
                    max: Vec3::new(x + 1.0, 1.0, 1.0),
                },
                phi: 1.0,
                w: Vec3::Z,
                cos_theta_o: -1.0,
                cos_theta_e: 0.0,
                two_sided: false,
            };
            BuildLight {
                index,
                bounds,
                centroid: bounds.aabb.centroid(),
            }
        };
        let row = [cube(0, 0.0), cube(1, 2.0), cube(2, 4.0)];
        assert_eq!(check_split(&row), 1);
        // A light whose φ makes every side that holds it cost ∞: no finite candidate, so
        // the count median.
        let mut huge = row.to_vec();
        huge.push(cube(3, 6.0));
        huge[1].bounds.phi = 3e38;
        assert_eq!(check_split(&huge), 2);
    }
}
