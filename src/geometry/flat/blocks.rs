//! Spheres, rectangles and disks four at a time: one shape per SIMD lane, the ray the
//! same in every lane (the layout of [`Triangle4`](crate::geometry::triangle4::Triangle4),
//! for the analytic shapes). glam's `Vec4` is SSE2 on x86-64 and NEON on aarch64, both
//! baseline.
//!
//! Each lane runs the scalar test's operations in the same order ([`Sphere::intersect`],
//! [`Rectangle::intersect`], [`Disk::intersect`]) with every early `return None` turned
//! into a lane mask, so a lane's verdict, distance and parameters are the scalar test's
//! bit for bit (tested in `flat/tests.rs`; rays that are not finite or have no
//! direction give the same verdicts, and a NaN distance where the scalar test's is NaN).
//! Unused lanes are masked out.

use glam::{BVec4A, Vec3, Vec4};

use crate::geometry::Ray;
use crate::geometry::shape::{Disk, Rectangle, Shape, Sphere};

/// Lanes per block.
pub const LANES: usize = 4;

/// What a block's test leaves: which lanes the scalar test would hit (`Some`), and each
/// lane's distance and surface parameters (zero where the scalar test leaves them for
/// the winning hit).
pub struct Hits4 {
    /// Lanes hit.
    pub some: BVec4A,
    /// Distances.
    pub t: Vec4,
    /// First surface parameter.
    pub u: Vec4,
    /// Second surface parameter.
    pub v: Vec4,
}

/// A block of up to four analytic shapes of one kind ([`Sphere4`], [`Rect4`],
/// [`Disk4`]), tested against one ray in every lane at once.
pub trait ShapeBlock: Sized {
    /// The scalar shape one lane holds.
    type Shape: Copy;
    /// The shape `shape` holds, if it is of this block's kind.
    fn pick(shape: &Shape) -> Option<Self::Shape>;
    /// The block of `shapes` (at most four; the other lanes unused).
    fn new(shapes: &[Self::Shape]) -> Self;
    /// The scalar test in every lane, in (0, t_max).
    fn hits(&self, ray: &Ray, t_max: f32) -> Hits4;
}

/// A vector's three coordinates over four lanes.
type V3x4 = [Vec4; 3];

/// The lanes below `n`.
fn used(n: usize) -> BVec4A {
    BVec4A::new(n > 0, n > 1, n > 2, n > 3)
}

/// Lane `l`'s coordinates of `vectors[l]`, structure-of-arrays (missing lanes `fill`).
fn soa(vectors: &[Vec3], fill: Vec3) -> V3x4 {
    std::array::from_fn(|axis| {
        Vec4::from_array(std::array::from_fn(|l| {
            vectors.get(l).copied().unwrap_or(fill)[axis]
        }))
    })
}

/// `a · b` for a lane vector and the ray's vector (glam's `Vec3::dot`, term by term).
#[inline(always)]
fn dot(a: &V3x4, b: Vec3) -> Vec4 {
    a[0] * b.x + a[1] * b.y + a[2] * b.z
}

/// `a · b` for two lane vectors.
#[inline(always)]
fn dot4(a: &V3x4, b: &V3x4) -> Vec4 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where `ray` meets, in each lane, the plane through `point` with normal `normal`, as
/// the scalar rectangle and disk tests compute it: (d · n, t = ((point − o) · n) / (d · n),
/// ray.at(t) − point).
#[inline(always)]
fn plane(point: &V3x4, normal: &V3x4, ray: &Ray) -> (Vec4, Vec4, V3x4) {
    let (o, d) = (ray.o, ray.d);
    let denom = dot(normal, d);
    let to = [
        point[0] - Vec4::splat(o.x),
        point[1] - Vec4::splat(o.y),
        point[2] - Vec4::splat(o.z),
    ];
    let t = dot4(&to, normal) / denom;
    let q = [
        (Vec4::splat(o.x) + d.x * t) - point[0],
        (Vec4::splat(o.y) + d.y * t) - point[1],
        (Vec4::splat(o.z) + d.z * t) - point[2],
    ];
    (denom, t, q)
}

/// Up to four spheres.
#[derive(Clone, Copy, Debug)]
pub struct Sphere4 {
    center: V3x4,
    radius: Vec4,
    used: BVec4A,
}

impl ShapeBlock for Sphere4 {
    type Shape = Sphere;

    fn pick(shape: &Shape) -> Option<Sphere> {
        match shape {
            Shape::Sphere(x) => Some(*x),
            _ => None,
        }
    }

    /// The block of `spheres` (at most four).
    fn new(spheres: &[Sphere]) -> Sphere4 {
        assert!(spheres.len() <= LANES);
        let centers: Vec<Vec3> = spheres.iter().map(|s| s.center).collect();
        Sphere4 {
            center: soa(&centers, Vec3::ZERO),
            radius: Vec4::from_array(std::array::from_fn(|l| {
                spheres.get(l).map_or(f32::NAN, |s| s.radius)
            })),
            used: used(spheres.len()),
        }
    }

