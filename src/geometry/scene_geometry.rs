//! The scene's geometry: primitives (a shape, a material, maybe a light) in BVH leaf
//! order, and the queries the renderer asks of them.

use glam::{Vec2, Vec3};

use super::bvh::{Bvh, PACKET, PADDING};
use super::flat::{FLAT_BLOCKS, FLAT_MAX, FlatShapes};
use super::hit::{NO_LIGHT, SurfaceHit};
use super::leaf_blocks::{LeafBlocks, wants_blocks};
use super::mesh::Mesh;
use super::shape::{Shape, ShapeHit};
use super::{Aabb, Ray, offset_origin};
use crate::math::Frame;

/// A shape with its material and, if it emits, its light index.
#[derive(Clone, Copy, Debug)]
pub struct Primitive {
    /// The shape.
    pub shape: Shape,
    /// Material index.
    pub material: u32,
    /// Light index, or [`NO_LIGHT`].
    pub light: u32,
}

/// All primitives of a scene behind a BVH (or, for a few, in SIMD blocks tested without
/// it: [`FlatShapes`]).
#[derive(Clone, Debug)]
pub struct Geometry {
    prims: Vec<Primitive>,
    /// Meshes, for shading normals and texture coordinates of triangles.
    pub meshes: Vec<Mesh>,
    bvh: Bvh,
    /// The leaves' triangles in SIMD blocks, where most primitives are triangles (then
    /// `prims` holds padding slots nothing hits, see [`LeafBlocks`]).
    blocks: Option<LeafBlocks>,
    /// The emitting primitives behind a BVH of their own, for [`Geometry::first_emitter`];
    /// `None` where they are more than [`EMITTER_SHARE`] of all primitives.
    emitters: Option<Emitters>,
    /// Every primitive in SIMD blocks by kind, where they fill at most [`FLAT_BLOCKS`]:
    /// then the queries test them all instead of walking the BVH (see [`FlatShapes`]).
    flat: Option<FlatShapes>,
    /// In such a scene, the emitting primitives alone in blocks of their own, where they
    /// fill fewer blocks than the whole scene (for [`Geometry::first_emitter`]).
    flat_emitters: Option<FlatShapes>,
}

/// The emitting primitives: their BVH, and for each of its leaf positions the primitive
/// (an index into [`Geometry::primitives`]).
#[derive(Clone, Debug)]
struct Emitters {
    bvh: Bvh,
    prims: Vec<u32>,
}

/// What a ray meets first, for direct lighting (see [`Geometry::first_emitter`]).
#[derive(Clone, Copy, Debug)]
pub enum Along {
    /// The closest hit, on an emitter.
    Emitter(SurfaceHit),
    /// Nothing: the ray leaves the scene.
    Escapes,
    /// Something that does not emit (or, when escapes are not asked for, nothing).
    Blocked,
}

/// Largest share of emitting primitives for which [`Geometry::first_emitter`] tests the
/// emitters first. A ray that meets an emitter then costs two traversals (the emitters',
/// and an any-hit query of the scene up to it) instead of one, which pays only where
/// most rays miss every emitter.
const EMITTER_SHARE: f32 = 0.25;

impl Geometry {
    /// Builds the BVH and stores primitives in its leaf order (with leaf blocks where
    /// most are triangles, see [`LeafBlocks`]).
    pub fn new(prims: Vec<Primitive>, meshes: Vec<Mesh>) -> Geometry {
        let blocks = wants_blocks(&prims);
        Geometry::build(prims, meshes, blocks)
    }

