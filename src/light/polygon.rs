//! Planar polygon emitters, convex or concave (simple outlines). Three strategies:
//! - `area`: a uniform point by rejection from the polygon's bounding rectangle in its
//!   plane, as on the lecture's slide (density 1/A);
//! - `solid-angle`: a triangle of the ear-clipped triangulation chosen with probability
//!   Ω_i/ΣΩ (its solid angle, Van Oosterom & Strackee 1983), then a direction uniform in
//!   it (Arvo 1995). The triangles of a simple planar polygon do not overlap, so neither
//!   do their spherical images, and the density is 1/ΣΩ over the polygon.
//!
//! A triangle whose spherical triangle is unsafe to sample (too small or nearly a
//! hemisphere, see [`safe_spherical_triangle`]) keeps its probability Ω_i/ΣΩ but places
//! its point uniformly by area; its density per steradian is then
//! (Ω_i/ΣΩ)·(1/A_i)·d²/cos θy. Which triangles are unsafe depends only on the shading
//! point, so `sample` and `pdf` agree.
//!
//! - `projected-solid-angle`: a triangle with probability Ω⊥_i/ΣΩ⊥ (its projected solid
//!   angle above the horizon, Lambert's formula), then a direction ∝ cos θ in it
//!   ([`ProjectedPolygon`]); the density is cos θ/ΣΩ⊥ over the polygon.
//!
//! The polygon's geometry in the scene is its triangulation (one mesh whose triangles all
//! point to this light), so it is intersectable like any mesh.

use glam::{DVec2, Vec2, Vec3};

use super::area::{
    EmitterKind, LightPoint, LightSampling, diffuse_emitted, diffuse_power, light_sample,
    uniform_area_pdf,
};
use super::area::{cosine_weights, hit_plane, safe_spherical_triangle, warped_pdf, warped_sample};
use super::area::{hit_plane64, projected_density, visible_projected_solid_angle};
use super::{LightSample, ShadingPoint};
use crate::math::Spectrum;
use crate::sampling::rng::hash_words;
use crate::sampling::warp::{
    Polygon, PolygonError, ProjectedPolygon, spherical_triangle_solid_angle,
    square_to_triangle_sqrt, triangle_area, triangle_to_barycentrics,
};
use crate::sampling::{Rng32, Uniform};

/// A diffuse emitter of constant radiance on a planar polygon.
#[derive(Clone, Debug)]
pub struct PolygonLight {
    /// The polygon (vertices, plane, bounds, triangulation).
    pub polygon: Polygon,
    /// Emitted radiance.
    pub radiance: Spectrum,
    /// Emits from both sides (default: only the side of the polygon's normal).
    pub two_sided: bool,
}

/// The uniform source of rejection sampling from one point `u`: `u` itself first (so a
/// stratified `u` stays stratified when the first candidate is accepted), then a stream
/// keyed by the bits of `u`.
struct ReusedUniform {
    first: Option<Vec2>,
    rng: Rng32,
}

impl ReusedUniform {
    fn new(u: Vec2) -> ReusedUniform {
        ReusedUniform {
            first: Some(u),
            rng: Rng32::new(hash_words(&[u.x.to_bits() as u64, u.y.to_bits() as u64])),
        }
    }
}

impl Uniform for ReusedUniform {
    fn next_1d(&mut self) -> f32 {
        self.rng.next_f32()
    }
    fn next_2d(&mut self) -> Vec2 {
        self.first
            .take()
            .unwrap_or_else(|| Vec2::new(self.rng.next_f32(), self.rng.next_f32()))
    }
}

impl PolygonLight {
    /// A one-sided polygon emitter (front side: right-handed with the vertex order).
    pub fn new(vertices: &[Vec3], radiance: Spectrum) -> Result<PolygonLight, PolygonError> {
        Ok(PolygonLight {
            polygon: Polygon::new(vertices)?,
            radiance,
            two_sided: false,
        })
    }

    /// The strategy in use when `sampling` is asked for: resolved for polygons.
    #[inline]
    pub fn strategy(sampling: LightSampling) -> LightSampling {
        sampling.resolve(EmitterKind::Polygon)
    }

    /// Radiance leaving a point of the polygon in direction `w`.
    #[inline]
    pub fn emitted(&self, w: Vec3) -> Spectrum {
        diffuse_emitted(self.radiance, self.two_sided, self.polygon.normal(), w)
    }

    /// Power Φ = π·L·A (×2 when two-sided), as luminance.
    pub fn power(&self) -> f32 {
        diffuse_power(self.radiance, self.two_sided, self.polygon.area())
    }

