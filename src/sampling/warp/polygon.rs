//! Uniform points on a planar polygon, convex or concave: by rejection from its bounding
//! rectangle in the polygon's plane, and by choosing a triangle of its ear-clipped
//! triangulation in proportion to area.

use glam::{Vec2, Vec3};

use super::ear_clipping::{contains, signed_area_2x, triangulate};
use super::triangle::{sample_triangle, square_to_triangle_sqrt};
use crate::math::Frame;
use crate::sampling::Uniform;
use crate::sampling::distribution::PiecewiseConstant1D;

/// Why a list of vertices is not a usable polygon.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolygonError {
    /// Fewer than three vertices.
    #[error("a polygon needs at least 3 vertices, got {0}")]
    TooFewVertices(usize),
    /// Zero area, or a non-finite coordinate.
    #[error("the polygon has zero area or a non-finite vertex")]
    Degenerate,
    /// Ear clipping found no ear: the outline crosses itself.
    #[error("the polygon is not simple (its outline crosses itself)")]
    NotSimple,
}

/// A simple planar polygon in world space with its plane frame, bounding rectangle and
/// area-weighted triangulation. Every sampler has pdf 1/area per unit area.
#[derive(Clone, Debug)]
pub struct Polygon {
    vertices: Vec<Vec3>,
    /// Plane frame: `frame.n` is the normal (Newell's method), s and t span the plane.
    frame: Frame,
    origin: Vec3,
    /// Vertices in (s, t) plane coordinates.
    planar: Vec<Vec2>,
    bounds: (Vec2, Vec2),
    area: f32,
    triangles: Vec<[usize; 3]>,
    /// Picks a triangle with probability ∝ its area.
    triangle_choice: PiecewiseConstant1D,
}

