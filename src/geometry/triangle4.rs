//! Four triangles intersected at once: Möller–Trumbore (1997) in four SIMD lanes over a
//! structure-of-arrays block (Embree's `Triangle4` leaf layout; Wald et al. 2008 test a
//! wide BVH's leaves this way). glam's `Vec4` is SSE2 on x86-64 and NEON on aarch64, both
//! baseline, so no feature detection is needed.
//!
//! Each lane runs the operations of [`intersect_triangle`](super::triangle::intersect_triangle) in
//! the same order, so a lane's verdict, distance and barycentrics are bit for bit the
//! scalar test's (tested below); of several hits the nearest wins, the lowest lane on a
//! tie, as the scalar test run over the lanes in turn would decide.

use glam::{BVec4A, Vec3, Vec4};
use rayon::prelude::*;

use super::Ray;
use super::bvh::{PADDING, huge_pages};
use super::triangle::TriangleHit;

/// Lanes per block.
pub const LANES: usize = 4;

/// Up to four triangles, coordinates structure-of-arrays: `p0[axis]` holds vertex 0's
/// coordinate along `axis` for the four lanes, `e1`, `e2` the edges p1 − p0 and p2 − p0.
/// Unused lanes are all zero (a degenerate triangle nothing hits) with id [`NO_TRIANGLE`].
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct Triangle4 {
    p0: [Vec4; 3],
    e1: [Vec4; 3],
    e2: [Vec4; 3],
    /// The caller's index of each lane's triangle.
    pub ids: [u32; LANES],
}

/// The id of an unused lane.
pub const NO_TRIANGLE: u32 = u32::MAX;

/// A lane's hit: which lane, and where.
#[derive(Clone, Copy, Debug)]
pub struct LaneHit {
    /// The lane (0..4).
    pub lane: usize,
    /// Distance and barycentrics.
    pub hit: TriangleHit,
}

impl Triangle4 {
    /// The block of `triangles` (at most four, as (id, p0, e1, e2)); the other lanes unused.
    pub fn new(triangles: &[(u32, [Vec3; 3])]) -> Triangle4 {
        assert!(
            triangles.len() <= LANES,
            "a block holds at most four triangles"
        );
        let mut coords = [[[0.0f32; LANES]; 3]; 3];
        let mut ids = [NO_TRIANGLE; LANES];
        for (lane, (id, vectors)) in triangles.iter().enumerate() {
            ids[lane] = *id;
            for (k, v) in vectors.iter().enumerate() {
                for axis in 0..3 {
                    coords[k][axis][lane] = v[axis];
                }
            }
        }
        let soa = |k: usize| coords[k].map(Vec4::from_array);
        Triangle4 {
            p0: soa(0),
            e1: soa(1),
            e2: soa(2),
            ids,
        }
    }

    /// One block per [`LANES`] slots of a BVH's block-laid primitive order (see
    /// `Bvh::build_blocks`): `lane(position, index)` gives the (id, [p0, e1, e2]) of the
    /// primitive `index` at leaf-order `position`, or `None` for a slot that holds no
    /// triangle. Padding slots (`bvh::PADDING`) stay unused lanes. Blocks are built in
    /// parallel.
    pub fn blocks(
        order: &[u32],
        lane: impl Fn(usize, u32) -> Option<(u32, [Vec3; 3])> + Sync,
    ) -> Vec<Triangle4> {
        // Blocks are independent: built in parallel (a 1M-triangle mesh has 250k+).
        let mut blocks = huge_pages::with_capacity(order.len().div_ceil(LANES));
        blocks.par_extend(order.par_chunks(LANES).enumerate().map(|(k, slots)| {
            let mut lanes = [(NO_TRIANGLE, [Vec3::ZERO; 3]); LANES];
            for (l, &index) in slots.iter().enumerate() {
                if index != PADDING {
                    lanes[l] = lane(k * LANES + l, index).unwrap_or(lanes[l]);
                }
            }
            Triangle4::new(&lanes)
        }));
        blocks
    }

    /// The lanes hit in (0, t_max), as a mask, with their distances and barycentrics.
    #[inline(always)]
    fn hits(&self, ray: &Ray, t_max: f32) -> (BVec4A, Vec4, Vec4, Vec4) {
        let [dx, dy, dz] = ray.d.to_array().map(Vec4::splat);
        let [e1x, e1y, e1z] = self.e1;
        let [e2x, e2y, e2z] = self.e2;
        // p = d × e2, det = e1 · p (glam's Vec3 cross and dot, term by term).
        let px = dy * e2z - e2y * dz;
        let py = dz * e2x - e2z * dx;
        let pz = dx * e2y - e2x * dy;
        let det = e1x * px + e1y * py + e1z * pz;
        let inv_det = Vec4::ONE / det;
        // s = o − p0, b1 = (s · p) / det.
        let sx = Vec4::splat(ray.o.x) - self.p0[0];
        let sy = Vec4::splat(ray.o.y) - self.p0[1];
        let sz = Vec4::splat(ray.o.z) - self.p0[2];
        let b1 = (sx * px + sy * py + sz * pz) * inv_det;
        // q = s × e1, b2 = (d · q) / det, t = (e2 · q) / det.
        let qx = sy * e1z - e1y * sz;
        let qy = sz * e1x - e1z * sx;
        let qz = sx * e1y - e1x * sy;
        let b2 = (dx * qx + dy * qy + dz * qz) * inv_det;
        let t = (e2x * qx + e2y * qy + e2z * qz) * inv_det;
        let (zero, one) = (Vec4::ZERO, Vec4::ONE);
        // The scalar test's conditions as it writes them (`!(b2 < 0)` is not `b2 ≥ 0`
        // for a NaN).
        let valid = det.cmpne(zero)
            & det.is_finite_mask()
            & b1.cmpge(zero)
            & b1.cmple(one)
            & !b2.cmplt(zero)
            & !(b1 + b2).cmpgt(one)
            & t.cmpgt(zero)
            & t.cmplt(Vec4::splat(t_max));
        (valid, t, b1, b2)
    }

