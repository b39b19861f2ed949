//! A triangle mesh ready for ray queries: a [`Bvh`] over the triangles and the triangles
//! themselves as (p0, e1, e2) in the tree's leaf order, so a leaf reads consecutive memory
//! and the Möller–Trumbore test needs no edge subtraction.

use glam::Vec3;

use super::Bvh;
use crate::geometry::triangle::{TriangleHit, intersect_triangle};
use crate::geometry::{Aabb, Ray};

/// Triangles in BVH leaf order with their BVH. Queries return the triangle's index in
/// the `indices` given to [`TriangleSet::new`].
#[derive(Clone, Debug)]
pub struct TriangleSet {
    bvh: Bvh,
    /// (p0, p1 − p0, p2 − p0) per triangle, in leaf order.
    edges: Vec<[Vec3; 3]>,
}

impl TriangleSet {
    /// Builds the set from shared vertices and index triples. Triples that name a
    /// missing vertex become empty triangles that nothing hits.
    pub fn new(positions: &[Vec3], indices: &[[u32; 3]]) -> TriangleSet {
        let vertex = |i: u32| positions.get(i as usize).copied();
        let corners: Vec<Option<[Vec3; 3]>> = indices
            .iter()
            .map(|t| Some([vertex(t[0])?, vertex(t[1])?, vertex(t[2])?]))
            .collect();
        let bounds: Vec<Aabb> = corners
            .iter()
            .map(|c| c.map_or(Aabb::EMPTY, |c| Aabb::from_points(&c)))
            .collect();
        let bvh = Bvh::build(&bounds);
        let edges = bvh
            .primitive_order()
            .iter()
            .map(|&i| match corners[i as usize] {
                Some([p0, p1, p2]) => [p0, p1 - p0, p2 - p0],
                None => [Vec3::ZERO; 3],
            })
            .collect();
        TriangleSet { bvh, edges }
    }

    /// The closest triangle hit in (0, t_max) (Möller & Trumbore 1997): the triangle's
    /// original index and the hit (distance and barycentrics).
    #[inline]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<(u32, TriangleHit)> {
        let mut hit = None;
        let (prim, _) = self.bvh.closest_hit(ray, t_max, |prim, ray, t_closest| {
            let [p0, e1, e2] = self.edges[prim as usize];
            let h = intersect_triangle(ray, p0, e1, e2, t_closest)?;
            hit = Some(h);
            Some(h.t)
        })?;
        Some((self.bvh.primitive_order()[prim as usize], hit?))
    }

    /// True when some triangle is hit in (0, t_max) (shadow rays).
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        self.bvh.any_hit(ray, t_max, |prim, ray, t_max| {
            let [p0, e1, e2] = self.edges[prim as usize];
            intersect_triangle(ray, p0, e1, e2, t_max).is_some()
        })
    }

    /// The underlying BVH.
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// Bytes held per triangle: the tree (nodes and primitive order) and the triangles'
    /// vertex and edge vectors, over the triangle count.
    pub fn bytes_per_triangle(&self) -> f64 {
        let triangles = self.edges.len().max(1);
        (self.bvh.memory_bytes() + std::mem::size_of_val(self.edges.as_slice())) as f64
            / triangles as f64
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// True when the set holds no triangles.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
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
}
