//! Light sources: diffuse area emitters on shapes and point lights; light selection for
//! many lights. Knows nothing of the renderer; the integrators ask lights for samples
//! and densities at a shading point.

mod area;
pub mod environment;
mod lanes;
mod point;
mod polygon;
pub mod select;

pub use area::{
    AreaLight, EmissionTexture, EmitterKind, LightPoint, LightSampling, UnsupportedSampling,
    UntexturableShape, check_sampling, sampling_summary, texture_uv_at, uniform_area_pdf,
};
pub use environment::Environment;
pub use lanes::{KERNELS, LaneJob, LightLanes};
pub use point::PointLight;
pub use polygon::PolygonLight;
pub use select::LightBounds;

use glam::{Vec2, Vec3};

use crate::math::Spectrum;
pub use crate::settings::LightStrategy;

/// What a light needs to know of the point it illuminates.
#[derive(Clone, Copy, Debug)]
pub struct ShadingPoint {
    /// Position.
    pub p: Vec3,
    /// Geometric normal (for ray offsets).
    pub ng: Vec3,
    /// Shading normal (for the cosine term and the horizon test).
    pub n: Vec3,
}

/// Light arriving at a shading point. `pdf` is per unit solid angle at that point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the shading point towards the light.
    pub w_in: Vec3,
    /// Distance to the sampled point.
    pub distance: f32,
    /// Emitted radiance towards the shading point.
    pub radiance: Spectrum,
    /// Density per steradian (Dirac weight 1 for delta lights).
    pub pdf: f32,
    /// The sample came from a delta distribution (point light).
    pub delta: bool,
    /// The point on the light.
    pub point: Vec3,
    /// Geometric normal of the light at `point` (zero for point lights).
    pub normal: Vec3,
}

/// Converts a density per unit area at `y` into a density per steradian at `x`:
/// p_ω = p_A · |x − y|² / |cos θ_y| (the change of variables between the area and the
/// directional forms of the rendering integral). Zero when the light is seen edge-on.
#[inline]
pub fn area_to_solid_angle(pdf_area: f32, distance_squared: f32, cos_theta_y: f32) -> f32 {
    let c = cos_theta_y.abs();
    if c <= 0.0 {
        0.0
    } else {
        pdf_area * distance_squared / c
    }
}

/// A light source of the scene (a closed set: one `match` per call).
#[derive(Clone, Debug)]
pub enum Light {
    /// A diffuse emitter on a shape.
    Area(AreaLight),
    /// A point light.
    Point(PointLight),
    /// Light from infinitely far away: an environment map or a constant.
    Environment(Environment),
    /// A diffuse emitter on a planar polygon (its geometry is its triangulation).
    Polygon(PolygonLight),
}

impl Light {
    /// Draws a direction towards the light from `at` with `strategy`; `None` when the
    /// sample carries no light (behind the emitter, below the horizon of `at`, or a
    /// degenerate case).
    #[inline]
    pub fn sample(
        &self,
        at: &ShadingPoint,
        u: Vec2,
        strategy: LightStrategy,
    ) -> Option<LightSample> {
        match self {
            Light::Area(l) => l.sample_with(at, u, strategy),
            Light::Point(l) => l.sample(at),
            Light::Environment(e) => {
                let (w_in, radiance, pdf) = e.sample(u, strategy.env_compensation)?;
                // Horizon rejection before the shadow ray, as for area lights.
                (at.n.dot(w_in) > 0.0 && at.ng.dot(w_in) > 0.0).then_some(LightSample {
                    w_in,
                    distance: f32::INFINITY,
                    radiance,
                    pdf,
                    delta: false,
                    point: at.p + w_in,
                    normal: -w_in,
                })
            }
            Light::Polygon(l) => {
                l.sample_with(at, u, strategy.sampling, strategy.horizon_rejection)
            }
        }
    }

    /// For a light at infinity: density per steradian of sampling direction `w` (unit,
    /// towards the light) with `strategy`. Zero for other lights, which a direction alone
    /// cannot name.
    #[inline]
    pub fn infinite_pdf(&self, w: Vec3, strategy: LightStrategy) -> f32 {
        match self {
            Light::Environment(e) => e.pdf(w, strategy.env_compensation),
            _ => 0.0,
        }
    }

    /// For a light at infinity: radiance arriving from direction `w` (a ray that escapes
    /// the scene along `w`). Zero for other lights.
    #[inline]
    pub fn infinite_radiance(&self, w: Vec3) -> Spectrum {
        match self {
            Light::Environment(e) => e.eval(w),
            _ => Spectrum::ZERO,
        }
    }

    /// [`Light::infinite_radiance`] and [`Light::infinite_pdf`] together (one lookup of
    /// the direction in an environment map).
    #[inline]
    pub fn infinite_radiance_pdf(&self, w: Vec3, strategy: LightStrategy) -> (Spectrum, f32) {
        match self {
            Light::Environment(e) => e.eval_pdf(w, strategy.env_compensation),
            _ => (Spectrum::ZERO, 0.0),
        }
    }

    /// True when `strategy` leaves this light nothing to draw: an environment with
    /// nothing above its mean under MIS compensation
    /// (no [`Environment::has_compensation`]). Its light samples would all be empty, so
    /// light selection gives it probability zero ([`select::Selector::without_silent`]).
    pub fn draws_no_samples(&self, strategy: LightStrategy) -> bool {
        matches!(self, Light::Environment(e) if strategy.env_compensation && !e.has_compensation())
    }

    /// True for lights at infinity (no point to aim a shadow segment at).
    #[inline]
    pub fn is_infinite(&self) -> bool {
        matches!(self, Light::Environment(_))
    }

    /// Density per steradian at `at` of sampling the direction towards `y` (a point on
    /// this light with geometric normal `ny`) with `strategy`. Zero for delta lights.
    #[inline]
    pub fn pdf(&self, at: &ShadingPoint, y: Vec3, ny: Vec3, strategy: LightStrategy) -> f32 {
        match self {
            Light::Area(l) => l.pdf_with(at, y, ny, strategy),
            Light::Point(_) => 0.0,
            Light::Environment(e) => e.pdf((y - at.p).normalize(), strategy.env_compensation),
            Light::Polygon(l) => l.pdf(at, y, ny, strategy.sampling),
        }
    }

    /// Radiance emitted from the point `y` with normal `ny` in direction `w` (away from
    /// it).
    #[inline]
    pub fn emitted(&self, y: Vec3, ny: Vec3, w: Vec3) -> Spectrum {
        match self {
            Light::Area(l) => l.emitted(y, ny, w),
            Light::Point(_) | Light::Environment(_) => Spectrum::ZERO,
            Light::Polygon(l) => l.emitted(w),
        }
    }

    /// Emitted power Φ (luminance of the RGB power), for selection by power.
    pub fn power(&self) -> f32 {
        match self {
            Light::Area(l) => l.power(),
            Light::Point(l) => l.power(),
            Light::Environment(e) => e.power(),
            Light::Polygon(l) => l.power(),
        }
    }

    /// True for delta lights, which directional strategies can never hit.
    pub fn is_delta(&self) -> bool {
        matches!(self, Light::Point(_))
    }
}
