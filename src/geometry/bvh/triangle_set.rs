//! A triangle mesh ready for ray queries: a [`Bvh`] built for leaf blocks, and the
//! triangles as (p0, e1, e2) in four-lane [`Triangle4`] blocks, one per leaf, so a leaf is
//! one read of consecutive memory and one SIMD Möller–Trumbore test.

use glam::Vec3;
use rayon::prelude::*;

use super::{BLOCK, Bvh, PACKET, huge_pages};
use crate::geometry::triangle::TriangleHit;
use crate::geometry::triangle4::Triangle4;
use crate::geometry::{Aabb, Ray};

/// Triangles in leaf blocks with their BVH. Queries return the triangle's index in the
/// `indices` given to [`TriangleSet::new`].
#[derive(Clone, Debug)]
pub struct TriangleSet {
    bvh: Bvh,
    /// One block per leaf, in leaf order: block k holds leaf-order positions 4k .. 4k + 4.
    blocks: Vec<Triangle4>,
    /// Number of triangles.
    len: usize,
}

impl TriangleSet {
    /// Builds the set from shared vertices and index triples. Triples that name a
    /// missing vertex become empty triangles that nothing hits.
    ///
    /// # Panics
    /// With more than 2²⁷ triangles (the leaf blocks' limit, see [`Bvh::build_blocks`]).
    pub fn new(positions: &[Vec3], indices: &[[u32; 3]]) -> TriangleSet {
        let corners = |t: &[u32; 3]| -> Option<[Vec3; 3]> {
            let vertex = |i: u32| positions.get(i as usize).copied();
            Some([vertex(t[0])?, vertex(t[1])?, vertex(t[2])?])
        };
        // Boxes and blocks are independent per triangle and per block: both in parallel
        // (on a 1M-triangle mesh they were a fifth of the build on one thread).
        let mut bounds: Vec<Aabb> = huge_pages::with_capacity(indices.len());
        bounds.par_extend(
            indices
                .par_iter()
                .map(|t| corners(t).map_or(Aabb::EMPTY, |c| Aabb::from_points(&c))),
        );
        let bvh = Bvh::build_blocks(&bounds);
        let blocks = Triangle4::blocks(bvh.primitive_order(), |_, i| {
            let edges = match corners(&indices[i as usize]) {
                Some([p0, p1, p2]) => [p0, p1 - p0, p2 - p0],
                None => [Vec3::ZERO; 3],
            };
            Some((i, edges))
        });
        TriangleSet {
            bvh,
            blocks,
            len: indices.len(),
        }
    }

