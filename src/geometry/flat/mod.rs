//! Scenes of a few primitives tested without a tree: every shape of the scene in SIMD
//! blocks of four by kind (triangles as [`Triangle4`], spheres, rectangles and disks as
//! [`Sphere4`], [`Rect4`], [`Disk4`]), each block one branch-free test of the ray against
//! its four shapes.
//!
//! Where a scene's primitives fill at most [`FLAT_BLOCKS`] blocks (most conformance
//! scenes, the README's), this is cheaper than walking its BVH: the tree's root already
//! tests four boxes, and a ray through a floor, a wall and a few spheres then visits most
//! leaves, one shape at a time, with the traversal's stack and branches on top. On
//! `builtin:assignment` (seven primitives) a camera ray took about 580 instructions in
//! packets through its tree (680 alone); its two blocks take about 150.
//!
//! The answers are the tree's: every lane computes the scalar test's distance bit for
//! bit, the closest hit is the nearest (the first in block order on an exact tie, or
//! between hits within rounding of a box's entry face, where the tree's visiting order
//! decides instead), and a shadow ray is blocked when some shape reports a hit, as in
//! the tree's any-hit query.

mod blocks;

use glam::{Vec2, Vec4};

pub use blocks::{Disk4, Hits4, Rect4, ShapeBlock, Sphere4};

use super::Ray;
use super::scene_geometry::Primitive;
use super::shape::{Shape, ShapeHit};
use super::triangle4::Triangle4;

/// Most blocks a scene's primitives may fill for its queries to skip the BVH: the
/// tree's root alone tests four boxes, about the cost of one block. With three blocks,
/// the README's scene (a rectangle block and a sphere block), `cbox_diffuse.xml` and
/// `envmap_rotated.xml` took 4–7 % fewer instructions; `tent_point.xml` (four blocks:
/// twelve triangles of a cube and a floor) took 3.5 % more flat than through its tree
/// (BENCHMARKS.md, session 27).
pub const FLAT_BLOCKS: usize = 3;

/// Most primitives a flat scene can have ([`FLAT_BLOCKS`] full blocks).
pub const FLAT_MAX: usize = FLAT_BLOCKS * blocks::LANES;

/// A block of four shapes of one kind and the primitive index of each lane.
#[derive(Clone, Copy, Debug)]
struct Block<S> {
    shapes: S,
    prims: [u32; blocks::LANES],
}

/// Every primitive of a small scene, in blocks by kind.
#[derive(Clone, Debug)]
pub struct FlatShapes {
    triangles: Vec<Triangle4>,
    rects: Vec<Block<Rect4>>,
    spheres: Vec<Block<Sphere4>>,
    disks: Vec<Block<Disk4>>,
}

/// The shapes of kind `S` among `prims` (index, primitive), in blocks of four.
fn blocks_of<S: ShapeBlock>(prims: &[(u32, Primitive)]) -> Vec<Block<S>> {
    let items: Vec<(u32, S::Shape)> = prims
        .iter()
        .filter_map(|(i, p)| Some((*i, S::pick(&p.shape)?)))
        .collect();
    items
        .chunks(blocks::LANES)
        .map(|chunk| {
            let shapes: Vec<S::Shape> = chunk.iter().map(|&(_, s)| s).collect();
            Block {
                shapes: S::new(&shapes),
                prims: std::array::from_fn(|l| chunk.get(l).map_or(u32::MAX, |c| c.0)),
            }
        })
        .collect()
}

/// The closest distance so far and what was hit there.
type Best = (f32, Option<(u32, ShapeHit)>);

/// `best`, brought nearer by the closest hit of `ray` among `blocks`.
#[inline(always)]
fn closest_in<S: ShapeBlock>(blocks: &[Block<S>], ray: &Ray, best: &mut Best) {
    for b in blocks {
        if let Some((lane, hit)) = nearest(&b.shapes.hits(ray, best.0), best.0) {
            *best = (hit.t, Some((b.prims[lane], hit)));
        }
    }
}