    /// The corners of triangle `i` of the triangulation.
    fn triangle(&self, i: usize) -> [Vec3; 3] {
        let v = self.polygon.vertices();
        self.polygon.triangles()[i].map(|k| v[k])
    }

    /// Solid angle of triangle `i` seen from `x` (f64, Van Oosterom & Strackee).
    fn solid_angle(&self, x: Vec3, i: usize) -> f64 {
        let dir = |v: Vec3| (v - x).as_dvec3().normalize_or_zero();
        let [a, b, c] = self.triangle(i);
        spherical_triangle_solid_angle(dir(a), dir(b), dir(c))
    }

    /// ΣΩ_i over the triangulation seen from `x`.
    fn total_solid_angle(&self, x: Vec3) -> f64 {
        (0..self.polygon.triangles().len())
            .map(|i| self.solid_angle(x, i))
            .sum()
    }

    /// Draws a point with strategy `sampling` (resolved for polygons) and returns it as a
    /// direction from `at`; `None` when it carries no light (see
    /// [`AreaLight::sample`](super::AreaLight::sample)).
    pub fn sample(
        &self,
        at: &ShadingPoint,
        u: Vec2,
        sampling: LightSampling,
    ) -> Option<LightSample> {
        self.sample_with(at, u, sampling, true)
    }

    /// [`PolygonLight::sample`], keeping samples below the horizon of `at` unless
    /// `reject_below_horizon` (see [`AreaLight::sample_with`](super::AreaLight::sample_with)).
    pub fn sample_with(
        &self,
        at: &ShadingPoint,
        u: Vec2,
        sampling: LightSampling,
        reject_below_horizon: bool,
    ) -> Option<LightSample> {
        let n = self.polygon.normal();
        let strategy = Self::strategy(sampling);
        let point = if strategy == LightSampling::ProjectedSolidAngle {
            self.sample_projected(at, u)?
        } else if matches!(
            strategy,
            LightSampling::SolidAngle | LightSampling::SolidAngleCos
        ) {
            self.sample_solid_angle(at, u, strategy)?
        } else {
            let (y, _) = self.polygon.sample_rejection(&mut ReusedUniform::new(u));
            LightPoint {
                y,
                ny: n,
                pdf: uniform_area_pdf(at.p, y, n, self.polygon.area()),
            }
        };
        light_sample(at, point, reject_below_horizon, |_, w| self.emitted(w))
    }

    /// A triangle ∝ its solid angle, then a direction uniform in it (or a point uniform by
    /// area where its spherical triangle is unsafe).
    fn sample_solid_angle(
        &self,
        at: &ShadingPoint,
        u: Vec2,
        strategy: LightSampling,
    ) -> Option<LightPoint> {
        let total = self.total_solid_angle(at.p);
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let count = self.polygon.triangles().len();
        let mut target = u.x as f64 * total;
        let mut chosen = count - 1;
        for i in 0..count {
            let omega = self.solid_angle(at.p, i);
            if target < omega || i == count - 1 {
                chosen = i;
                target = (target / omega).clamp(0.0, 1.0);
                break;
            }
            target -= omega;
        }
        let u = Vec2::new(
            (target as f32).min(crate::sampling::sampler::ONE_MINUS_EPSILON),
            u.y,
        );
        let [a, b, c] = self.triangle(chosen);
        let n = self.polygon.normal();
        let y = match safe_spherical_triangle(at.p, a, b, c) {
            Some(st) => {
                let weights = cosine_weights(strategy, at, [a, b, c]);
                hit_plane(at.p, warped_sample(&st, weights, u).0, a, n)?
            }
            None => {
                let bary = square_to_triangle_sqrt(u);
                a + bary.x * (b - a) + bary.y * (c - a)
            }
        };
        Some(LightPoint {
            y,
            ny: n,
            pdf: self.solid_angle_pdf(at, y, n, strategy),
        })
    }

    /// Density per steradian at `at` of the direction towards `y` (a point of the polygon
    /// with normal `ny`) with strategy `sampling` (resolved for polygons).
    pub fn pdf(&self, at: &ShadingPoint, y: Vec3, ny: Vec3, sampling: LightSampling) -> f32 {
        let strategy = Self::strategy(sampling);
        if strategy == LightSampling::ProjectedSolidAngle {
            return match self.total_projected_solid_angle(at) {
                Some(total) => projected_density(at, y, total),
                None => 0.0,
            };
        }
        if !matches!(
            strategy,
            LightSampling::SolidAngle | LightSampling::SolidAngleCos
        ) {
            return uniform_area_pdf(at.p, y, ny, self.polygon.area());
        }
        self.solid_angle_pdf(at, y, ny, strategy)
    }