    /// [`Sphere::intersect`] in every lane, in (0, t_max).
    #[inline(always)]
    fn hits(&self, ray: &Ray, t_max: f32) -> Hits4 {
        let a = Vec4::splat(ray.d.length_squared());
        let d = ray.d;
        let f = [
            Vec4::splat(ray.o.x) - self.center[0],
            Vec4::splat(ray.o.y) - self.center[1],
            Vec4::splat(ray.o.z) - self.center[2],
        ];
        let b = -dot(&f, d);
        let k = b / a;
        let l = [f[0] + k * d.x, f[1] + k * d.y, f[2] + k * d.z];
        let r2 = self.radius * self.radius;
        let disc = a * (r2 - dot4(&l, &l));
        let c = dot4(&f, &f) - r2;
        // b.signum(): ±1 by b's sign bit (a NaN b makes q NaN either way).
        let q = b + Vec4::ONE.copysign(b) * disc.sqrt();
        let (x, y) = (c / q, q / a);
        let x_first = x.cmplt(y);
        let (t0, t1) = (Vec4::select(x_first, x, y), Vec4::select(x_first, y, x));
        let t = Vec4::select(t0.cmpgt(Vec4::ZERO), t0, t1);
        let some = self.used
            & !disc.cmplt(Vec4::ZERO)
            & q.cmpne(Vec4::ZERO)
            & !(t.cmple(Vec4::ZERO) | t.cmpge(Vec4::splat(t_max)));
        Hits4 {
            some,
            t,
            u: Vec4::ZERO,
            v: Vec4::ZERO,
        }
    }
}

/// Up to four rectangles.
#[derive(Clone, Copy, Debug)]
pub struct Rect4 {
    o: V3x4,
    ea: V3x4,
    eb: V3x4,
    normal: V3x4,
    /// |ea|² and |eb|², as the scalar test computes them.
    la: Vec4,
    lb: Vec4,
    used: BVec4A,
}

impl ShapeBlock for Rect4 {
    type Shape = Rectangle;

    fn pick(shape: &Shape) -> Option<Rectangle> {
        match shape {
            Shape::Rectangle(x) => Some(*x),
            _ => None,
        }
    }

    /// The block of `rects` (at most four).
    fn new(rects: &[Rectangle]) -> Rect4 {
        assert!(rects.len() <= LANES);
        let field = |f: fn(&Rectangle) -> Vec3, fill: Vec3| {
            soa(&rects.iter().map(f).collect::<Vec<_>>(), fill)
        };
        let nan = Vec3::splat(f32::NAN);
        let len = |f: fn(&Rectangle) -> f32| {
            Vec4::from_array(std::array::from_fn(|l| rects.get(l).map_or(f32::NAN, f)))
        };
        Rect4 {
            o: field(|r| r.o, nan),
            ea: field(|r| r.ea, nan),
            eb: field(|r| r.eb, nan),
            normal: field(|r| r.normal, nan),
            la: len(|r| r.ea.length_squared()),
            lb: len(|r| r.eb.length_squared()),
            used: used(rects.len()),
        }
    }

    /// [`Rectangle::intersect`] in every lane, in (0, t_max); both sides count.
    #[inline(always)]
    fn hits(&self, ray: &Ray, t_max: f32) -> Hits4 {
        let (denom, t, q) = plane(&self.o, &self.normal, ray);
        // ray.at(t) − o, dotted with each edge over the edge's squared length.
        let u = dot4(&q, &self.ea) / self.la;
        let v = dot4(&q, &self.eb) / self.lb;
        let (zero, one) = (Vec4::ZERO, Vec4::ONE);
        let some = self.used
            & denom.cmpne(zero)
            & t.cmpgt(zero)
            & t.cmplt(Vec4::splat(t_max))
            & zero.cmple(u)
            & u.cmple(one)
            & zero.cmple(v)
            & v.cmple(one);
        Hits4 { some, t, u, v }
    }
}

/// Up to four disks.
#[derive(Clone, Copy, Debug)]
pub struct Disk4 {
    center: V3x4,
    normal: V3x4,
    radius: Vec4,
    used: BVec4A,
}

impl ShapeBlock for Disk4 {
    type Shape = Disk;

    fn pick(shape: &Shape) -> Option<Disk> {
        match shape {
            Shape::Disk(x) => Some(*x),
            _ => None,
        }
    }

    /// The block of `disks` (at most four).
    fn new(disks: &[Disk]) -> Disk4 {
        assert!(disks.len() <= LANES);
        let nan = Vec3::splat(f32::NAN);
        Disk4 {
            center: soa(&disks.iter().map(|d| d.center).collect::<Vec<_>>(), nan),
            normal: soa(&disks.iter().map(|d| d.normal).collect::<Vec<_>>(), nan),
            radius: Vec4::from_array(std::array::from_fn(|l| {
                disks.get(l).map_or(f32::NAN, |d| d.radius)
            })),
            used: used(disks.len()),
        }
    }

    /// [`Disk::intersect`] in every lane, in (0, t_max); both sides count.
    #[inline(always)]
    fn hits(&self, ray: &Ray, t_max: f32) -> Hits4 {
        let (denom, t, q) = plane(&self.center, &self.normal, ray);
        let some = self.used
            & denom.cmpne(Vec4::ZERO)
            & t.cmpgt(Vec4::ZERO)
            & t.cmplt(Vec4::splat(t_max))
            & !dot4(&q, &q).cmpgt(self.radius * self.radius);
        Hits4 {
            some,
            t,
            u: Vec4::ZERO,
            v: Vec4::ZERO,
        }
    }
}
