//! Diffuse area emitters and their sampling strategies (area form of the rendering
//! integral: G·V·Le over the light's surface). One file per shape holds that shape's
//! strategies; this file holds the emitter, the strategy names, and the one place where
//! a sampled point becomes a [`LightSample`].
//!
//! Every strategy gives its density per steradian at the shading point; strategies that
//! draw points by area convert once, through [`area_to_solid_angle`](super::area_to_solid_angle).

mod cosine_warp;
mod disk;
mod projected;
mod rectangle;
mod sphere;
mod sphere_geometric;
pub(super) mod sphere_lanes;
mod strategies;
mod textured;
mod triangle;

pub(crate) use cosine_warp::{pdf as warped_pdf, sample as warped_sample};
pub(crate) use projected::{
    density as projected_density, hit_plane64, visible_projected_solid_angle,
};
pub use strategies::{EmitterKind, UnsupportedSampling, check_sampling, sampling_summary};
pub use textured::{EmissionTexture, UntexturableShape, uv_at as texture_uv_at};
pub(crate) use triangle::{cosine_weights, safe_spherical_triangle};

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::{LightSample, LightStrategy, ShadingPoint};
use crate::geometry::Shape;
use crate::math::{PI, Spectrum, spectrum::luminance};

pub use crate::settings::LightSampling;

/// A diffuse emitter on one shape (a mesh emits as one light per triangle), of constant
/// radiance or of a radiance texture.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// The emitting shape.
    pub shape: Shape,
    /// Emitted radiance (a factor on the texture's value when there is one).
    pub radiance: Spectrum,
    /// Emits from both sides (default: only the front, the side of the normal).
    pub two_sided: bool,
    /// A radiance texture and its sampling grid.
    pub texture: Option<Arc<EmissionTexture>>,
}

/// A point drawn on a light: the point, its geometric normal and the density per
/// steradian at the shading point of the direction towards it.
#[derive(Clone, Copy, Debug)]
pub struct LightPoint {
    /// The point on the light.
    pub y: Vec3,
    /// Geometric normal at `y`.
    pub ny: Vec3,
    /// Density per steradian at the shading point.
    pub pdf: f32,
}

/// Density per steradian at `x` of a point `y` (normal `ny`) drawn uniformly over an area
/// `area`: p_ω = (1/A)·|x − y|²/|cos θy|.
#[inline]
pub fn uniform_area_pdf(x: Vec3, y: Vec3, ny: Vec3, area: f32) -> f32 {
    area_pdf_to_solid_angle(x, y, ny, 1.0 / area)
}

/// Density per steradian at `x` of a point `y` (normal `ny`) drawn with density
/// `pdf_area` per unit area.
#[inline]
fn area_pdf_to_solid_angle(x: Vec3, y: Vec3, ny: Vec3, pdf_area: f32) -> f32 {
    let d = y - x;
    let dist2 = d.length_squared();
    if dist2.is_nan() || dist2 <= 0.0 {
        return 0.0;
    }
    super::area_to_solid_angle(pdf_area, dist2, ny.dot(d) / dist2.sqrt())
}

/// Radiance a diffuse emitter of radiance `l` sends from a point with normal `n` in
/// direction `w`: `l` on the front side (or both sides when `two_sided`), else zero.
#[inline]
pub(crate) fn diffuse_emitted(l: Spectrum, two_sided: bool, n: Vec3, w: Vec3) -> Spectrum {
    if two_sided || n.dot(w) > 0.0 {
        l
    } else {
        Spectrum::ZERO
    }
}

/// Power Φ = π·L·A of a diffuse emitter (×2 when two-sided), as luminance.
pub(crate) fn diffuse_power(l: Spectrum, two_sided: bool, area: f32) -> f32 {
    let sides = if two_sided { 2.0 } else { 1.0 };
    sides * PI * luminance(l) * area
}

/// Where the ray x + t·w (t > 0) meets the plane through `o` with normal `n`.
#[inline]
pub(crate) fn hit_plane(x: Vec3, w: Vec3, o: Vec3, n: Vec3) -> Option<Vec3> {
    let t = (o - x).dot(n) / w.dot(n);
    (t > 0.0 && t.is_finite()).then(|| x + t * w)
}

impl AreaLight {
    /// The strategy in use when `sampling` is asked for: resolved for this shape (on a
    /// textured emitter by [`LightSampling::resolve_textured`]; there `area` samples ∝
    /// emitted power).
    #[inline]
    pub fn strategy(&self, sampling: LightSampling) -> LightSampling {
        sampling.resolve_for(EmitterKind::of(&self.shape), self.texture.is_some())
    }

    /// Radiance leaving the point `y` (normal `ny`) in direction `w`.
    #[inline]
    pub fn emitted(&self, y: Vec3, ny: Vec3, w: Vec3) -> Spectrum {
        let l = diffuse_emitted(self.radiance, self.two_sided, ny, w);
        match &self.texture {
            Some(t) if l != Spectrum::ZERO => l * t.eval(&self.shape, y),
            _ => l,
        }
    }

