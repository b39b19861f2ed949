//! Directions in a convex planar polygon seen from a shading point, with density
//! proportional to cos θ (the *projected* solid angle), exactly: p(ω) = cos θ / Ω⊥.
//! For a Lambertian receiver under a constant emitter the unoccluded estimate is then
//! the same for every sample (the lecture's "p ∝ G" for planar lights).
//!
//! The construction follows the idea of Peters 2021 ("BRDF Importance Sampling for
//! Polygonal Lights", ACM TOG 40(4)): by Nusselt's analogue, uniform points in the
//! polygon's orthographic projection onto the tangent disk are cos-distributed
//! directions (Malley). The polygon is clipped to the upper hemisphere first (the
//! lecture's horizon, exactly: nothing is drawn below it). Each edge is a great-circle
//! arc whose projection is an ellipse arc around the origin, and the sector between
//! the origin and the projection of an arc of length s on a great circle with unit
//! normal n has area ½·n_z·s (Green's theorem; summed over the edges this is Lambert's
//! form-factor formula Ω⊥ = ½ Σ n_z,i θ_i). So the marginal in azimuth φ has a CDF
//! made of arc lengths, and at each φ the projected region is the radial interval
//! [r_in(φ), r_out(φ)] between an inner and an outer edge (r_in = 0 when the zenith is
//! inside), where r² = n_z² / (n_z² + (n·d)²) for the direction d of azimuth φ.
//!
//! Sampling inverts the CDF: u.x picks an azimuth interval between vertex azimuths and
//! then φ inside it — in closed form along the outer great circle when there is no inner
//! edge, otherwise by safeguarded Newton iteration on the CDF (its derivative is
//! ½(r_out² − r_in²) ≥ 0) — and u.y places r² uniformly in [r_in², r_out²]. All in f64.

use glam::{DVec2, DVec3};

use super::spherical_triangle::angle_between;

mod horizon;

pub use horizon::projected_solid_angle;
use horizon::{Frame64, clipped_directions};

/// Most vertices a polygon may have here (a quad gains one when clipped at the horizon).
pub const MAX_PROJECTED_VERTICES: usize = 8;

/// Below this projected solid angle (sr) a polygon is treated as invisible: it could
/// contribute at most L·10⁻¹² of irradiance.
pub const MIN_PROJECTED_SOLID_ANGLE: f64 = 1e-12;

/// One edge seen as a boundary in azimuth: its great circle's unit normal.
#[derive(Clone, Copy, Debug)]
struct Edge {
    normal: DVec3,
}

impl Edge {
    /// The point of this edge's great circle (upper half) at the azimuth of the unit
    /// vector `d` of the xy-plane.
    fn point_at(&self, d: DVec2) -> DVec3 {
        let n = self.normal;
        let nd = n.x * d.x + n.y * d.y;
        let nz = n.z.abs();
        // On the circle: n·w = 0 with w = α·d + β·ẑ, α ≥ 0 → w ∝ |n_z|·d − sgn(n_z)(n·d)·ẑ.
        // A meridian at its own azimuth (n_z = n·d = 0) is taken at the zenith, r = 0.
        (DVec3::new(nz * d.x, nz * d.y, -n.z.signum() * nd))
            .try_normalize()
            .unwrap_or(DVec3::Z)
    }

    /// Area of the projected sector under this edge's great circle from its point `p`
    /// to its point `q`: ½|n_z|·(arc length).
    fn sector(&self, p: DVec3, q: DVec3) -> f64 {
        0.5 * self.normal.z.abs() * angle_between(p, q)
    }
}

/// An azimuth interval [lo, lo + width) with the edges bounding the region over it.
#[derive(Clone, Copy, Debug)]
struct Interval {
    /// Start and width in pseudo-azimuth (see [`pseudo_azimuth`]) from the outline's
    /// start vertex (the intervals are built in this order; the tests read them).
    #[cfg_attr(not(test), allow(dead_code))]
    lo: f64,
    #[cfg_attr(not(test), allow(dead_code))]
    width: f64,
    /// Unit xy-directions of the azimuths lo and lo + width.
    d_lo: DVec2,
    /// Area of the region over the interval.
    area: f64,
    outer: Edge,
    /// The outer boundary's point at `lo`, and the arc length it runs across the interval.
    p_outer: DVec3,
    arc_outer: f64,
    /// The inner edge and its point at `lo`; `None` where the region reaches the origin
    /// (the zenith).
    inner: Option<(Edge, DVec3)>,
}

