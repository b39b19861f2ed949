//! Diffuse area emitters and their sampling strategies (area form of the rendering
//! integral: G·V·Le over the light's surface).

use glam::{Vec2, Vec3};

use super::{LightSample, ShadingPoint, area_to_solid_angle};
use crate::geometry::Shape;
use crate::math::{PI, Spectrum, spectrum::luminance};
use crate::sampling::warp::{square_to_uniform_disk_concentric, square_to_uniform_sphere};

named_enum! {
    /// How an area light draws its samples. Named as on the command line.
    pub enum LightSampling: "light sampling" {
        /// Uniform over the shape's area (lecture p₁ = 1/A), with horizon rejection before
        /// the shadow ray.
        Area => "area",
    }
}

/// A diffuse emitter of constant radiance on one shape (a mesh emits as one light per
/// triangle).
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// The emitting shape.
    pub shape: Shape,
    /// Emitted radiance.
    pub radiance: Spectrum,
    /// Emits from both sides (default: only the front, the side of the normal).
    pub two_sided: bool,
    /// Sampling strategy.
    pub sampling: LightSampling,
}

/// A point on a shape drawn uniformly by area, with its normal. Density 1/A.
#[inline]
pub fn sample_shape_area(shape: &Shape, u: Vec2) -> (Vec3, Vec3) {
    match shape {
        Shape::Rectangle(r) => (r.point(u), r.normal),
        Shape::Triangle(t) => {
            // Folding (lecture): (α, β) with α + β > 1 maps to (1 − α, 1 − β).
            let (a, b) = if u.x + u.y > 1.0 {
                (1.0 - u.x, 1.0 - u.y)
            } else {
                (u.x, u.y)
            };
            (t.p0 + a * t.e1 + b * t.e2, t.normal())
        }
        Shape::Sphere(s) => {
            let (n, _) = square_to_uniform_sphere(u);
            (s.center + s.radius * n, n)
        }
        Shape::Disk(d) => {
            let q = square_to_uniform_disk_concentric(u);
            let f = d.frame();
            (d.center + d.radius * (f.s * q.x + f.t * q.y), d.normal)
        }
    }
}

impl AreaLight {
    /// Radiance leaving a point with normal `ny` in direction `w`.
    #[inline]
    pub fn emitted(&self, ny: Vec3, w: Vec3) -> Spectrum {
        if self.two_sided || ny.dot(w) > 0.0 {
            self.radiance
        } else {
            Spectrum::ZERO
        }
    }

    /// Power Φ = π·L·A (×2 when two-sided), as luminance.
    pub fn power(&self) -> f32 {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        sides * PI * luminance(self.radiance) * self.shape.area()
    }

    /// Samples a point on the light and returns it as a direction from `at`. Checks the
    /// horizon at both ends (cos θ ≤ 0 at the shading point or at the light) before any
    /// shadow ray is traced: such samples carry no light.
    #[inline]
    pub fn sample(&self, at: &ShadingPoint, u: Vec2) -> Option<LightSample> {
        let (y, ny) = match self.sampling {
            LightSampling::Area => sample_shape_area(&self.shape, u),
        };
        let d = y - at.p;
        let dist2 = d.length_squared();
        if dist2.is_nan() || dist2 <= 0.0 {
            return None;
        }
        let distance = dist2.sqrt();
        let w_in = d / distance;
        let cos_x = at.n.dot(w_in);
        let radiance = self.emitted(ny, -w_in);
        if cos_x <= 0.0 || radiance == Spectrum::ZERO {
            return None;
        }
        let pdf = self.pdf(at, y, ny);
        (pdf > 0.0 && pdf.is_finite()).then_some(LightSample {
            w_in,
            distance,
            radiance,
            pdf,
            delta: false,
            point: y,
            normal: ny,
        })
    }

    /// Density per steradian of choosing the direction towards `y` (on this light).
    #[inline]
    pub fn pdf(&self, at: &ShadingPoint, y: Vec3, ny: Vec3) -> f32 {
        match self.sampling {
            LightSampling::Area => {
                let d = y - at.p;
                let dist2 = d.length_squared();
                let cos_y = ny.dot(d) / dist2.sqrt();
                area_to_solid_angle(1.0 / self.shape.area(), dist2, cos_y)
            }
        }
    }
}
