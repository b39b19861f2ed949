//! A per-point estimate of a light's unoccluded contribution, for adaptive selection
//! (lecture, many lights, solution #3: "estimate the contribution of each light source
//! for the current point, ignoring visibility — e.g. using one sample of G, or an
//! analytic formula, e.g. for spheres").
//!
//! The estimate is deterministic in the shading point, so a selector's `pmf` can
//! recompute it. It may be zero for a light that still contributes (a quad whose centre
//! is below the horizon but whose edge is above); the adaptive selector mixes it with
//! the conservative [`LightBounds::importance`](super::bounds::LightBounds::importance) so no
//! such light gets probability zero.

use glam::Vec3;

use crate::geometry::Shape;
use crate::light::{Light, ShadingPoint};
use crate::math::{PI, spectrum::luminance};

impl Light {
    /// Estimated irradiance (luminance) at `at`, visibility ignored:
    /// - sphere (radius r, centre at distance d, elevation cos θ): π·L·(r/d)²·cos θ, exact
    ///   for a sphere entirely above the horizon (Nusselt analog);
    /// - planar emitters: one sample of G at the centroid, L·A·cos θ_x·cos θ_y / d²;
    /// - point lights: I·cos θ / d².
    ///
    /// Capped at π·L, the irradiance of an emitter filling the hemisphere, so that
    /// lights close to the surface do not swamp the others.
    pub fn contribution_estimate(&self, at: &ShadingPoint) -> f32 {
        let e = match self {
            // From far away every orientation is alike: ∫L dω / 4 is the irradiance of a
            // plane under a constant environment of the same power (π·L).
            Light::Environment(env) => env.radiance_integral() / 4.0,
            Light::Point(l) => {
                let d = l.position - at.p;
                let dist2 = d.length_squared();
                let cos_x = at.n.dot(d) / dist2.sqrt();
                luminance(l.intensity) * cos_x.max(0.0) / dist2
            }
            Light::Polygon(l) => {
                // One sample of G at the vertex centroid (inside for convex polygons, a
                // fair proxy otherwise; the adaptive floor covers the rest).
                let v = l.polygon.vertices();
                let c = v.iter().copied().sum::<Vec3>() / v.len() as f32;
                let radiance = luminance(l.radiance);
                let d = c - at.p;
                let dist2 = d.length_squared();
                let w = d / dist2.sqrt();
                let n = l.polygon.normal();
                let cos_y = if l.two_sided {
                    n.dot(w).abs()
                } else {
                    (-n.dot(w)).max(0.0)
                };
                let cos_x = at.n.dot(w).max(0.0);
                (radiance * l.polygon.area() * cos_x * cos_y / dist2).min(PI * radiance)
            }
            Light::Area(l) => {
                let radiance = luminance(l.mean_radiance());
                let (center, normal, area) = match &l.shape {
                    Shape::Sphere(s) => {
                        let d = s.center - at.p;
                        let dist2 = d.length_squared();
                        let cos_x = at.n.dot(d) / dist2.sqrt();
                        let sin2 = (s.radius * s.radius / dist2).min(1.0);
                        return (PI * radiance * sin2 * cos_x.max(0.0)).min(PI * radiance);
                    }
                    Shape::Rectangle(r) => (r.o + 0.5 * (r.ea + r.eb), r.normal, r.area()),
                    Shape::Triangle(t) => (t.p0 + (t.e1 + t.e2) / 3.0, t.normal(), t.area()),
                    Shape::Disk(d) => (d.center, d.normal, d.area()),
                };
                let d: Vec3 = center - at.p;
                let dist2 = d.length_squared();
                let w = d / dist2.sqrt();
                let cos_x = at.n.dot(w).max(0.0);
                let cos_y = if l.two_sided {
                    normal.dot(w).abs()
                } else {
                    (-normal.dot(w)).max(0.0)
                };
                (radiance * area * cos_x * cos_y / dist2).min(PI * radiance)
            }
        };
        if e.is_finite() { e.max(0.0) } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::{Rectangle, Sphere};
    use crate::light::AreaLight;
    use crate::math::Spectrum;

    fn area(shape: Shape) -> Light {
        Light::Area(AreaLight {
            shape,
            radiance: Spectrum::splat(2.0),
            two_sided: false,
            texture: None,
        })
    }

    #[test]
    fn known_values() {
        let at = ShadingPoint {
            p: Vec3::ZERO,
            ng: Vec3::Y,
            n: Vec3::Y,
        };
        let s = area(Shape::Sphere(Sphere::new(Vec3::new(0.0, 4.0, 0.0), 1.0)));
        let e = s.contribution_estimate(&at);
        assert!((e - PI * 2.0 / 16.0).abs() < 1e-5, "{e}");
        // A small unit-area quad 10 above, facing down: ≈ L·A/d².
        let q = area(Shape::Rectangle(
            Rectangle::new(
                Vec3::new(-0.5, 10.0, -0.5),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
            )
            .expect("rectangle"),
        ));
        let e = q.contribution_estimate(&at);
        assert!((e - 2.0 / 100.0).abs() < 1e-6, "{e}");
        // Touching the point: capped at π L, never infinite or NaN.
        let touching = area(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0)));
        assert_eq!(touching.contribution_estimate(&at), 0.0);
        let close = area(Shape::Sphere(Sphere::new(Vec3::new(0.0, 1e-3, 0.0), 1.0)));
        assert!(close.contribution_estimate(&at) <= PI * 2.0);
    }
}