    /// The radiance averaged over the surface (the constant radiance when untextured).
    pub fn mean_radiance(&self) -> Spectrum {
        match &self.texture {
            Some(t) => self.radiance * t.mean(),
            None => self.radiance,
        }
    }

    /// Power Φ = π·L̄·A (×2 when two-sided), as luminance.
    pub fn power(&self) -> f32 {
        diffuse_power(self.mean_radiance(), self.two_sided, self.shape.area())
    }

    /// Samples a point on the light with strategy `sampling` (resolved for the shape) and
    /// returns it as a direction from `at`. Checks the horizon at both ends (cos θ ≤ 0 at the shading
    /// point or at the light) before any shadow ray is traced: such samples carry no
    /// light. The returned pdf equals [`AreaLight::pdf`] at the sampled point.
    #[inline]
    pub fn sample(
        &self,
        at: &ShadingPoint,
        u: Vec2,
        sampling: LightSampling,
    ) -> Option<LightSample> {
        self.sample_with(at, u, LightStrategy::from(sampling))
    }

    /// [`AreaLight::sample`] with the whole render strategy: samples below the horizon
    /// of `at` are kept (for the estimator to score zero after its shadow ray) unless
    /// `horizon_rejection`, and `fast_paths` picks the f32 fast paths where a shape has
    /// one.
    #[inline]
    pub fn sample_with(
        &self,
        at: &ShadingPoint,
        u: Vec2,
        render: LightStrategy,
    ) -> Option<LightSample> {
        let reject_below_horizon = render.horizon_rejection;
        let strategy = self.strategy(render.sampling);
        let point = match (&self.shape, &self.texture) {
            (shape, Some(t)) if strategy == LightSampling::Area => {
                let (y, ny, pdf_area) = t.sample(shape, u)?;
                LightPoint {
                    y,
                    ny,
                    pdf: area_pdf_to_solid_angle(at.p, y, ny, pdf_area),
                }
            }
            (Shape::Sphere(s), _) => sphere::sample(s, strategy, at, u)?,
            (Shape::Rectangle(r), _) => rectangle::sample(r, strategy, render.fast_paths, at, u)?,
            (Shape::Triangle(t), _) => {
                let best = render.sampling == LightSampling::Best;
                triangle::sample(t, (strategy, best), render.fast_paths, at, u)?
            }
            (Shape::Disk(d), _) => disk::sample(d, strategy, at, u)?,
        };
        let y = point.y;
        light_sample(at, point, reject_below_horizon, |ny, w| {
            self.emitted(y, ny, w)
        })
    }

    /// Density per steradian at `at` of choosing the direction towards `y` (a point on
    /// this light with geometric normal `ny`) with strategy `sampling`.
    #[inline]
    pub fn pdf(&self, at: &ShadingPoint, y: Vec3, ny: Vec3, sampling: LightSampling) -> f32 {
        self.pdf_with(at, y, ny, LightStrategy::from(sampling))
    }

    /// [`AreaLight::pdf`] under the whole render strategy (its `fast_paths` as in
    /// [`AreaLight::sample_with`]).
    #[inline]
    pub fn pdf_with(&self, at: &ShadingPoint, y: Vec3, ny: Vec3, render: LightStrategy) -> f32 {
        let strategy = self.strategy(render.sampling);
        if let (Some(t), LightSampling::Area) = (&self.texture, strategy) {
            return area_pdf_to_solid_angle(at.p, y, ny, t.pdf(&self.shape, y));
        }
        match &self.shape {
            Shape::Sphere(s) => sphere::pdf(s, strategy, at, y, ny),
            Shape::Rectangle(r) => rectangle::pdf(r, strategy, render.fast_paths, at, y, ny),
            Shape::Triangle(t) => {
                let best = render.sampling == LightSampling::Best;
                triangle::pdf(t, (strategy, best), render.fast_paths, at, y, ny)
            }
            Shape::Disk(d) => disk::pdf(d, strategy, at, y, ny),
        }
    }
}

/// Turns a point drawn on a light into a [`LightSample`] at `at`, or `None` when it
/// carries no light: below the horizon of `at` (if `reject_below_horizon`; lecture:
/// check cos θ₁ < 0 before evaluating visibility), emitting away from `at`
/// (`emitted(ny, −w_in)` is zero), or a degenerate density.
#[inline]
pub(crate) fn light_sample(
    at: &ShadingPoint,
    point: LightPoint,
    reject_below_horizon: bool,
    emitted: impl Fn(Vec3, Vec3) -> Spectrum,
) -> Option<LightSample> {
    let LightPoint { y, ny, pdf } = point;
    let d = y - at.p;
    let dist2 = d.length_squared();
    if dist2.is_nan() || dist2 <= 0.0 {
        return None;
    }
    let distance = dist2.sqrt();
    let w_in = d / distance;
    let radiance = emitted(ny, -w_in);
    if (reject_below_horizon && at.n.dot(w_in) <= 0.0) || radiance == Spectrum::ZERO {
        return None;
    }
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
