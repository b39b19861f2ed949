//! The scene's leaves as blocks: where most primitives are mesh triangles, the scene BVH
//! is built with leaf blocks ([`Bvh::build_blocks`]) and each block's triangles are kept
//! again as one [`Triangle4`], so a leaf's triangles are one SIMD test; its other shapes
//! (spheres, rectangles, disks) are tested one by one as before.

use super::bvh::node::MAX_PRIMITIVES;
use super::bvh::{BLOCK, Bvh, PADDING};
use super::hit::NO_LIGHT;
use super::scene_geometry::Primitive;
use super::shape::{Shape, ShapeHit};
use super::triangle4::Triangle4;
use super::{Aabb, Ray};
use glam::{Vec2, Vec3};

/// Per leaf block: its triangles in SIMD lanes, and which lanes hold other shapes.
#[derive(Clone, Debug)]
pub struct LeafBlocks {
    /// Block k's triangles (lanes of other shapes and padding left empty).
    triangles: Vec<Triangle4>,
    /// Block k's lanes holding a shape other than a triangle, as a bit mask, and
    /// [`HAS_TRIANGLES`] where some lane holds a triangle.
    others: Vec<u8>,
}

/// The bit of [`LeafBlocks::others`] set where a block holds a triangle: blocks of other
/// shapes alone (a small scene's floor and lights, laid out together) skip the SIMD
/// triangle test.
const HAS_TRIANGLES: u8 = 1 << 7;

/// Least share of triangles among the primitives for which the scene BVH is built with
/// leaf blocks. Below it leaves stay one primitive at a time (the SAH of blocks makes
/// leaves of four, which costs four tests where the shapes are spheres or rectangles).
pub const BLOCK_SHARE: f32 = 0.5;

/// True when `prims` should be tested in leaf blocks (and are few enough for a block
/// build: at most [`MAX_PRIMITIVES`] / [`BLOCK`]).
pub fn wants_blocks(prims: &[Primitive]) -> bool {
    if prims.len() > MAX_PRIMITIVES / BLOCK {
        return false;
    }
    let triangles = prims
        .iter()
        .filter(|p| matches!(p.shape, Shape::Triangle(_)))
        .count();
    !prims.is_empty() && triangles as f32 >= BLOCK_SHARE * prims.len() as f32
}

/// A primitive no ray hits and that does not emit, for the padding slots of leaf blocks.
fn padding(template: &Primitive) -> Primitive {
    Primitive {
        shape: Shape::Triangle(super::shape::Triangle {
            p0: Vec3::ZERO,
            e1: Vec3::ZERO,
            e2: Vec3::ZERO,
            mesh: 0,
            index: 0,
        }),
        material: template.material,
        light: NO_LIGHT,
    }
}

impl LeafBlocks {
    /// Builds the BVH with leaf blocks over `prims` (non-empty) and returns it with the
    /// primitives in its leaf order (padding slots hold a primitive nothing hits) and the
    /// blocks.
    pub fn build(prims: &[Primitive]) -> (Bvh, Vec<Primitive>, LeafBlocks) {
        let bounds: Vec<Aabb> = prims.iter().map(|p| p.shape.bounds()).collect();
        let bvh = Bvh::build_blocks(&bounds);
        let filler = padding(&prims[0]);
        let laid: Vec<Primitive> = bvh
            .primitive_order()
            .iter()
            .map(|&i| {
                if i == PADDING {
                    filler
                } else {
                    prims[i as usize]
                }
            })
            .collect();
        let triangles = Triangle4::blocks(bvh.primitive_order(), |at, _| match laid[at].shape {
            Shape::Triangle(t) => Some((at as u32, [t.p0, t.e1, t.e2])),
            _ => None,
        });
        // Padding slots hold an empty triangle, so they never count as other shapes (nor
        // as triangles).
        let order = bvh.primitive_order();
        let others = laid
            .chunks(BLOCK)
            .zip(order.chunks(BLOCK))
            .map(|(block, ids)| {
                let other = |(_, p): &(usize, &Primitive)| !matches!(p.shape, Shape::Triangle(_));
                let mask = (block.iter().enumerate().filter(other))
                    .fold(0u8, |mask, (lane, _)| mask | 1 << lane);
                let triangle = block
                    .iter()
                    .zip(ids)
                    .any(|(p, &id)| id != PADDING && matches!(p.shape, Shape::Triangle(_)));
                mask | if triangle { HAS_TRIANGLES } else { 0 }
            })
            .collect();
        (bvh, laid, LeafBlocks { triangles, others })
    }

    /// The closest hit in (0, t_closest) among the leaf at `first` (a multiple of
    /// [`BLOCK`]): its leaf-order position and the hit. Triangles are tested first, then
    /// the other shapes within the triangles' distance.
    #[inline(always)]
    pub fn closest_hit(
        &self,
        prims: &[Primitive],
        first: u32,
        ray: &Ray,
        mut t_closest: f32,
    ) -> Option<(u32, ShapeHit)> {
        let k = first as usize / BLOCK;
        let mut best = None;
        let kinds = self.others[k];
        if kinds & HAS_TRIANGLES != 0
            && let Some(h) = self.triangles[k].closest_hit(ray, t_closest)
        {
            t_closest = h.hit.t;
            let uv = Vec2::new(h.hit.b1, h.hit.b2);
            best = Some((first + h.lane as u32, ShapeHit { t: h.hit.t, uv }));
        }
        let mut others = kinds & !HAS_TRIANGLES;
        while others != 0 {
            let prim = first + others.trailing_zeros();
            others &= others - 1;
            if let Some(h) = prims[prim as usize].shape.intersect(ray, t_closest) {
                t_closest = h.t;
                best = Some((prim, h));
            }
        }
        best
    }

    /// True when something in the leaf at `first` blocks `ray` in (0, t_max).
    #[inline(always)]
    pub fn any_hit(&self, prims: &[Primitive], first: u32, ray: &Ray, t_max: f32) -> bool {
        let k = first as usize / BLOCK;
        let kinds = self.others[k];
        if kinds & HAS_TRIANGLES != 0 && self.triangles[k].any_hit(ray, t_max) {
            return true;
        }
        let mut others = kinds & !HAS_TRIANGLES;
        while others != 0 {
            let prim = first + others.trailing_zeros();
            others &= others - 1;
            if prims[prim as usize].shape.intersect(ray, t_max).is_some() {
                return true;
            }
        }
        false
    }
}
