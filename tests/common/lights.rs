//! Emitters and shading points shared by the light tests: one light per shape facing
//! down onto the plane z = 0 region, every strategy each shape has, and the points it is
//! seen from (near, far, grazing, partly below the horizon).

use glam::{DVec3, Vec2, Vec3};
use lightlab::geometry::shape::{Disk, Rectangle, Sphere, Triangle};
use lightlab::geometry::{Ray, Shape};
use lightlab::light::{
    AreaLight, Light, LightSample, LightSampling, LightStrategy, PolygonLight, ShadingPoint,
};
use lightlab::math::{PI, Spectrum};
use lightlab::sampling::warp::spherical_triangle_solid_angle;

/// Radiance of every test light.
pub const RADIANCE: f32 = 1.5;

/// The emitting shapes under test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TestShape {
    /// Sphere at (0, 0, 1), radius 0.5.
    Sphere,
    /// 1 × 1 square at z = 1 facing down.
    Rectangle,
    /// A triangle at z = 1 facing down.
    Triangle,
    /// A concave L-shaped polygon at z = 1 facing down.
    Polygon,
    /// A disk at z = 1 facing down, radius 0.5.
    Disk,
}

/// Every shape with every strategy it has.
pub const STRATEGIES: [(TestShape, &[LightSampling]); 5] = {
    use LightSampling::*;
    [
        (
            TestShape::Sphere,
            &[Area, VisibleArea, SolidAngle, Geometric],
        ),
        (
            TestShape::Rectangle,
            &[Area, SolidAngle, SolidAngleCos, ProjectedSolidAngle],
        ),
        (
            TestShape::Triangle,
            &[Area, SolidAngle, SolidAngleCos, ProjectedSolidAngle],
        ),
        (
            TestShape::Polygon,
            &[Area, SolidAngle, SolidAngleCos, ProjectedSolidAngle],
        ),
        (TestShape::Disk, &[Area, SolidAngle]),
    ]
};

/// The L-shaped outline (clockwise seen from above, so the normal points down).
pub fn polygon_vertices() -> Vec<Vec3> {
    [
        (0.0, 0.0),
        (0.0, 1.0),
        (0.4, 1.0),
        (0.4, 0.4),
        (1.0, 0.4),
        (1.0, 0.0),
    ]
    .iter()
    .map(|&(x, y)| Vec3::new(x - 0.5, y - 0.5, 1.0))
    .collect()
}

/// The vertices of a planar shape (None for spheres and disks).
pub fn outline(shape: TestShape) -> Option<Vec<Vec3>> {
    match shape {
        TestShape::Rectangle => match shape_of(shape) {
            Shape::Rectangle(r) => Some(r.corners().to_vec()),
            _ => None,
        },
        TestShape::Triangle => match shape_of(shape) {
            Shape::Triangle(t) => Some(t.vertices().to_vec()),
            _ => None,
        },
        TestShape::Polygon => Some(polygon_vertices()),
        _ => None,
    }
}

fn shape_of(shape: TestShape) -> Shape {
    match shape {
        TestShape::Sphere => Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 1.0), 0.5)),
        TestShape::Rectangle => Shape::Rectangle(
            Rectangle::new(Vec3::new(-0.5, -0.5, 1.0), Vec3::Y, Vec3::X).expect("square"),
        ),
        TestShape::Triangle => Shape::Triangle(Triangle {
            p0: Vec3::new(-0.5, -0.4, 1.0),
            e1: Vec3::new(0.2, 1.0, 0.0),
            e2: Vec3::new(1.0, 0.1, 0.0),
            mesh: 0,
            index: 0,
        }),
        TestShape::Disk => Shape::Disk(Disk::new(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z, 0.5)),
        TestShape::Polygon => unreachable!("polygons are not a Shape"),
    }
}

/// A light and the strategy it is sampled with (in a render, the estimator carries the
/// strategy to the light).
pub struct TestLight {
    /// The light.
    pub light: Light,
    /// How it is sampled.
    pub strategy: LightStrategy,
}

impl TestLight {
    /// `Light::sample` with this strategy.
    pub fn sample(&self, at: &ShadingPoint, u: Vec2) -> Option<LightSample> {
        self.light.sample(at, u, self.strategy)
    }

    /// `Light::pdf` with this strategy.
    pub fn pdf(&self, at: &ShadingPoint, y: Vec3, ny: Vec3) -> f32 {
        self.light.pdf(at, y, ny, self.strategy)
    }
}

/// The light of `shape` sampled with `strategy`.
pub fn light(shape: TestShape, strategy: LightSampling) -> TestLight {
    let radiance = Spectrum::splat(RADIANCE);
    let light = match shape {
        TestShape::Polygon => {
            Light::Polygon(PolygonLight::new(&polygon_vertices(), radiance).expect("polygon"))
        }
        _ => Light::Area(AreaLight {
            shape: shape_of(shape),
            radiance,
            two_sided: false,
            texture: None,
        }),
    };
    TestLight {
        light,
        strategy: strategy.into(),
    }
}

/// A shading point at `p` with normal `n`.
pub fn at(p: Vec3, n: Vec3) -> ShadingPoint {
    let n = n.normalize();
    ShadingPoint { p, ng: n, n }
}

/// Where a shading point sits relative to the light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// 0.1–0.2 below the light, facing it.
    Near,
    /// About 10 away.
    Far,
    /// Low and to the side: the light seen at a grazing angle (about 15° for planar
    /// lights), above the horizon. Much flatter slivers defeat the harness's quadrature.
    Grazing,
    /// The normal tilted so the horizon cuts the light roughly in half.
    PartlyBelow,
}