/// Azimuth steps (in pseudo-angle, half a turn = 2) at most this small are meridian
/// edges seen through rounding: no interval is cut there.
const MIN_AZIMUTH_STEP: f64 = 1e-12;

/// The inversion stops when the area it reached is within this fraction of the
/// interval's area of the target: far below what an f32 direction resolves.
const NEWTON_TOLERANCE: f64 = 1e-10;

/// Most Newton steps of the inversion (it converges in a few; bisection is the fallback).
const MAX_NEWTON_STEPS: usize = 60;

/// A convex polygon seen from a shading point, ready for sampling ∝ cos θ.
#[derive(Clone, Debug)]
pub struct ProjectedPolygon {
    frame: Frame64,
    /// The clipped outline, unit directions in the local frame, counter-clockwise.
    outline: [DVec3; MAX_PROJECTED_VERTICES],
    len: usize,
    intervals: [Interval; MAX_PROJECTED_VERTICES],
    count: usize,
    /// Ω⊥, the sampler's normaliser.
    projected_solid_angle: f64,
    /// The vertex the pseudo-azimuths are counted from, and whether the outline winds
    /// around the zenith (then they run over [0, 4), else over (−2, 2)); for the tests.
    #[cfg_attr(not(test), allow(dead_code))]
    start: DVec3,
    #[cfg_attr(not(test), allow(dead_code))]
    around_zenith: bool,
}

/// A pseudo-angle of the xy-part of `d`: monotone in the azimuth φ over [−π/2, 3π/2),
/// with values in [−1, 3) and a(φ + π) = a(φ) + 2, so steps of less than half a turn
/// stay below 2 and unwrap like angles, without trigonometry.
fn pseudo_azimuth(d: DVec3) -> f64 {
    let p = d.y / (d.x.abs() + d.y.abs());
    if d.x >= 0.0 { p } else { 2.0 - p }
}

/// The signed pseudo-angle step from the azimuth of `a` to that of `b`, in (−2, 2]
/// (half a turn is 2).
fn azimuth_step(a: DVec3, b: DVec3) -> f64 {
    let step = pseudo_azimuth(b) - pseudo_azimuth(a);
    if step > 2.0 {
        step - 4.0
    } else if step <= -2.0 {
        step + 4.0
    } else {
        step
    }
}

/// Six times the signed volume of the cone over the outline: positive when it runs
/// counter-clockwise seen from outside the sphere (a fan of triple products).
fn orientation(v: &[DVec3]) -> f64 {
    (1..v.len() - 1)
        .map(|i| v[0].dot(v[i].cross(v[i + 1])))
        .sum()
}

