//! Bounding volume hierarchy. (Brute-force stand-in with the final API; replaced by the
//! wide binned-SAH BVH.)

use super::{Aabb, Ray};

/// Acceleration structure over primitives known by their boxes.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    bounds: Vec<Aabb>,
    order: Vec<u32>,
}

impl Bvh {
    /// Builds over primitives given by their bounding boxes.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        Bvh { bounds: bounds.to_vec(), order: (0..bounds.len() as u32).collect() }
    }

    /// Primitive indices in leaf order.
    pub fn primitive_order(&self) -> &[u32] {
        &self.order
    }

    /// Closest hit in (0, t_max).
    pub fn closest_hit<F: FnMut(u32, &Ray, f32) -> Option<f32>>(
        &self,
        ray: &Ray,
        t_max: f32,
        mut intersect: F,
    ) -> Option<(u32, f32)> {
        let mut best = None;
        let mut t_best = t_max;
        for i in 0..self.bounds.len() as u32 {
            if let Some(t) = intersect(i, ray, t_best) {
                t_best = t;
                best = Some((i, t));
            }
        }
        best
    }

    /// Any hit in (0, t_max).
    pub fn any_hit<F: FnMut(u32, &Ray, f32) -> bool>(&self, ray: &Ray, t_max: f32, mut occludes: F) -> bool {
        (0..self.bounds.len() as u32).any(|i| occludes(i, ray, t_max))
    }

    /// Box of everything.
    pub fn bounds(&self) -> Aabb {
        self.bounds.iter().fold(Aabb::EMPTY, |a, b| a.union(*b))
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        1
    }
}