impl Polygon {
    /// The polygon with these vertices in order (either orientation). They should lie in
    /// one plane; off-plane components are projected away along the Newell normal.
    pub fn new(vertices: &[Vec3]) -> Result<Polygon, PolygonError> {
        if vertices.len() < 3 {
            return Err(PolygonError::TooFewVertices(vertices.len()));
        }
        // Newell's normal: robust for concave and nearly collinear outlines.
        let n = vertices.len();
        let newell: Vec3 = (0..n)
            .map(|i| vertices[i].cross(vertices[(i + 1) % n]))
            .sum();
        let length = newell.length();
        if !(length > 0.0 && length.is_finite()) {
            return Err(PolygonError::Degenerate);
        }
        let frame = Frame::from_normal(newell / length);
        let origin = vertices[0];
        let planar: Vec<Vec2> = vertices
            .iter()
            .map(|&v| to_plane(&frame, origin, v))
            .collect();
        let area = 0.5 * signed_area_2x(&planar).abs();
        let triangles = triangulate(&planar).ok_or(PolygonError::NotSimple)?;
        let areas: Vec<f32> = triangles
            .iter()
            .map(|t| 0.5 * signed_area_2x(&[planar[t[0]], planar[t[1]], planar[t[2]]]).abs())
            .collect();
        let triangle_choice =
            PiecewiseConstant1D::new(&areas).map_err(|_| PolygonError::Degenerate)?;
        let bounds = planar.iter().fold((planar[0], planar[0]), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
        if !(area > 0.0 && area.is_finite()) {
            return Err(PolygonError::Degenerate);
        }
        Ok(Polygon {
            vertices: vertices.to_vec(),
            frame,
            origin,
            planar,
            bounds,
            area,
            triangles,
            triangle_choice,
        })
    }

    /// The polygon's area.
    pub fn area(&self) -> f32 {
        self.area
    }

    /// The unit normal (right-handed with the vertex order).
    pub fn normal(&self) -> Vec3 {
        self.frame.n
    }

    /// The vertices in order (world space).
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// The ear-clipping triangulation as vertex index triples.
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Density of every sampler: 1/area per unit area at points of the polygon (within
    /// 10⁻⁴ of its plane relative to its size), else 0.
    pub fn pdf(&self, x: Vec3) -> f32 {
        let size = (self.bounds.1 - self.bounds.0).max_element();
        let height = (x - self.origin).dot(self.frame.n).abs();
        let p = to_plane(&self.frame, self.origin, x);
        // Points on the outline (up to rounding) belong to the closed polygon.
        if height <= 1e-4 * size
            && (contains(&self.planar, p) || distance_to_outline(&self.planar, p) <= 1e-5 * size)
        {
            self.uniform_pdf()
        } else {
            0.0
        }
    }

    fn uniform_pdf(&self) -> f32 {
        1.0 / self.area
    }

    /// Uniform point by rejection: points of the bounding rectangle (in the polygon's
    /// plane) until one falls inside (acceptance = area / rectangle area).
    pub fn sample_rejection(&self, src: &mut impl Uniform) -> (Vec3, f32) {
        let (lo, hi) = self.bounds;
        loop {
            let p = lo + src.next_2d() * (hi - lo);
            if contains(&self.planar, p) {
                return (self.plane_point(p), self.uniform_pdf());
            }
        }
    }

    /// Uniform point by the triangulation: u₀ picks a triangle ∝ area and, rescaled,
    /// joins u₁ in the square-root map inside it. Two numbers, no rejection.
    ///
    /// ```
    /// use glam::{Vec2, Vec3};
    /// use lightlab::sampling::warp::Polygon;
    /// let l = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)].map(|(x, y)| Vec3::new(x, y, 0.));
    /// let polygon = Polygon::new(&l).unwrap();
    /// let (p, pdf) = polygon.sample_triangulated(Vec2::new(0.7, 0.2));
    /// assert!(polygon.pdf(p) > 0.0 && (pdf - 1.0 / 3.0).abs() < 1e-6);
    /// ```
    pub fn sample_triangulated(&self, u: Vec2) -> (Vec3, f32) {
        let (index, _, u_reused) = self.triangle_choice.sample_discrete(u.x);
        let [a, b, c] = self.triangles[index];
        let barycentrics = square_to_triangle_sqrt(Vec2::new(u_reused, u.y));
        let (v, p) = (&self.vertices, &self.planar);
        // Sample in the plane so the point lies on the projected outline exactly.
        let point = sample_triangle(
            p[a].extend(0.0),
            p[b].extend(0.0),
            p[c].extend(0.0),
            barycentrics,
        )
        .map_or(v[a], |(q, _)| self.plane_point(q.truncate()));
        (point, self.uniform_pdf())
    }

    fn plane_point(&self, p: Vec2) -> Vec3 {
        self.origin + p.x * self.frame.s + p.y * self.frame.t
    }
}

/// Distance from `p` to the nearest edge of the closed outline.
fn distance_to_outline(vertices: &[Vec2], p: Vec2) -> f32 {
    let n = vertices.len();
    (0..n)
        .map(|i| {
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            let t = ((p - a).dot(b - a) / (b - a).length_squared().max(f32::MIN_POSITIVE))
                .clamp(0.0, 1.0);
            (a + t * (b - a) - p).length()
        })
        .fold(f32::INFINITY, f32::min)
}

fn to_plane(frame: &Frame, origin: Vec3, x: Vec3) -> Vec2 {
    Vec2::new((x - origin).dot(frame.s), (x - origin).dot(frame.t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng32;

    #[test]
    fn samples_lie_inside_and_degenerate_input_is_an_error() {
        let tilt = |x: f32, y: f32| Vec3::new(x, y, 0.5 * x + 0.25 * y);
        let l =
            [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)].map(|(x, y)| tilt(x, y));
        let polygon = Polygon::new(&l).expect("valid");
        let mut rng = Rng32::new(9);
        for _ in 0..1000 {
            let (p, pdf) = polygon.sample_rejection(&mut rng);
            assert!(polygon.pdf(p) == pdf);
            let (p, pdf) = polygon.sample_triangulated(rng.next_2d());
            assert!(polygon.pdf(p) > 0.0 && pdf.is_finite(), "{p}");
        }
        assert!(
            (polygon.area() - 3.0 * tilt(1.0, 0.0).cross(tilt(0.0, 1.0)).length()).abs() < 1e-4
        );
        assert_eq!(
            Polygon::new(&l[..2]).unwrap_err(),
            PolygonError::TooFewVertices(2)
        );
        assert!(Polygon::new(&[Vec3::ZERO, Vec3::X, Vec3::X * 2.0]).is_err());
    }
}