impl ProjectedPolygon {
    /// The convex polygon `vertices` (world space, in order, either orientation, at most
    /// [`MAX_PROJECTED_VERTICES`] − 1) seen from `x` with unit normal `n`; `None` when
    /// its part above the horizon has Ω⊥ below [`MIN_PROJECTED_SOLID_ANGLE`].
    pub fn new(x: DVec3, n: DVec3, vertices: &[DVec3]) -> Option<ProjectedPolygon> {
        let frame = Frame64::new(n);
        let (mut v, len) = clipped_directions(&frame, x, vertices);
        let v = &mut v[..len];
        if len == 0 {
            return None;
        }
        if orientation(v) < 0.0 {
            v.reverse();
        }
        // Each edge's azimuth span (a, b), unwrapped along the outline from a vertex with
        // an azimuth (a > b on inner edges). A vertex at the zenith has no azimuth: the
        // edge leaving it spans the wedge at the origin, where r = 0 (its n_z is 0).
        let has_azimuth = |d: DVec3| d.x * d.x + d.y * d.y > 1e-28;
        let start = (0..len).find(|&i| has_azimuth(v[i]))?;
        let xy = |d: DVec3| DVec2::new(d.x, d.y).normalize();
        let mut spans = [((0.0f64, DVec2::X), (0.0f64, DVec2::X)); MAX_PROJECTED_VERTICES];
        let (mut acc, mut last) = (0.0, v[start]);
        for step in 0..len {
            let i = (start + step) % len;
            let j = (i + 1) % len;
            let a = (acc, xy(last));
            if has_azimuth(v[j]) {
                // An edge in a plane through the normal (a meridian) keeps its azimuth;
                // rounding would give it a step of either sign.
                let step = azimuth_step(last, v[j]);
                if step.abs() > MIN_AZIMUTH_STEP {
                    acc += step;
                    last = v[j];
                }
            }
            spans[i] = (a, (acc, xy(last)));
        }
        // Back at the start the azimuth has turned by 2π (4) around the zenith, else by 0.
        let contains_zenith = acc > 2.0;
        let mut outline = [DVec3::ZERO; MAX_PROJECTED_VERTICES];
        outline[..len].copy_from_slice(v);
        let mut polygon = ProjectedPolygon {
            frame,
            outline,
            len,
            intervals: [Interval::EMPTY; MAX_PROJECTED_VERTICES],
            count: 0,
            projected_solid_angle: 0.0,
            start: v[start],
            around_zenith: contains_zenith,
        };
        let edge = |i: usize| {
            let c = v[i].cross(v[(i + 1) % len]);
            c.try_normalize().map(|normal| Edge { normal })
        };
        // Breakpoints: the vertices' azimuths, sorted, with their xy-directions.
        let mut breaks = [(0.0f64, DVec2::X); MAX_PROJECTED_VERTICES + 1];
        let mut nb = 0;
        for &(a, b) in &spans[..len] {
            for t in [a, b] {
                if !breaks[..nb].iter().any(|x| x.0 == t.0) && nb < breaks.len() {
                    breaks[nb] = t;
                    nb += 1;
                }
            }
        }
        let breaks = &mut breaks[..nb];
        breaks.sort_by(|a, b| a.0.total_cmp(&b.0));

        let mut cumulative = 0.0;
        for w in breaks.windows(2) {
            let ((lo, d_lo), (hi, d_hi)) = (w[0], w[1]);
            let mid = 0.5 * (lo + hi);
            let covering = |outer: bool| {
                (0..len).find_map(|i| {
                    let ((a, _), (b, _)) = spans[i];
                    let hit = if outer {
                        a < b && a <= mid && mid <= b
                    } else {
                        b < a && b <= mid && mid <= a
                    };
                    if hit { Some(edge(i)) } else { None }
                })
            };
            let Some(Some(outer)) = covering(true) else {
                continue;
            };
            let inner = if contains_zenith {
                None
            } else {
                covering(false).flatten().filter(|e| e.normal.z != 0.0)
            };
            let interval = Interval::new(lo, hi - lo, (d_lo, d_hi), outer, inner);
            if !(interval.area > 0.0 && interval.area.is_finite()) {
                continue;
            }
            cumulative += interval.area;
            if polygon.count < polygon.intervals.len() {
                polygon.intervals[polygon.count] = interval;
                polygon.count += 1;
            }
        }
        // Ω⊥ as the sum of the intervals' areas (Lambert's formula up to rounding).
        polygon.projected_solid_angle = cumulative;
        (cumulative >= MIN_PROJECTED_SOLID_ANGLE && cumulative.is_finite()).then_some(polygon)
    }

    /// Ω⊥, the projected solid angle of the part above the horizon.
    pub fn projected_solid_angle(&self) -> f64 {
        self.projected_solid_angle
    }

    /// A world-space unit direction ∝ cos θ in the polygon, and its density per
    /// steradian (cos θ / Ω⊥).
    pub fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let intervals = || self.intervals[..self.count].iter();
        let mut target = u.x * self.projected_solid_angle;
        let mut chosen = None;
        for interval in intervals() {
            chosen = Some(interval);
            if target < interval.area {
                break;
            }
            target -= interval.area;
        }
        let interval = chosen.expect("a projected polygon has an interval");
        let target = target.clamp(0.0, interval.area);
        let (d, r_out2, r_in2) = interval.invert(target);
        let r2 = (r_in2 + u.y * (r_out2 - r_in2)).clamp(0.0, 1.0);
        let r = r2.sqrt();
        let local = DVec3::new(r * d.x, r * d.y, (1.0 - r2).max(0.0).sqrt());
        (self.frame.to_world(local), self.pdf_local(local.z))
    }

    /// Density per steradian of [`ProjectedPolygon::sample`] for a world direction `w`:
    /// cos θ / Ω⊥ inside the clipped polygon, zero outside it.
    pub fn pdf(&self, w: DVec3) -> f64 {
        let local = self.frame.to_local(w);
        let v = &self.outline[..self.len];
        let inside = (0..v.len()).all(|i| v[i].cross(v[(i + 1) % v.len()]).dot(local) >= 0.0);
        if inside { self.pdf_local(local.z) } else { 0.0 }
    }

    fn pdf_local(&self, cos_theta: f64) -> f64 {
        cos_theta.max(0.0) / self.projected_solid_angle
    }
}