    /// [`Geometry::new`] with leaf blocks or without.
    fn build(prims: Vec<Primitive>, meshes: Vec<Mesh>, use_blocks: bool) -> Geometry {
        let (bvh, prims, blocks) = if use_blocks && !prims.is_empty() {
            let (bvh, laid, blocks) = LeafBlocks::build(&prims);
            (bvh, laid, Some(blocks))
        } else {
            let bounds: Vec<Aabb> = prims.iter().map(|p| p.shape.bounds()).collect();
            let bvh = Bvh::build(&bounds);
            let laid = bvh
                .primitive_order()
                .iter()
                .map(|&i| prims[i as usize])
                .collect();
            (bvh, laid, None)
        };
        let is_padding = |i: usize| blocks.is_some() && bvh.primitive_order()[i] == PADDING;
        let emitting: Vec<u32> = (0..prims.len() as u32)
            .filter(|&i| prims[i as usize].light != NO_LIGHT && !is_padding(i as usize))
            .collect();
        let real = (0..prims.len()).filter(|&i| !is_padding(i)).count();
        let flat = (real <= FLAT_MAX)
            .then(|| {
                let listed: Vec<(u32, Primitive)> = (0..prims.len())
                    .filter(|&i| !is_padding(i))
                    .map(|i| (i as u32, prims[i]))
                    .collect();
                FlatShapes::new(&listed)
            })
            .filter(|flat| flat.block_count() <= FLAT_BLOCKS);
        let emitters = (emitting.len() as f32 <= EMITTER_SHARE * real as f32).then(|| {
            let bounds: Vec<Aabb> = emitting
                .iter()
                .map(|&i| prims[i as usize].shape.bounds())
                .collect();
            let bvh = Bvh::build(&bounds);
            let prims = bvh
                .primitive_order()
                .iter()
                .map(|&k| emitting[k as usize])
                .collect();
            Emitters { bvh, prims }
        });
        // The emitters' blocks pay where they are fewer than the scene's: with as many,
        // a ray tests them all and then, when it meets a light, every block again.
        let flat_emitters = flat.as_ref().and_then(|all| {
            let listed: Vec<(u32, Primitive)> =
                emitting.iter().map(|&i| (i, prims[i as usize])).collect();
            let apart = FlatShapes::new(&listed);
            (apart.block_count() < all.block_count()).then_some(apart)
        });
        Geometry {
            prims,
            meshes,
            bvh,
            blocks,
            emitters,
            flat,
            flat_emitters,
        }
    }

    /// The primitives, in BVH order (indices match [`SurfaceHit::prim`]); with leaf
    /// blocks, padding slots hold copies of a primitive with an empty triangle.
    pub fn primitives(&self) -> &[Primitive] {
        &self.prims
    }

    /// The primitives in the order they were added to the scene (padding slots left
    /// out).
    pub fn primitives_as_added(&self) -> Vec<Primitive> {
        let mut added: Vec<(u32, Primitive)> = self
            .bvh
            .primitive_order()
            .iter()
            .zip(&self.prims)
            .filter(|(i, _)| **i != PADDING)
            .map(|(&i, p)| (i, *p))
            .collect();
        added.sort_unstable_by_key(|(i, _)| *i);
        added.into_iter().map(|(_, p)| p).collect()
    }