    /// The nearest hit in (0, t_max) among the lanes (the lowest lane on a tie).
    #[inline(always)]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<LaneHit> {
        let (valid, t, b1, b2) = self.hits(ray, t_max);
        let mask = valid.bitmask();
        if mask == 0 {
            return None;
        }
        let t = Vec4::select(valid, t, Vec4::INFINITY);
        let nearest = t.min_element();
        let lane = (t.cmpeq(Vec4::splat(nearest)).bitmask() & mask).trailing_zeros() as usize;
        Some(LaneHit {
            lane,
            hit: TriangleHit {
                t: t[lane],
                b1: b1[lane],
                b2: b2[lane],
            },
        })
    }

    /// True when some lane is hit in (0, t_max).
    #[inline(always)]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        self.hits(ray, t_max).0.any()
    }
}

#[cfg(test)]
mod tests {
    use super::super::triangle::intersect_triangle;
    use super::*;

    /// A xorshift stream of floats in [0, 1).
    fn stream(mut state: u64) -> impl FnMut() -> f32 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    #[test]
    fn every_lane_is_the_scalar_test_bit_for_bit() {
        let mut next = stream(0x9e37_79b9_7f4a_7c15);
        let mut next_u = stream(0x2545_f491_4f6c_dd1d);
        let mut point = || Vec3::new(next(), next(), next()) * 2.0 - Vec3::ONE;
        let (mut hits, mut checked) = (0, 0);
        for round in 0..20_000 {
            let count = 1 + round % LANES;
            let tris: Vec<(u32, [Vec3; 3])> = (0..count)
                .map(|k| {
                    let p0 = point();
                    // Some triangles share a plane or are degenerate, to test ties and det = 0.
                    let (e1, e2) = match round % 7 {
                        0 => (Vec3::X, Vec3::X * 2.0),
                        _ => (point(), point()),
                    };
                    (k as u32 + 10, [p0, e1, e2])
                })
                .collect();
            let block = Triangle4::new(&tris);
            // Aimed at a point of the plane of one of them, inside or near it.
            let (_, [p0, e1, e2]) = tris[round % count];
            let target = p0 + e1 * (next_u() * 0.9) + e2 * (next_u() * 0.9);
            let o = point() * 3.0;
            let ray = Ray::new(o, (target - o).normalize_or(Vec3::Z));
            let t_max = if round % 3 == 0 { 1.5 } else { f32::INFINITY };
            // The scalar test over the lanes in turn, keeping strictly nearer hits.
            let mut expected: Option<(usize, TriangleHit)> = None;
            for (lane, (_, [p0, e1, e2])) in tris.iter().enumerate() {
                let bound = expected.map_or(t_max, |e| e.1.t);
                if let Some(h) = intersect_triangle(&ray, *p0, *e1, *e2, bound) {
                    expected = Some((lane, h));
                }
            }
            let got = block.closest_hit(&ray, t_max);
            assert_eq!(got.is_some(), expected.is_some(), "round {round}");
            assert_eq!(block.any_hit(&ray, t_max), expected.is_some());
            if let (Some(g), Some((lane, h))) = (got, expected) {
                assert_eq!(g.lane, lane, "round {round}");
                assert_eq!(
                    [g.hit.t, g.hit.b1, g.hit.b2].map(f32::to_bits),
                    [h.t, h.b1, h.b2].map(f32::to_bits),
                    "round {round}"
                );
                assert_eq!(block.ids[lane], lane as u32 + 10);
                hits += 1;
            }
            checked += 1;
        }
        // Enough of both outcomes for the comparison to mean something.
        assert!(
            hits > checked / 20 && hits < checked - checked / 20,
            "{hits} of {checked}"
        );
    }

    #[test]
    fn ties_go_to_the_lowest_lane_and_unused_lanes_never_hit() {
        let tri = (
            0u32,
            [Vec3::new(-1.0, -1.0, 0.0), Vec3::X * 3.0, Vec3::Y * 3.0],
        );
        let block = Triangle4::new(&[(7, tri.1), (8, tri.1)]);
        let ray = Ray::new(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z);
        let hit = block.closest_hit(&ray, f32::INFINITY).expect("hit");
        assert_eq!((hit.lane, block.ids[hit.lane]), (0, 7));
        let empty = Triangle4::new(&[]);
        assert!(empty.closest_hit(&ray, f32::INFINITY).is_none() && !empty.any_hit(&ray, 1e30));
        assert_eq!(empty.ids, [NO_TRIANGLE; LANES]);
    }
}
