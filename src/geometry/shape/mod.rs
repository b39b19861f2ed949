//! Shapes the renderer intersects: triangles (of meshes), spheres, rectangles and disks.
//! A closed set, so one `enum` with one `match` per operation (no dynamic dispatch).

mod disk;
mod rectangle;
mod sphere;

pub use disk::Disk;
pub use rectangle::Rectangle;
pub use sphere::Sphere;

use glam::{Vec2, Vec3};

use super::triangle::intersect_triangle;
use super::{Aabb, Ray};

/// One triangle of a mesh: the first vertex and two edges, plus where its shading
/// normals live (`mesh`, `index` into [`Mesh`](crate::geometry::Mesh) data).
#[derive(Clone, Copy, Debug)]
pub struct Triangle {
    /// Vertex 0.
    pub p0: Vec3,
    /// p1 − p0.
    pub e1: Vec3,
    /// p2 − p0.
    pub e2: Vec3,
    /// Index of the mesh in the scene's mesh list.
    pub mesh: u32,
    /// Index of the triangle in its mesh.
    pub index: u32,
}

impl Triangle {
    /// Area ½|e1 × e2|.
    pub fn area(&self) -> f32 {
        0.5 * self.e1.cross(self.e2).length()
    }

    /// Unit geometric normal (e1 × e2, counter-clockwise front).
    pub fn normal(&self) -> Vec3 {
        self.e1.cross(self.e2).normalize_or_zero()
    }

    /// The three vertices.
    pub fn vertices(&self) -> [Vec3; 3] {
        [self.p0, self.p0 + self.e1, self.p0 + self.e2]
    }
}

/// A shape of the scene.
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// A mesh triangle.
    Triangle(Triangle),
    /// A sphere.
    Sphere(Sphere),
    /// A rectangle (parallelogram with perpendicular edges).
    Rectangle(Rectangle),
    /// A disk.
    Disk(Disk),
}

/// Where a ray met a shape, before shading data is computed.
#[derive(Clone, Copy, Debug)]
pub struct ShapeHit {
    /// Ray parameter.
    pub t: f32,
    /// Surface parameters (barycentrics b1, b2 for triangles; (u, v) in \[0, 1\]² otherwise).
    pub uv: Vec2,
}

impl Shape {
    /// The shape's bounding box.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Triangle(t) => Aabb::from_points(&t.vertices()),
            Shape::Sphere(s) => s.bounds(),
            Shape::Rectangle(r) => r.bounds(),
            Shape::Disk(d) => d.bounds(),
        }
    }

    /// Surface area.
    pub fn area(&self) -> f32 {
        match self {
            Shape::Triangle(t) => t.area(),
            Shape::Sphere(s) => s.area(),
            Shape::Rectangle(r) => r.area(),
            Shape::Disk(d) => d.area(),
        }
    }

    /// The nearest intersection in (0, t_max).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Triangle(t) => {
                intersect_triangle(ray, t.p0, t.e1, t.e2, t_max).map(|h| ShapeHit {
                    t: h.t,
                    uv: Vec2::new(h.b1, h.b2),
                })
            }
            Shape::Sphere(s) => s.intersect(ray, t_max),
            Shape::Rectangle(r) => r.intersect(ray, t_max),
            Shape::Disk(d) => d.intersect(ray, t_max),
        }
    }

    /// Geometric normal (unit; the side the shape calls "front") at the point `p` on the
    /// shape.
    #[inline]
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        match self {
            Shape::Triangle(t) => t.normal(),
            Shape::Sphere(s) => s.normal_at(p),
            Shape::Rectangle(r) => r.normal,
            Shape::Disk(d) => d.normal,
        }
    }

    /// Texture coordinates at the point `p` on the shape whose hit had parameters
    /// `shape_uv` ([`ShapeHit::uv`]); for a triangle of a mesh, the mesh's own texture
    /// coordinates come first (see [`crate::geometry::Geometry::texture_uv`]).
    #[inline]
    pub fn texture_uv(&self, p: Vec3, shape_uv: Vec2) -> Vec2 {
        match self {
            Shape::Triangle(_) | Shape::Rectangle(_) => shape_uv,
            Shape::Sphere(s) => s.uv_at(p),
            Shape::Disk(d) => d.uv_at(p),
        }
    }
}