    /// Ω⊥ of triangle `i` above the horizon of `at` (zero when below
    /// [`MIN_PROJECTED_SOLID_ANGLE`](crate::sampling::warp::MIN_PROJECTED_SOLID_ANGLE)).
    fn projected_solid_angle(&self, at: &ShadingPoint, i: usize) -> f64 {
        visible_projected_solid_angle(&self.triangle(i).map(|v| v.as_dvec3()), at).unwrap_or(0.0)
    }

    /// ΣΩ⊥_i over the triangulation, or `None` when no triangle is visible from `at`.
    fn total_projected_solid_angle(&self, at: &ShadingPoint) -> Option<f64> {
        let total: f64 = (0..self.polygon.triangles().len())
            .map(|i| self.projected_solid_angle(at, i))
            .sum();
        (total > 0.0 && total.is_finite()).then_some(total)
    }

    /// `projected-solid-angle`: a triangle of the triangulation with probability
    /// Ω⊥_i/ΣΩ⊥ (u.x reused after the choice), then a direction ∝ cos θ in it; the
    /// triangles do not overlap, so the density is cos θ/ΣΩ⊥ over the whole polygon.
    fn sample_projected(&self, at: &ShadingPoint, u: Vec2) -> Option<LightPoint> {
        let total = self.total_projected_solid_angle(at)?;
        let count = self.polygon.triangles().len();
        let mut target = u.x as f64 * total;
        let mut chosen = None;
        for i in 0..count {
            let omega = self.projected_solid_angle(at, i);
            if omega > 0.0 {
                chosen = Some((i, (target / omega).clamp(0.0, 1.0)));
                if target < omega {
                    break;
                }
                target -= omega;
            }
        }
        let (i, reused) = chosen?;
        let vertices = self.triangle(i).map(|v| v.as_dvec3());
        let (x, n) = (at.p.as_dvec3(), at.n.as_dvec3());
        let triangle = ProjectedPolygon::new(x, n, &vertices)?;
        let w = triangle
            .sample(DVec2::new(reused.min(1.0 - f64::EPSILON), u.y as f64))
            .0;
        let y = hit_plane64(x, w, vertices[0], self.polygon.normal().as_dvec3())?.as_vec3();
        Some(LightPoint {
            y,
            ny: self.polygon.normal(),
            pdf: projected_density(at, y, total),
        })
    }

    /// The density of [`PolygonLight::sample_solid_angle`]: the triangle's choice
    /// probability Ω_i/ΣΩ times its own density 1/Ω_i (uniform) or warped/Ω_i.
    fn solid_angle_pdf(
        &self,
        at: &ShadingPoint,
        y: Vec3,
        ny: Vec3,
        strategy: LightSampling,
    ) -> f32 {
        let total = self.total_solid_angle(at.p);
        if !(total > 0.0 && total.is_finite()) {
            return 0.0;
        }
        let i = self.triangle_containing(y);
        let [a, b, c] = self.triangle(i);
        match safe_spherical_triangle(at.p, a, b, c) {
            Some(st) => match cosine_weights(strategy, at, [a, b, c]) {
                None => (1.0 / total) as f32,
                // (Ω_i/ΣΩ)·bilinear/Ω_i = bilinear/ΣΩ.
                weights => {
                    let warped = warped_pdf(&st, weights, (y - at.p).normalize());
                    (warped as f64 * st.solid_angle() as f64 / total) as f32
                }
            },
            None => {
                let choice = (self.solid_angle(at.p, i) / total) as f32;
                choice * uniform_area_pdf(at.p, y, ny, triangle_area(a, b, c))
            }
        }
    }

    /// The triangle of the triangulation that holds `y` (the one it is deepest inside, so
    /// points on shared edges get one answer).
    fn triangle_containing(&self, y: Vec3) -> usize {
        let depth = |i: usize| {
            let [a, b, c] = self.triangle(i);
            let bary = triangle_to_barycentrics(a, b, c, y);
            bary.x.min(bary.y).min(1.0 - bary.x - bary.y)
        };
        (0..self.polygon.triangles().len())
            .map(|i| (i, depth(i)))
            .fold((0, f32::NEG_INFINITY), |best, (i, d)| {
                if d > best.1 { (i, d) } else { best }
            })
            .0
    }
}