    /// The BVH.
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// Box around everything.
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// The closest hit of `ray` in (0, t_max), with its shading data.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<SurfaceHit> {
        if let Some(flat) = &self.flat {
            let (prim, hit) = flat.closest_hit(ray, t_max)?;
            return self.surface_hit(prim, ray, &hit);
        }
        // Every hit a leaf reports (t below the closest so far) becomes the closest, so
        // the last one reported is the winner: keep its surface parameters.
        let mut last = None;
        let (prim, _) = match &self.blocks {
            Some(blocks) => self.bvh.closest_hit_leaf(ray, t_max, |first, _, r, t| {
                let (prim, hit) = blocks.closest_hit(&self.prims, first, r, t)?;
                last = Some(hit);
                Some((prim, hit.t))
            }),
            None => self.bvh.closest_hit(ray, t_max, |i, r, t| {
                let hit = self.prims[i as usize].shape.intersect(r, t)?;
                last = Some(hit);
                Some(hit.t)
            }),
        }?;
        self.surface_hit(prim, ray, &last?)
    }

    /// [`Geometry::intersect`] for a packet of rays traced together (see
    /// [`Bvh::closest_hit_packet`]): ray `lane` in (0, `t_max[lane]`); lanes whose t_max is
    /// not positive take no part and get `None`. Each hit is at the single-ray query's
    /// distance, up to the visiting order's say at exact ties (see
    /// [`Bvh::closest_hit_packet`]). In a scene tested without a tree, each ray is
    /// tested alone.
    #[inline]
    pub fn intersect_packet(
        &self,
        rays: &[Ray; PACKET],
        t_max: &[f32; PACKET],
    ) -> [Option<SurfaceHit>; PACKET] {
        if self.flat.is_some() {
            return std::array::from_fn(|l| {
                (t_max[l] > 0.0)
                    .then(|| self.intersect(&rays[l], t_max[l]))
                    .flatten()
            });
        }
        // As in `intersect`: the last hit a lane's leaves report is its closest.
        let mut last = [None; PACKET];
        let found = match &self.blocks {
            Some(blocks) => self
                .bvh
                .closest_hit_packet(rays, t_max, |lane, first, _, r, t| {
                    let (prim, hit) = blocks.closest_hit(&self.prims, first, r, t)?;
                    last[lane] = Some(hit);
                    Some((prim, hit.t))
                }),
            None => self
                .bvh
                .closest_hit_packet(rays, t_max, |lane, first, count, r, mut t| {
                    let mut best = None;
                    for prim in first..first + count {
                        let shape = &self.prims[prim as usize].shape;
                        if let Some(hit) = shape.intersect(r, t).filter(|h| h.t < t) {
                            t = hit.t;
                            last[lane] = Some(hit);
                            best = Some((prim, hit.t));
                        }
                    }
                    best
                }),
        };
        std::array::from_fn(|l| self.surface_hit(found[l]?.0, &rays[l], &last[l]?))
    }

    /// What `ray` meets first, as direct lighting asks it of a BSDF-sampled ray: the
    /// closest hit if it is on an emitter, else whether the ray escapes the scene (told
    /// only when `tell_escape`, for an environment to light it; otherwise such rays are
    /// [`Along::Blocked`] too). The same answer as `intersect(ray, ∞)` classified, found
    /// more cheaply where emitters are few and there is no escape to tell: the emitters
    /// alone are intersected first; a ray that meets one at distance t needs only an
    /// any-hit query of the scene in (0, t) (every shape reports hits below its t_max
    /// only, so the emitter does not block itself), and one that meets none needs no
    /// traversal at all. In a scene without emitting shapes, an escape is one any-hit
    /// query. A blocker at exactly the emitter's distance, which the
    /// closest-hit query would order by traversal, here leaves the emitter visible; one
    /// whose distance is NaN (a sphere too large to square its radius) blocks it, as it
    /// blocks shadow rays. A scene tested without a tree ([`Geometry::is_flat`]) does
    /// the same with its emitters' blocks and then all its blocks where the emitters
    /// fill fewer blocks than the scene and no escape is asked (see
    /// `first_emitter_flat`); otherwise it takes the closest hit.
    #[inline]
    pub fn first_emitter(&self, ray: &Ray, tell_escape: bool) -> Along {
        // With escapes to tell and emitters to find, the two queries (the emitters', then
        // an any-hit one of the scene) cost more than the one closest hit: +6.8 % of
        // all instructions on `constant_env.xml` (a sphere light under a sky).
        let emitters = match &self.emitters {
            _ if self.flat.is_some() => return self.first_emitter_flat(ray, tell_escape),
            Some(e) if !tell_escape || e.prims.is_empty() => e,
            _ => return self.classify(self.intersect(ray, f32::INFINITY), tell_escape),
        };
        let mut last = None;
        let nearest = emitters.bvh.closest_hit(ray, f32::INFINITY, |k, r, t| {
            let prim = emitters.prims[k as usize];
            let hit = self.prims[prim as usize].shape.intersect(r, t)?;
            last = Some(hit);
            Some(hit.t)
        });
        match (nearest, last) {
            (Some((k, t)), Some(hit)) if !self.occluded(ray, t) => self
                .surface_hit(emitters.prims[k as usize], ray, &hit)
                .map_or(Along::Blocked, Along::Emitter),
            (None, _) if tell_escape && !self.occluded(ray, f32::INFINITY) => Along::Escapes,
            _ => Along::Blocked,
        }
    }

    /// [`Geometry::first_emitter`] in a scene tested without a tree. Where its emitters
    /// fill fewer blocks than the scene and no escape is asked for: the emitters' blocks
    /// first (usually one block: a ray that misses it needs nothing more), then an
    /// any-hit pass over every block up to the emitter met. Otherwise the closest hit,
    /// one pass over every block. On the README's scene (a small light over six shapes)
    /// the closest hit and its shading data cost a BSDF ray about 335 instructions, and
    /// most BSDF rays miss the light.
    #[inline]
    fn first_emitter_flat(&self, ray: &Ray, tell_escape: bool) -> Along {
        match &self.flat_emitters {
            Some(emitting) if !tell_escape => match emitting.closest_hit(ray, f32::INFINITY) {
                Some((prim, hit)) if !self.occluded(ray, hit.t) => self
                    .surface_hit(prim, ray, &hit)
                    .map_or(Along::Blocked, Along::Emitter),
                _ => Along::Blocked,
            },
            _ => self.classify(self.intersect(ray, f32::INFINITY), tell_escape),
        }
    }

    /// The closest hit `closest` as [`Geometry::first_emitter`] reports it.
    #[inline]
    fn classify(&self, closest: Option<SurfaceHit>, tell_escape: bool) -> Along {
        match closest {
            Some(y) if y.light != NO_LIGHT => Along::Emitter(y),
            None if tell_escape => Along::Escapes,
            _ => Along::Blocked,
        }
    }

    /// True when something blocks `ray` in (0, t_max).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        if let Some(flat) = &self.flat {
            return flat.any_hit(ray, t_max);
        }
        match &self.blocks {
            Some(blocks) => self.bvh.any_hit_leaf(ray, t_max, |first, _, r, t| {
                blocks.any_hit(&self.prims, first, r, t)
            }),
            None => self.bvh.any_hit(ray, t_max, |i, r, t| {
                self.prims[i as usize].shape.intersect(r, t).is_some()
            }),
        }
    }

    /// True when the segment from surface point `x` (geometric normal `nx`) to surface
    /// point `y` (geometric normal `ny`) is blocked; both ends are offset off their
    /// surfaces so neither counts as a blocker.
    #[inline]
    pub fn segment_occluded(&self, x: Vec3, nx: Vec3, y: Vec3, ny: Vec3) -> bool {
        let o = offset_origin(x, nx, y - x);
        let target = offset_origin(y, ny, x - y);
        self.occluded(&Ray::new(o, target - o), 1.0 - 1e-4)
    }

    /// True when a ray leaving surface point `x` along unit `w` is blocked within
    /// `distance` (used for point lights and lights at a known distance).
    #[inline]
    pub fn direction_occluded(&self, x: Vec3, nx: Vec3, w: Vec3, distance: f32) -> bool {
        let o = offset_origin(x, nx, w);
        self.occluded(&Ray::new(o, w), distance * (1.0 - 1e-4))
    }

    /// Texture coordinates of `hit`: a mesh's own where it has them, else the shape's.
    pub fn texture_uv(&self, hit: &SurfaceHit) -> Vec2 {
        let p = &self.prims[hit.prim as usize];
        match &p.shape {
            Shape::Triangle(tri) => {
                let b = hit.shape_uv;
                self.meshes[tri.mesh as usize].uv(tri.index, b.x, b.y)
            }
            shape => shape.texture_uv(hit.p, hit.shape_uv),
        }
    }

    fn surface_hit(&self, prim: u32, ray: &Ray, hit: &ShapeHit) -> Option<SurfaceHit> {
        let p = &self.prims[prim as usize];
        let point = ray.at(hit.t);
        let ng = p.shape.normal_at(point);
        let mut ns = ng;
        if let Shape::Triangle(tri) = &p.shape {
            let mesh = &self.meshes[tri.mesh as usize];
            if let Some(n) = mesh.shading_normal(tri.index, hit.uv.x, hit.uv.y) {
                // Keep the shading normal on the geometric normal's side.
                ns = if n.dot(ng) < 0.0 { -n } else { n };
            }
        }
        Some(SurfaceHit {
            p: point,
            t: hit.t,
            ng,
            frame: Frame::from_normal(ns),
            shape_uv: hit.uv,
            prim,
            material: p.material,
            light: p.light,
        })
    }

    /// The same geometry queried through its BVH even where it is small (for tests).
    #[cfg(test)]
    pub fn without_flat(mut self) -> Geometry {
        self.flat = None;
        self.flat_emitters = None;
        self
    }

    /// Whether the queries test every primitive in SIMD blocks instead of walking the BVH
    /// (a scene whose primitives fill at most [`FLAT_BLOCKS`] blocks).
    pub fn is_flat(&self) -> bool {
        self.flat.is_some()
    }

    /// True when primitive `prim` emits.
    pub fn is_emitter(&self, prim: u32) -> bool {
        self.prims[prim as usize].light != NO_LIGHT
    }
}

#[cfg(test)]
mod leaf_block_tests;

#[cfg(test)]
mod tests;
