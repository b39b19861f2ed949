//! The scene's geometry: primitives (a shape, a material, maybe a light) in BVH leaf
//! order, and the queries the renderer asks of them.

use glam::Vec3;

use super::bvh::Bvh;
use super::hit::{NO_LIGHT, SurfaceHit};
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

/// All primitives of a scene behind a BVH.
#[derive(Clone, Debug)]
pub struct Geometry {
    prims: Vec<Primitive>,
    /// Meshes, for shading normals and texture coordinates of triangles.
    pub meshes: Vec<Mesh>,
    bvh: Bvh,
}

impl Geometry {
    /// Builds the BVH and stores primitives in its leaf order.
    pub fn new(prims: Vec<Primitive>, meshes: Vec<Mesh>) -> Geometry {
        let bounds: Vec<Aabb> = prims.iter().map(|p| p.shape.bounds()).collect();
        let bvh = Bvh::build(&bounds);
        let prims = bvh
            .primitive_order()
            .iter()
            .map(|&i| prims[i as usize])
            .collect();
        Geometry { prims, meshes, bvh }
    }

    /// The primitives, in BVH order (indices match [`SurfaceHit::prim`]).
    pub fn primitives(&self) -> &[Primitive] {
        &self.prims
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
        // Every hit the closure reports (t below the closest so far) becomes the closest,
        // so the last one it reports is the winner: keep its surface parameters.
        let mut last = None;
        let (prim, _) = self.bvh.closest_hit(ray, t_max, |i, r, t| {
            let hit = self.prims[i as usize].shape.intersect(r, t)?;
            last = Some(hit);
            Some(hit.t)
        })?;
        self.surface_hit(prim, ray, &last?)
    }

    /// True when something blocks `ray` in (0, t_max).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.bvh.any_hit(ray, t_max, |i, r, t| {
            self.prims[i as usize].shape.intersect(r, t).is_some()
        })
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

    fn surface_hit(&self, prim: u32, ray: &Ray, hit: &ShapeHit) -> Option<SurfaceHit> {
        let p = &self.prims[prim as usize];
        let point = ray.at(hit.t);
        let geo = p.shape.geometry_at(point, hit);
        let (mut ns, mut uv) = (geo.ng, geo.uv);
        if let Shape::Triangle(tri) = &p.shape {
            let mesh = &self.meshes[tri.mesh as usize];
            if let Some(n) = mesh.shading_normal(tri.index, hit.uv.x, hit.uv.y) {
                // Keep the shading normal on the geometric normal's side.
                ns = if n.dot(geo.ng) < 0.0 { -n } else { n };
            }
            uv = mesh.uv(tri.index, hit.uv.x, hit.uv.y);
        }
        Some(SurfaceHit {
            p: point,
            t: hit.t,
            ng: geo.ng,
            frame: Frame::from_normal(ns),
            uv,
            prim,
            material: p.material,
            light: p.light,
        })
    }

    /// True when primitive `prim` emits.
    pub fn is_emitter(&self, prim: u32) -> bool {
        self.prims[prim as usize].light != NO_LIGHT
    }
}