impl Interval {
    /// A placeholder for unused slots.
    const EMPTY: Interval = Interval {
        lo: 0.0,
        width: 0.0,
        d_lo: DVec2::X,
        area: 0.0,
        outer: Edge { normal: DVec3::Z },
        p_outer: DVec3::Z,
        arc_outer: 0.0,
        inner: None,
    };

    fn new(
        lo: f64,
        width: f64,
        (d_lo, d_hi): (DVec2, DVec2),
        outer: Edge,
        inner: Option<Edge>,
    ) -> Interval {
        let p_outer = outer.point_at(d_lo);
        let mut interval = Interval {
            lo,
            width,
            d_lo,
            area: 0.0,
            outer,
            p_outer,
            arc_outer: angle_between(p_outer, outer.point_at(d_hi)),
            inner: inner.map(|e| (e, e.point_at(d_lo))),
        };
        interval.area = interval.area_until(d_hi);
        interval
    }

    /// Area of the region between `lo` and the azimuth of `d`: the outer edge's sector
    /// minus the inner edge's.
    fn area_until(&self, d: DVec2) -> f64 {
        let outer = self.outer.sector(self.p_outer, self.outer.point_at(d));
        outer - self.inner.map_or(0.0, |(e, p)| e.sector(p, e.point_at(d)))
    }

    /// The outer boundary's point an arc length `s` past `p_outer`, towards larger φ.
    fn outer_point(&self, s: f64) -> DVec3 {
        let n = self.outer.normal;
        let tangent = n.cross(self.p_outer) * n.z.signum();
        let (sin, cos) = s.sin_cos();
        self.p_outer * cos + tangent * sin
    }

    /// The azimuth (as a unit xy-direction) where the area over [lo, φ] is `target`,
    /// with r_out² and r_in² there. Parametrised by the arc length s along the outer
    /// edge, whose sector grows as ½|n_z|·s: closed form without an inner edge, else
    /// Newton on F(s) − target with F'(s) = ½|n_z|(1 − r_in²/r_out²) (since
    /// dφ/ds = |n_z|/r_out² and dF/dφ = ½(r_out² − r_in²)), kept in a shrinking bracket.
    fn invert(&self, target: f64) -> (DVec2, f64, f64) {
        let nz_outer = self.outer.normal.z.abs();
        let at = |s: f64| {
            let p = self.outer_point(s);
            let r2 = p.x * p.x + p.y * p.y;
            let d = if r2 > 0.0 {
                DVec2::new(p.x, p.y) / r2.sqrt()
            } else {
                self.d_lo
            };
            (d, r2)
        };
        let Some((inner, p_inner)) = self.inner else {
            let (d, r2) = at((2.0 * target / nz_outer).clamp(0.0, self.arc_outer));
            return (d, r2, 0.0);
        };
        let (mut lo, mut hi) = (0.0, self.arc_outer);
        let mut s = self.arc_outer * (target / self.area).clamp(0.0, 1.0);
        let mut result = (self.d_lo, 0.0, 0.0);
        for _ in 0..MAX_NEWTON_STEPS {
            let (d, r_out2) = at(s);
            let q = inner.point_at(d);
            let r_in2 = (q.x * q.x + q.y * q.y).min(r_out2);
            result = (d, r_out2, r_in2);
            let g = 0.5 * nz_outer * s - inner.sector(p_inner, q) - target;
            if g.abs() <= NEWTON_TOLERANCE * self.area {
                break;
            }
            if g > 0.0 {
                hi = s;
            } else {
                lo = s;
            }
            let slope = 0.5 * nz_outer * (1.0 - r_in2 / r_out2);
            let mut next = s - g / slope;
            if !(slope > 0.0 && next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if hi - lo <= 1e-15 * self.arc_outer {
                break;
            }
            s = next;
        }
        result
    }
}

#[cfg(test)]
mod tests;
