//! The 4-wide node and its slab test: four child boxes stored structure-of-arrays, so
//! the test of all four children is one loop over `[f32; 4]` lanes that the compiler
//! turns into SSE instructions (the layout of Wald et al. 2008, "Getting Rid of
//! Packets: Efficient SIMD Single-Ray Traversal using Multi-branching BVHs", and of
//! Embree's BVH4).

use glam::Vec3;

use crate::geometry::{Aabb, Ray};

/// Children per node.
pub const WIDTH: usize = 4;

/// Largest number of primitives in one leaf (the count is packed into two bits).
pub const MAX_LEAF_SIZE: usize = 4;

/// Bit set in a child reference that names a leaf.
const LEAF_BIT: u32 = 1 << 31;
/// Leaf references keep `count - 1` in bits 29..31 and the first primitive below.
const COUNT_SHIFT: u32 = 29;
/// Mask of the first primitive in a leaf reference.
const FIRST_MASK: u32 = (1 << COUNT_SHIFT) - 1;

/// Largest number of primitives a [`super::Bvh`] can hold (leaf references keep the
/// first primitive in 29 bits).
pub const MAX_PRIMITIVES: usize = 1 << COUNT_SHIFT;

/// A reference to a child: an inner node index, or a leaf (first primitive, count).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChildRef(pub u32);

impl ChildRef {
    /// The reference to inner node `index`.
    #[inline]
    pub fn inner(index: u32) -> ChildRef {
        ChildRef(index)
    }

    /// The reference to a leaf holding primitives `first .. first + count`
    /// (1 ≤ count ≤ [`MAX_LEAF_SIZE`], first < [`MAX_PRIMITIVES`]).
    #[inline]
    pub fn leaf(first: u32, count: u32) -> ChildRef {
        debug_assert!((1..=MAX_LEAF_SIZE as u32).contains(&count) && first <= FIRST_MASK);
        ChildRef(LEAF_BIT | ((count - 1) << COUNT_SHIFT) | first)
    }

    /// True when the reference names a leaf.
    #[inline]
    pub fn is_leaf(self) -> bool {
        self.0 & LEAF_BIT != 0
    }

    /// The primitive range of a leaf reference, as (first, count).
    #[inline]
    pub fn leaf_range(self) -> (u32, u32) {
        (self.0 & FIRST_MASK, ((self.0 >> COUNT_SHIFT) & 3) + 1)
    }
}

/// A 4-wide node: the boxes of up to four children, one `[f32; 4]` per bound and axis,
/// in the order min x, min y, min z, max x, max y, max z. Unused lanes hold the empty
/// box, which the slab test below never hits.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub struct WideNode {
    /// `planes[k][lane]`: k = 0..3 lower bounds along x, y, z; k = 3..6 upper bounds.
    pub planes: [[f32; WIDTH]; 6],
    /// The children; only lanes with a non-empty box are meaningful.
    pub children: [ChildRef; WIDTH],
}

impl WideNode {
    /// A node with every lane empty.
    pub fn empty() -> WideNode {
        let mut planes = [[f32::INFINITY; WIDTH]; 6];
        for bound in &mut planes[3..] {
            *bound = [f32::NEG_INFINITY; WIDTH];
        }
        WideNode {
            planes,
            children: [ChildRef(0); WIDTH],
        }
    }

    /// Stores child `lane`'s box and reference.
    pub fn set_child(&mut self, lane: usize, bounds: &Aabb, child: ChildRef) {
        for axis in 0..3 {
            self.planes[axis][lane] = bounds.min[axis];
            self.planes[axis + 3][lane] = bounds.max[axis];
        }
        self.children[lane] = child;
    }

    /// The box of child `lane` (the empty box where the lane is unused).
    pub fn child_bounds(&self, lane: usize) -> Aabb {
        let p = &self.planes;
        Aabb {
            min: Vec3::new(p[0][lane], p[1][lane], p[2][lane]),
            max: Vec3::new(p[3][lane], p[4][lane], p[5][lane]),
        }
    }

    /// Entry distances of the four lanes; a lane is hit when its entry is below
    /// `f32::INFINITY` (misses return +∞). A box counts as hit when the ray enters it
    /// in [0, t_max].
    #[inline(always)]
    pub fn intersect(&self, ray: &RayData, t_max: f32) -> [f32; WIDTH] {
        let near = [
            &self.planes[ray.near[0]],
            &self.planes[ray.near[1]],
            &self.planes[ray.near[2]],
        ];
        let far = [
            &self.planes[ray.far[0]],
            &self.planes[ray.far[1]],
            &self.planes[ray.far[2]],
        ];
        let mut entry = [0.0f32; WIDTH];
        for lane in 0..WIDTH {
            // Slab test: t = (plane − o) / d along each axis, nearer planes first.
            let tx0 = (near[0][lane] - ray.o.x) * ray.inv_d.x;
            let ty0 = (near[1][lane] - ray.o.y) * ray.inv_d.y;
            let tz0 = (near[2][lane] - ray.o.z) * ray.inv_d.z;
            let tx1 = (far[0][lane] - ray.o.x) * ray.inv_d.x;
            let ty1 = (far[1][lane] - ray.o.y) * ray.inv_d.y;
            let tz1 = (far[2][lane] - ray.o.z) * ray.inv_d.z;
            // A zero direction component gives 1/d = ±∞, and (plane − o)·∞ is NaN only for
            // a ray lying in that plane, which is inside the slab. `max`/`min` below drop a
            // NaN in their first argument, and the running value (seeded with 0 and t_max)
            // is always the second, so such a NaN simply leaves the interval unchanged.
            let t0 = max(tx0, max(ty0, max(tz0, 0.0)));
            // Ize 2013 ("Robust BVH Ray Traversal", eq. 9): widening the exit distance by
            // 1 + 2γ₃ makes the test conservative under float rounding.
            let t1 = min(tx1, min(ty1, min(tz1, t_max))) * ROBUST_EXIT_SCALE;
            entry[lane] = if t0 <= t1 { t0 } else { f32::INFINITY };
        }
        entry
    }
}

