//! Sphere emitters: the lecture's four strategies.
//! - `area` (p₁ = 1/A over the whole sphere; half the points face away and carry no light);
//! - `visible-area` (p₂ = 1/A_cap over the cap visible from the shading point, of area
//!   2πr²(1 − r/D) at distance D from the centre);
//! - `solid-angle` (p₃ = 1/Ω uniform in the cone of half-angle θmax, sin θmax = r/D;
//!   pbrt-v4 §6.2.4);
//! - `geometric` (p₄ ∝ cos θx·cos θy/d², see [`super::sphere_geometric`]).
//!
//! From inside the sphere (D ≤ r) no cap or cone exists and every strategy is `area`;
//! `sample` and `pdf` make that choice from the shading point alone, so they agree.

use glam::{Vec2, Vec3};

use super::sphere_geometric::ProjectedCone;
use super::{LightPoint, LightSampling, uniform_area_pdf};
use crate::geometry::shape::Sphere;
use crate::light::ShadingPoint;
use crate::math::{Frame, PI};
use crate::sampling::warp::{square_to_uniform_cone, square_to_uniform_sphere, uniform_cone_pdf};

/// Slack of the visible-cap test on points handed to `pdf` (they come from rounding-prone
/// ray hits near the silhouette).
pub(super) const CAP_SLACK: f32 = 1e-3;

/// The sphere seen from outside: direction from the centre to the shading point and the
/// ratio r/D.
#[derive(Clone, Copy, Debug)]
struct View {
    /// Unit vector from the centre towards the shading point (the cap's axis).
    b: Vec3,
    /// r/D = sin θmax.
    ratio: f32,
}

impl View {
    /// `None` from inside or on the sphere.
    fn new(s: &Sphere, x: Vec3) -> Option<View> {
        let d = x - s.center;
        let distance = d.length();
        let ratio = s.radius / distance;
        (ratio < 1.0 - 1e-5 && ratio.is_finite()).then(|| View {
            b: d / distance,
            ratio,
        })
    }

    /// 1 − cos θmax = (r/D)²/(1 + cos θmax), exact for small spheres.
    fn one_minus_cos_max(&self) -> f32 {
        let sin2 = self.ratio * self.ratio;
        sin2 / (1.0 + (1.0 - sin2).sqrt())
    }

    /// Whether the point with unit normal `ny` is on the visible cap.
    fn sees(&self, ny: Vec3) -> bool {
        ny.dot(self.b) >= self.ratio - CAP_SLACK
    }

    /// The `solid-angle` density of a point on the visible cap: the cone's constant
    /// 1/(2π(1 − cos θmax)), as the warp computes it.
    fn cone_pdf(&self) -> f32 {
        uniform_cone_pdf(Vec3::Z, 1.0 - self.one_minus_cos_max())
    }
}

/// A uniform point on the whole sphere and its outward normal.
#[inline]
pub(super) fn sample_area(s: &Sphere, u: Vec2) -> (Vec3, Vec3) {
    let (n, _) = square_to_uniform_sphere(u);
    (s.center + s.radius * n, n)
}

/// The strategy that applies at `x`: `area` from inside, else the resolved one.
fn effective(s: &Sphere, strategy: LightSampling, x: Vec3) -> Option<(View, LightSampling)> {
    match strategy {
        LightSampling::Area => None,
        _ => View::new(s, x).map(|v| (v, strategy)),
    }
}

/// The first point where the ray x + t·w meets the sphere, for w inside the cone the
/// sphere subtends (rounding near the silhouette is clamped to the tangent point).
fn cone_hit(s: &Sphere, x: Vec3, w: Vec3) -> (Vec3, Vec3) {
    let to_center = s.center - x;
    let along = w.dot(to_center);
    // Distance² from the centre to the ray's line, computed from the perpendicular part.
    let perp2 = (to_center - along * w).length_squared();
    let t = along - (s.radius * s.radius - perp2).max(0.0).sqrt();
    let y = x + t * w;
    let ny = ((y - s.center) / s.radius).normalize_or_zero();
    (s.center + s.radius * ny, ny)
}

/// The projected cone of the `geometric` strategy at `at`.
fn projected_cone(view: &View, at: &ShadingPoint) -> Option<ProjectedCone> {
    ProjectedCone::new(-view.b, at.n, view.one_minus_cos_max() as f64)
}

/// Draws a point of `s` with `strategy`.
pub(super) fn sample(
    s: &Sphere,
    strategy: LightSampling,
    at: &ShadingPoint,
    u: Vec2,
) -> Option<LightPoint> {
    let Some((view, strategy)) = effective(s, strategy, at.p) else {
        let (y, ny) = sample_area(s, u);
        return Some(LightPoint {
            y,
            ny,
            pdf: uniform_area_pdf(at.p, y, ny, s.area()),
        });
    };
    let (y, ny) = match strategy {
        LightSampling::VisibleArea => {
            // Uniform on the cap cos α ∈ [r/D, 1] around b (Archimedes: uniform in cos α).
            let (local, _) = square_to_uniform_cone(u, view.ratio);
            let ny = Frame::from_normal(view.b).to_world(local);
            (s.center + s.radius * ny, ny)
        }
        LightSampling::Geometric => {
            let (w, _) = projected_cone(&view, at)?.sample(u)?;
            cone_hit(s, at.p, w)
        }
        _ => {
            let cos_max = 1.0 - view.one_minus_cos_max();
            let (local, _) = square_to_uniform_cone(u, cos_max);
            let w = Frame::from_normal(-view.b).to_world(local);
            let (y, ny) = cone_hit(s, at.p, w);
            // `pdf`'s value for this point from the view already at hand (`pdf` would
            // find the view again, a chain of two square roots and three divisions).
            let pdf = if view.sees(ny) { view.cone_pdf() } else { 0.0 };
            return Some(LightPoint { y, ny, pdf });
        }
    };
    // The density of the point, by the one pdf function.
    let pdf = pdf(s, strategy, at, y, ny);
    Some(LightPoint { y, ny, pdf })
}

/// Density per steradian at `at` of the direction towards `y` (normal `ny`) on `s`.
pub(super) fn pdf(
    s: &Sphere,
    strategy: LightSampling,
    at: &ShadingPoint,
    y: Vec3,
    ny: Vec3,
) -> f32 {
    let Some((view, strategy)) = effective(s, strategy, at.p) else {
        return uniform_area_pdf(at.p, y, ny, s.area());
    };
    if !view.sees(ny) {
        return 0.0;
    }
    match strategy {
        LightSampling::VisibleArea => {
            // Cap area 2πr²(1 − r/D).
            let cap = 2.0 * PI * s.radius * s.radius * (1.0 - view.ratio);
            uniform_area_pdf(at.p, y, ny, cap)
        }
        LightSampling::Geometric => match projected_cone(&view, at) {
            Some(cone) => cone.pdf((y - at.p).normalize_or_zero()),
            None => 0.0,
        },
        _ => view.cone_pdf(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strategies_from_inside_fall_back_to_area() {
        let s = Sphere::new(Vec3::ZERO, 1.0);
        let at = ShadingPoint {
            p: Vec3::new(0.0, 0.0, 0.5),
            ng: Vec3::Z,
            n: Vec3::Z,
        };
        for strategy in [
            LightSampling::VisibleArea,
            LightSampling::SolidAngle,
            LightSampling::Geometric,
        ] {
            let point = sample(&s, strategy, &at, Vec2::new(0.3, 0.4)).expect("point");
            let area = uniform_area_pdf(at.p, point.y, point.ny, s.area());
            assert_eq!(point.pdf, area);
        }
    }
}