/// Whether some shape of `blocks` blocks `ray` in (0, t_max).
#[inline(always)]
fn any_in<S: ShapeBlock>(blocks: &[Block<S>], ray: &Ray, t_max: f32) -> bool {
    blocks.iter().any(|b| b.shapes.hits(ray, t_max).some.any())
}

/// The nearest lane of `h` hit below `best` (the lowest lane on a tie), with its hit.
#[inline(always)]
fn nearest(h: &Hits4, best: f32) -> Option<(usize, ShapeHit)> {
    // A hit at a NaN distance is a hit only to an any-hit query (as in the tree).
    let mask = h.some & h.t.cmplt(Vec4::splat(best));
    if !mask.any() {
        return None;
    }
    let t = Vec4::select(mask, h.t, Vec4::INFINITY);
    let m = t.min_element();
    let lane = (t.cmpeq(Vec4::splat(m)).bitmask() & mask.bitmask()).trailing_zeros() as usize;
    let uv = Vec2::new(h.u[lane], h.v[lane]);
    Some((lane, ShapeHit { t: m, uv }))
}

impl FlatShapes {
    /// The blocks of `prims` (index into the geometry's primitives, primitive).
    pub fn new(prims: &[(u32, Primitive)]) -> FlatShapes {
        let tris: Vec<(u32, [glam::Vec3; 3])> = prims
            .iter()
            .filter_map(|&(i, p)| match p.shape {
                Shape::Triangle(t) => Some((i, [t.p0, t.e1, t.e2])),
                _ => None,
            })
            .collect();
        FlatShapes {
            triangles: tris.chunks(blocks::LANES).map(Triangle4::new).collect(),
            rects: blocks_of(prims),
            spheres: blocks_of(prims),
            disks: blocks_of(prims),
        }
    }

    /// Number of blocks (of every kind).
    pub fn block_count(&self) -> usize {
        self.triangles.len() + self.rects.len() + self.spheres.len() + self.disks.len()
    }

    /// The closest hit of `ray` in (0, t_max): the primitive's index and the hit. A ray
    /// that is not finite, or has no direction, hits nothing. Inlined into each caller:
    /// left as a call, `envmap_rotated.xml` took 0.8 % more instructions.
    #[inline(always)]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<(u32, ShapeHit)> {
        if !usable(ray) {
            return None;
        }
        // Each kind's blocks in turn, keeping the nearest so far.
        let mut best: Best = (t_max, None);
        for block in &self.triangles {
            if let Some(h) = block.closest_hit(ray, best.0) {
                let uv = Vec2::new(h.hit.b1, h.hit.b2);
                best = (
                    h.hit.t,
                    Some((block.ids[h.lane], ShapeHit { t: h.hit.t, uv })),
                );
            }
        }
        closest_in(&self.rects, ray, &mut best);
        closest_in(&self.spheres, ray, &mut best);
        closest_in(&self.disks, ray, &mut best);
        best.1
    }

    /// True when something blocks `ray` in (0, t_max). A ray that is not finite, or has
    /// no direction, or an interval that is empty or NaN, is never blocked (the tree
    /// refuses the first and the last; a ray without direction, which no renderer's
    /// query makes, may there count as blocked by a sphere around its origin).
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        usable(ray)
            && t_max > 0.0
            && (any_in(&self.rects, ray, t_max)
                || any_in(&self.spheres, ray, t_max)
                || self.triangles.iter().any(|b| b.any_hit(ray, t_max))
                || any_in(&self.disks, ray, t_max))
    }
}

/// Whether `ray` can hit anything: finite, with a direction (the tree refuses rays that
/// are not finite; a zero direction would make every sphere lane's distance NaN).
#[inline(always)]
fn usable(ray: &Ray) -> bool {
    ray.o.is_finite() && ray.d.is_finite() && ray.d != glam::Vec3::ZERO
}

#[cfg(test)]
mod tests;