/// Every placement.
pub const PLACEMENTS: [Placement; 4] = [
    Placement::Near,
    Placement::Far,
    Placement::Grazing,
    Placement::PartlyBelow,
];

/// The shading point of `placement` for `shape`.
pub fn placement(shape: TestShape, placement: Placement) -> ShadingPoint {
    match (shape, placement) {
        (TestShape::Sphere, Placement::Near) => at(Vec3::new(0.1, 0.0, 0.4), Vec3::Z),
        (_, Placement::Near) => at(Vec3::new(0.1, -0.2, 0.8), Vec3::Z),
        (_, Placement::Far) => at(Vec3::new(1.0, 2.0, -9.0), Vec3::new(0.0, 0.3, 1.0)),
        (TestShape::Sphere, Placement::Grazing) => at(Vec3::new(3.0, 0.0, 0.3), Vec3::Z),
        // The triangle's sliver is thinner still: a little higher.
        (TestShape::Triangle, Placement::Grazing) => at(Vec3::new(1.4, 0.1, 0.5), Vec3::Z),
        (_, Placement::Grazing) => at(Vec3::new(1.6, 0.2, 0.55), Vec3::Z),
        (_, Placement::PartlyBelow) => at(Vec3::new(0.05, 0.1, 0.3), Vec3::new(1.0, 0.0, 0.3)),
    }
}

/// The first point where the ray from `at` along `w` meets the light, with its normal.
pub fn hit(light: &Light, at: &ShadingPoint, w: Vec3) -> Option<(Vec3, Vec3)> {
    let ray = Ray::new(at.p, w);
    match light {
        Light::Area(a) => {
            let h = a.shape.intersect(&ray, f32::INFINITY)?;
            let y = ray.at(h.t);
            Some((y, a.shape.normal_at(y)))
        }
        Light::Polygon(l) => {
            let n = l.polygon.normal();
            let t = (l.polygon.vertices()[0] - at.p).dot(n) / w.dot(n);
            let y = at.p + t * w;
            (t > 0.0 && l.polygon.pdf(y) > 0.0).then_some((y, n))
        }
        Light::Point(_) | Light::Environment(_) => None,
    }
}

/// The density per steradian of the light's strategy for direction `w` from `at`, zero
/// where a sample would carry no light (missing the light, below the horizon, or seeing
/// the light's back): the density of the directions `sample` returns.
pub fn direction_pdf(light: &TestLight, at: &ShadingPoint, w: Vec3) -> f32 {
    match hit(&light.light, at, w) {
        Some((y, ny)) if at.n.dot(w) > 0.0 && light.light.emitted(y, ny, -w) != Spectrum::ZERO => {
            light.pdf(at, y, ny)
        }
        _ => 0.0,
    }
}

/// The axis (towards the light's centre) and cos of the widest angle of the light from
/// `p`, with a margin: a cap that holds every direction to the light.
pub fn cap(shape: TestShape, p: Vec3) -> (Vec3, f32) {
    match shape {
        TestShape::Sphere | TestShape::Disk => {
            let c = Vec3::new(0.0, 0.0, 1.0);
            let axis = (c - p).normalize();
            let d = (c - p).length();
            let half = (0.5 / d).min(1.0).asin() * 1.05 + 0.02;
            (axis, half.min(PI).cos())
        }
        _ => {
            let v = outline(shape).expect("planar");
            let (lo, hi) = v
                .iter()
                .fold((v[0], v[0]), |(lo, hi), &q| (lo.min(q), hi.max(q)));
            let center = 0.5 * (lo + hi);
            let axis = (center - p).normalize();
            let z = v
                .iter()
                .map(|&q| (q - p).normalize().dot(axis))
                .fold(1.0f32, f32::min);
            let half = z.clamp(-1.0, 1.0).acos() * 1.05 + 0.02;
            (axis, half.min(PI).cos())
        }
    }
}

/// The solid angle of the light seen from `p` (the whole light in front of `p`):
/// analytic for spheres (2π(1 − cos θmax)) and disks on their axis; the sum of the
/// spherical triangles of a triangulation (Van Oosterom & Strackee) for planar shapes.
pub fn solid_angle(shape: TestShape, p: Vec3) -> f64 {
    let c = DVec3::new(0.0, 0.0, 1.0);
    let p64 = p.as_dvec3();
    match shape {
        TestShape::Sphere => {
            let d = (c - p64).length();
            2.0 * std::f64::consts::PI * (1.0 - (1.0 - 0.25 / (d * d)).sqrt())
        }
        TestShape::Disk => {
            assert!(
                p.x == 0.0 && p.y == 0.0,
                "disk solid angle only on the axis"
            );
            let d = (c - p64).length();
            2.0 * std::f64::consts::PI * (1.0 - d / (d * d + 0.25).sqrt())
        }
        _ => {
            let v = outline(shape).expect("planar");
            let triangles: Vec<[usize; 3]> = match shape {
                TestShape::Polygon => vec![[0, 1, 2], [0, 2, 3], [0, 3, 5], [3, 4, 5]],
                _ => (1..v.len() - 1).map(|i| [0, i, i + 1]).collect(),
            };
            let dir = |q: Vec3| (q - p).as_dvec3().normalize();
            triangles
                .iter()
                .map(|t| spherical_triangle_solid_angle(dir(v[t[0]]), dir(v[t[1]]), dir(v[t[2]])))
                .sum()
        }
    }
}
