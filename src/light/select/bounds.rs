//! Light bounds for many-light selection: where a light (or a cluster of lights) is, how
//! strong it is and which way it emits, and the importance those bounds give a shading
//! point — an upper-bound-like estimate of the irradiance the cluster can deliver,
//! zero only when no light in it can reach the point (Conty Estevez & Kulla 2018,
//! "Importance Sampling of Many Lights with Adaptive Tree Splitting", §4; pbrt-v4
//! `LightBounds::Importance`, §12.6.3).

use glam::Vec3;

use super::cone::DirectionCone;
use super::prepared::PreparedBounds;
use crate::geometry::{Aabb, Shape};
use crate::light::{Light, ShadingPoint};
use crate::math::{PI, spectrum::luminance};

/// Spatial, emission and orientation bounds of a light or a cluster of lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    /// Box around every emitting point.
    pub aabb: Aabb,
    /// Intensity scale φ: irradiance ≈ φ·cos θ'·cos θ_i / d² (L·A for a planar emitter,
    /// L·πr² for a sphere, I for a point light; summed over a cluster). Luminance.
    pub phi: f32,
    /// Axis of the normal cone.
    pub w: Vec3,
    /// cos θ_o: every emitter normal is within θ_o of `w`.
    pub cos_theta_o: f32,
    /// cos θ_e: each emitter emits within θ_e of its normal (π/2 for diffuse emitters).
    pub cos_theta_e: f32,
    /// Emits on both sides of its normals.
    pub two_sided: bool,
}

impl LightBounds {
    /// No lights: φ = 0, which [`LightBounds::union`] treats as the identity.
    pub const EMPTY: LightBounds = LightBounds {
        aabb: Aabb::EMPTY,
        phi: 0.0,
        w: Vec3::Z,
        cos_theta_o: 1.0,
        cos_theta_e: 1.0,
        two_sided: false,
    };

    /// The bounds of two clusters together: box union, summed φ, the union of the normal
    /// cones and the wider emission angle.
    #[inline]
    pub fn union(&self, b: &LightBounds) -> LightBounds {
        if self.phi == 0.0 {
            return *b;
        }
        if b.phi == 0.0 {
            return *self;
        }
        let cone = DirectionCone {
            w: self.w,
            cos_theta: self.cos_theta_o,
        }
        .union(DirectionCone {
            w: b.w,
            cos_theta: b.cos_theta_o,
        });
        LightBounds {
            aabb: self.aabb.union(b.aabb),
            phi: self.phi + b.phi,
            w: cone.w,
            cos_theta_o: cone.cos_theta,
            cos_theta_e: self.cos_theta_e.min(b.cos_theta_e),
            two_sided: self.two_sided || b.two_sided,
        }
    }

    /// Importance at shading point `at`: φ · cos θ' / d² · cos θ'_i, where d is the
    /// distance to the box centre (clamped below by a tenth of half the box diagonal, so
    /// points near or inside a cluster do not blow up), θ' is the smallest angle between an
    /// emitter normal and the direction to `at` allowed by the normal cone and the box's
    /// angular size, and θ'_i the smallest angle between the shading normal and a
    /// direction into the box. Zero when θ' ≥ θ_e (every emitter faces away) or when the
    /// whole box lies below the horizon of `at`.
    /// The arithmetic lives in [`PreparedBounds`], which the light BVH keeps per node
    /// (its per-node constants computed once); this is the same float.
    pub fn importance(&self, at: &ShadingPoint) -> f32 {
        PreparedBounds::new(self).importance(at)
    }
}