    /// The closest triangle hit in (0, t_max) (Möller & Trumbore 1997, four triangles at
    /// a time): the triangle's original index and the hit (distance and barycentrics).
    #[inline]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<(u32, TriangleHit)> {
        let mut hit = None;
        let (id, _) = self
            .bvh
            .closest_hit_leaf(ray, t_max, |first, _, ray, t_closest| {
                let block = &self.blocks[first as usize / BLOCK];
                let h = block.closest_hit(ray, t_closest)?;
                hit = Some(h.hit);
                Some((block.ids[h.lane], h.hit.t))
            })?;
        Some((id, hit?))
    }

    /// [`TriangleSet::closest_hit`] for a packet of rays traced together (see
    /// [`Bvh::closest_hit_packet`]; lanes whose ray is not finite or whose t_max is not
    /// positive take no part).
    #[inline]
    pub fn closest_hit_packet(
        &self,
        rays: &[Ray; PACKET],
        t_max: &[f32; PACKET],
    ) -> [Option<(u32, TriangleHit)>; PACKET] {
        let mut hits = [None; PACKET];
        let found = self
            .bvh
            .closest_hit_packet(rays, t_max, |lane, first, _, ray, t_closest| {
                let block = &self.blocks[first as usize / BLOCK];
                let h = block.closest_hit(ray, t_closest)?;
                hits[lane] = Some(h.hit);
                Some((block.ids[h.lane], h.hit.t))
            });
        std::array::from_fn(|l| Some((found[l]?.0, hits[l]?)))
    }

    /// True when some triangle is hit in (0, t_max) (shadow rays).
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        self.bvh.any_hit_leaf(ray, t_max, |first, _, ray, t_max| {
            self.blocks[first as usize / BLOCK].any_hit(ray, t_max)
        })
    }

    /// The underlying BVH.
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// Bytes held per triangle: the tree (nodes and primitive order) and the triangle
    /// blocks (vertex, edges and ids, padding lanes included), over the triangle count.
    pub fn bytes_per_triangle(&self) -> f64 {
        (self.bvh.memory_bytes() + std::mem::size_of_val(self.blocks.as_slice())) as f64
            / self.len.max(1) as f64
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the set holds no triangles.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_original_indices_and_ignores_bad_triples() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.0, 0.0, 1.0)];
        let shifted: Vec<Vec3> = positions.iter().map(|p| *p + Vec3::Z).collect();
        let all: Vec<Vec3> = positions.iter().chain(&shifted).copied().collect();
        let set = TriangleSet::new(&all, &[[0, 1, 99], [4, 5, 6], [0, 1, 2]]);
        let down = Ray::new(Vec3::new(0.2, 0.2, 5.0), -Vec3::Z);
        let (index, hit) = set.closest_hit(&down, f32::INFINITY).expect("hit");
        assert_eq!(index, 1);
        assert!((hit.t - 4.0).abs() < 1e-5);
        assert!(set.any_hit(&down, 4.5) && !set.any_hit(&down, 3.9));
        let up = Ray::new(Vec3::new(0.2, 0.2, 0.5), Vec3::Z);
        assert_eq!(set.closest_hit(&up, f32::INFINITY).map(|h| h.0), Some(1));
        assert!(
            TriangleSet::new(&all, &[])
                .closest_hit(&down, 1e9)
                .is_none()
        );
    }

    #[test]
    fn blocks_find_the_brute_force_closest_hit() {
        use crate::geometry::triangle::intersect_triangle;
        use crate::sampling::Rng32;
        let mut rng = Rng32::new(41);
        let mut point =
            |scale: f32| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * scale;
        // A grid of shared vertices (rays meet shared edges) and random triangles over it.
        let positions: Vec<Vec3> = (0..400).map(|_| point(10.0)).collect();
        let mut indices: Vec<[u32; 3]> = (0..3000u32)
            .map(|i| [i % 400, (i * 7 + 1) % 400, (i * 13 + 5) % 400])
            .collect();
        indices.push([0, 1, 400]); // names a missing vertex
        let set = TriangleSet::new(&positions, &indices);
        let corners = |t: &[u32; 3]| t.map(|i| positions.get(i as usize).copied());
        let (mut hits, mut blocked) = (0, 0);
        for k in 0..3000 {
            let o = point(14.0) - Vec3::splat(2.0);
            let d = (point(10.0) - o).normalize();
            let ray = Ray::new(o, d);
            let t_max = if k % 2 == 0 { f32::INFINITY } else { 6.0 };
            let brute = indices
                .iter()
                .filter_map(|t| match corners(t) {
                    [Some(a), Some(b), Some(c)] => intersect_triangle(&ray, a, b - a, c - a, t_max),
                    _ => None,
                })
                .map(|h| h.t)
                .min_by(f32::total_cmp);
            let got = set.closest_hit(&ray, t_max);
            assert_eq!(got.map(|(_, h)| h.t), brute, "ray {k}");
            if let Some((index, hit)) = got {
                let [a, b, c] = corners(&indices[index as usize]).map(Option::unwrap);
                let again = intersect_triangle(&ray, a, b - a, c - a, t_max).expect("hit");
                assert_eq!((again.t, again.b1, again.b2), (hit.t, hit.b1, hit.b2));
                hits += 1;
            }
            assert_eq!(set.any_hit(&ray, t_max), brute.is_some());
            blocked += set.any_hit(&ray, t_max) as u32;
        }
        assert!(hits > 1000 && blocked == hits, "{hits} hits");
        assert!(set.bytes_per_triangle() > 36.0);
    }
}