/// 1 + 2γ₃ with γₙ = nε/(1 − nε), ε = 2⁻²⁴ (Ize 2013; Pharr et al., pbrt-v4 §6.8).
pub(super) const ROBUST_EXIT_SCALE: f32 =
    1.0 + 2.0 * (3.0 * 5.960_464_5e-8 / (1.0 - 3.0 * 5.960_464_5e-8));

/// `a > b ? a : b`, written so it compiles to one `maxps` lane.
#[inline(always)]
pub(super) fn max(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// `a < b ? a : b`, written so it compiles to one `minps` lane.
#[inline(always)]
pub(super) fn min(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// What traversal precomputes per ray: origin, reciprocal direction, and for each axis the index of the nearer plane (0..3 for min, 3..6 for max).
#[derive(Clone, Copy, Debug)]
pub struct RayData {
    /// Ray origin.
    pub o: Vec3,
    /// 1/d; zero components give ±∞.
    pub inv_d: Vec3,
    /// Index into [`WideNode::planes`] of the plane the ray meets first, per axis.
    pub near: [usize; 3],
    /// Index of the plane the ray leaves through, per axis.
    pub far: [usize; 3],
}

impl RayData {
    /// The precomputed form of `ray`, or `None` when its origin or direction is not finite
    /// (such a ray hits nothing: with a NaN the slab test could not reject empty lanes).
    #[inline]
    pub fn new(ray: &Ray) -> Option<RayData> {
        if !(ray.o.is_finite() && ray.d.is_finite()) {
            return None;
        }
        let inv_d = ray.d.recip();
        // The sign of 1/d (not of d) picks the near plane, so −0 is handled like any
        // negative component.
        let near = |axis: usize| if inv_d[axis] < 0.0 { axis + 3 } else { axis };
        let far = |axis: usize| (near(axis) + 3) % 6;
        Some(RayData {
            o: ray.o,
            inv_d,
            near: [near(0), near(1), near(2)],
            far: [far(0), far(1), far(2)],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node_with(boxes: &[Aabb]) -> WideNode {
        let mut node = WideNode::empty();
        for (lane, b) in boxes.iter().enumerate() {
            node.set_child(lane, b, ChildRef::inner(lane as u32));
        }
        node
    }

    #[test]
    fn leaf_references_round_trip() {
        for (first, count) in [(0, 1), (7, 4), (MAX_PRIMITIVES as u32 - 1, 3)] {
            let r = ChildRef::leaf(first, count);
            assert!(r.is_leaf() && r.leaf_range() == (first, count));
        }
        assert!(!ChildRef::inner(5).is_leaf());
    }

    #[test]
    fn slab_test_hits_misses_and_skips_empty_lanes() {
        let unit = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        let flat = Aabb {
            min: Vec3::new(0.0, 0.0, 2.0),
            max: Vec3::new(1.0, 1.0, 2.0),
        };
        let node = node_with(&[unit, flat]);
        let cases = [
            // (origin, direction, expected hit lanes)
            (
                Vec3::new(0.5, 0.5, -1.0),
                Vec3::Z,
                [true, true, false, false],
            ),
            (
                Vec3::new(0.5, 0.5, 3.0),
                -Vec3::Z,
                [true, true, false, false],
            ),
            (
                Vec3::new(0.5, 0.5, 0.5),
                Vec3::X,
                [true, false, false, false],
            ),
            (
                Vec3::new(2.0, 0.5, 0.5),
                Vec3::X,
                [false, false, false, false],
            ),
            // Axis-parallel ray lying in the flat box's plane and along a box face.
            (
                Vec3::new(-1.0, 0.5, 2.0),
                Vec3::X,
                [false, true, false, false],
            ),
            (
                Vec3::new(-1.0, 0.0, 0.0),
                Vec3::X,
                [true, false, false, false],
            ),
            (
                Vec3::new(-1.0, 0.0, -0.0),
                Vec3::new(1.0, -0.0, 0.0),
                [true, false, false, false],
            ),
        ];
        for (o, d, expected) in cases {
            let entry = node.intersect(
                &RayData::new(&Ray::new(o, d)).expect("finite"),
                f32::INFINITY,
            );
            let hits = entry.map(|t| t < f32::INFINITY);
            assert_eq!(hits, expected, "ray {o} {d}: {entry:?}");
            assert!(entry.iter().all(|t| !t.is_nan()));
        }
    }

    #[test]
    fn t_max_bounds_the_test() {
        let node = node_with(&[Aabb {
            min: Vec3::splat(2.0),
            max: Vec3::splat(3.0),
        }]);
        let ray =
            RayData::new(&Ray::new(Vec3::splat(2.5) - Vec3::X * 2.5, Vec3::X)).expect("finite");
        assert!(node.intersect(&ray, 1.0)[0] == f32::INFINITY);
        assert!((node.intersect(&ray, 10.0)[0] - 2.0).abs() < 1e-6);
    }
}