impl Light {
    /// The light's bounds for selection. Planar emitters: a one-normal cone with
    /// θ_e = π/2; spheres and point lights: every normal (θ_o = π), θ_e = π/2; lights at
    /// infinity: φ = 0 (no spatial bounds; selectors handle them apart).
    pub fn bounds(&self) -> LightBounds {
        match self {
            // A light at infinity has no box; selectors treat it apart (φ = 0 keeps it
            // out of any spatial cluster).
            Light::Environment(_) => LightBounds {
                aabb: Aabb {
                    min: Vec3::ZERO,
                    max: Vec3::ZERO,
                },
                phi: 0.0,
                w: Vec3::Z,
                cos_theta_o: -1.0,
                cos_theta_e: 0.0,
                two_sided: false,
            },
            Light::Area(l) => {
                let radiance = luminance(l.mean_radiance()).max(0.0);
                let (w, cos_theta_o, phi) = match &l.shape {
                    Shape::Sphere(s) => (Vec3::Z, -1.0, radiance * PI * s.radius * s.radius),
                    Shape::Rectangle(r) => (r.normal, 1.0, radiance * r.area()),
                    Shape::Triangle(t) => (t.normal(), 1.0, radiance * t.area()),
                    Shape::Disk(d) => (d.normal, 1.0, radiance * d.area()),
                };
                LightBounds {
                    aabb: l.shape.bounds(),
                    phi: if phi.is_finite() { phi } else { 0.0 },
                    w,
                    cos_theta_o,
                    cos_theta_e: 0.0,
                    two_sided: l.two_sided,
                }
            }
            Light::Polygon(l) => {
                let phi = luminance(l.radiance).max(0.0) * l.polygon.area();
                let v = l.polygon.vertices();
                let aabb = v.iter().fold(
                    Aabb {
                        min: v[0],
                        max: v[0],
                    },
                    |b, &p| Aabb {
                        min: b.min.min(p),
                        max: b.max.max(p),
                    },
                );
                LightBounds {
                    aabb,
                    phi: if phi.is_finite() { phi } else { 0.0 },
                    w: l.polygon.normal(),
                    cos_theta_o: 1.0,
                    cos_theta_e: 0.0,
                    two_sided: l.two_sided,
                }
            }
            Light::Point(l) => {
                let phi = luminance(l.intensity).max(0.0);
                LightBounds {
                    aabb: Aabb {
                        min: l.position,
                        max: l.position,
                    },
                    phi: if phi.is_finite() { phi } else { 0.0 },
                    w: Vec3::Z,
                    cos_theta_o: -1.0,
                    cos_theta_e: 0.0,
                    two_sided: false,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::{Rectangle, Sphere};
    use crate::light::{AreaLight, PointLight};
    use crate::math::Spectrum;

    fn at(p: Vec3, n: Vec3) -> ShadingPoint {
        ShadingPoint { p, ng: n, n }
    }

    fn sphere_light(center: Vec3, radius: f32) -> Light {
        Light::Area(AreaLight {
            shape: Shape::Sphere(Sphere::new(center, radius)),
            radiance: Spectrum::ONE,
            two_sided: false,
            texture: None,
        })
    }

    #[test]
    fn sphere_importance_is_its_irradiance_when_above_the_horizon() {
        // E = π L sin²α cos θ for a sphere fully above the horizon; the bound uses the
        // box's bounding sphere, so θ'_i is smaller and the importance at least E.
        let light = sphere_light(Vec3::new(0.0, 10.0, 0.0), 0.5);
        let imp = light.bounds().importance(&at(Vec3::ZERO, Vec3::Y));
        let e = PI * 0.25 / 100.0;
        assert!(imp >= e && imp < 1.01 * e, "{imp} vs {e}");
    }

    #[test]
    fn lights_that_can_contribute_are_never_zero() {
        let p = at(Vec3::ZERO, Vec3::Y);
        // Centre just below the horizon, cap above it.
        let low = sphere_light(Vec3::new(5.0, -0.1, 0.0), 0.2);
        assert!(low.bounds().importance(&p) > 0.0);
        // Tiny and far.
        let far = sphere_light(Vec3::new(3e3, 1e3, 0.0), 1e-3);
        assert!(far.bounds().importance(&p) > 0.0);
        let point = Light::Point(PointLight {
            position: Vec3::new(1e4, 1.0, 0.0),
            intensity: Spectrum::splat(1e-3),
        });
        assert!(point.bounds().importance(&p) > 0.0);
        // A quad just above the horizon, facing the point.
        let quad = Rectangle::new(
            Vec3::new(4.0, 0.01, -0.5),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 0.2, 0.0),
        )
        .expect("rectangle");
        let quad = Light::Area(AreaLight {
            shape: Shape::Rectangle(quad),
            radiance: Spectrum::ONE,
            two_sided: false,
            texture: None,
        });
        assert!(quad.bounds().w.x < 0.0);
        assert!(quad.bounds().importance(&p) > 0.0);
    }

    #[test]
    fn lights_that_cannot_contribute_are_zero() {
        let p = at(Vec3::ZERO, Vec3::Y);
        assert_eq!(
            sphere_light(Vec3::new(0.0, -5.0, 0.0), 1.0)
                .bounds()
                .importance(&p),
            0.0
        );
        // A quad above, facing up (away from the point).
        let quad = Rectangle::new(
            Vec3::new(-0.5, 2.0, 0.5),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -1.0),
        )
        .expect("rectangle");
        let quad = Light::Area(AreaLight {
            shape: Shape::Rectangle(quad),
            radiance: Spectrum::ONE,
            two_sided: false,
            texture: None,
        });
        assert!(quad.bounds().w.y > 0.0);
        assert_eq!(quad.bounds().importance(&p), 0.0);
    }
}
