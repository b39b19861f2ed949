//! Spatial reuse of resampled light samples (`--ris-spatial K`): Bitterli et al. 2020,
//! "Spatiotemporal reservoir resampling for real-time ray tracing with dynamic direct
//! lighting" (its unbiased combination of reservoirs), read as generalized RIS (Lin et al.
//! 2022, "Generalized resampled importance sampling: foundations of ReSTIR").
//!
//! Each sample index of the image is shaded in two passes. The first finds every pixel's
//! primary hit and fills its reservoirs by RIS from M candidates ([`super::ris`]). The
//! second combines a pixel's reservoir with those of K neighbouring pixels and traces one
//! shadow ray to the sample it keeps.
//!
//! Samples travel between pixels as points on lights, so reservoirs live in the measure
//! all shading points share: area on surface lights, solid angle at infinity, counting on
//! point lights. There the target is p̂_q(y) = luminance(f·|cos θ|·Le)(q → y) · J_q(y), with
//! J = |cos θ_y| / |q − y|² on a surface (solid angle to area, the lecture's G without
//! the receiver's cosine) and 1 otherwise; a reservoir's contribution weight is
//! W_A = W_ω / J.
//!
//! Combining the pixel's reservoir (canonical, c) with K neighbours' at q: offer each kept
//! y_i with weight m_i(y_i) · p̂_q(y_i) · W_i, keep y, and give it W = Σ w / p̂_q(y). The
//! MIS weights m_i need only sum to one over the reservoirs that can hold y (Lin et al.
//! 2022's condition for unbiased GRIS). They are pairwise (Bitterli 2022, "Correlations
//! and reuse for fast and accurate physically based light transport", PhD thesis,
//! Dartmouth: pairwise MIS, here without its defensive term and with equal confidences):
//! each neighbour pairs with the canonical reservoir, which counts 1/K in every pair,
//!   m_i(y) = (1/K) · p̂_i(y) / (p̂_i(y) + p̂_c(y)/K),
//!   m_c(y) = (1/K) · Σ_i (p̂_c(y)/K) / (p̂_i(y) + p̂_c(y)/K),
//! with p̂_c = p̂_q. Equal targets give every reservoir 1/(K+1); and since
//! p̂_q / (p̂_i + p̂_q/K) ≤ K, a neighbour's offer is at most p̂_i(y_i)·W_i, its own mean
//! candidate weight, however differently q sees y_i. (The simpler 1/Z weights,
//! Z = #{i : p̂_i(y) > 0}, are unbiased too but let a sample near a neighbour's silhouette,
//! where its J and so its p̂ are tiny and its W huge, land on q with a large p̂_q:
//! fireflies, relMSE 0.7–2.0 on `shirley-100` at 2 s against 2.7·10⁻³ without reuse.)
//! Each m costs one evaluation of p̂ at another point, 2K per combination. The target has
//! no visibility term, so no reservoir's support is cut by a shadow; the one shadow ray
//! goes to the kept y, and E[f·Le·V·J·W] is the direct light. Neighbours are chosen by
//! position and by similar normal and depth (their primary hits), never by what their
//! reservoirs hold.
//!
//! Support: p̂_q(y) > 0 must imply that q's own candidates can land on y. The light BVH
//! gives no light that can light a point a zero probability and every light strategy
//! covers what its light shows a point; the target is cut at the geometric and at the
//! shading horizon, and so are the candidates of reservoirs filled for reuse.
//!
//! Under MIS the light sample's weight uses the source density at q (selection pmf × the
//! light's density), as plain RIS does ([`super::ris`]); the BSDF samples are unchanged.

use glam::{Vec2, Vec3};

use super::mis::{LightTechnique, estimate_with};
use super::ris::{Reservoir, above_horizons, resample};
use super::{Context, Estimator, EstimatorKind, Shading, emitted_at, f_cos};
use crate::bsdf::{Bsdf, Material};
use crate::geometry::{Ray, SurfaceHit};
use crate::light::select::LightSelector;
use crate::light::{LightSample, ShadingPoint};
use crate::math::{Spectrum, spectrum::luminance};
use crate::sampling::Uniform;
use crate::scene::Scene;
use crate::settings::MisHeuristic;

/// A pixel's primary hit, ready to be shaded and to be looked at by its neighbours.
#[derive(Clone, Debug)]
pub struct SpatialSurface {
    hit: SurfaceHit,
    material: Material,
    at: ShadingPoint,
    /// ω_out in the shading frame.
    w_out: Vec3,
}

impl SpatialSurface {
    /// The shading normal.
    pub fn normal(&self) -> Vec3 {
        self.at.n
    }

    /// Distance from the camera along the primary ray.
    pub fn depth(&self) -> f32 {
        self.hit.t
    }
}

/// Where on a light a reservoir's sample is, in terms every shading point understands.
#[derive(Clone, Copy, Debug)]
enum OnLight {
    /// A point and its geometric normal on a surface light.
    Surface { p: Vec3, n: Vec3 },
    /// A point light (the light's index says all).
    Delta,
    /// A direction towards a light at infinity.
    Direction(Vec3),
}

/// The sample a reservoir keeps.
#[derive(Clone, Copy, Debug)]
struct Kept {
    light: u32,
    y: OnLight,
    /// Contribution weight in the reuse measure, W_A = W_ω / J.
    w: f32,
    /// The target p̂ (reuse measure) at the pixel that drew it.
    target: f32,
    /// The source density (pmf × solid-angle density) at the pixel that drew it.
    p_source: f32,
}

/// One pixel's reservoir for one light sample: what it kept (every pixel's reservoir
/// drew the same number of candidates, so their pairwise MIS weights need no counts).
#[derive(Clone, Copy, Debug, Default)]
pub struct SpatialReservoir {
    kept: Option<Kept>,
}

/// A pixel as its neighbours see it: its surface and its reservoirs.
#[derive(Clone, Copy, Debug)]
pub struct Reuse<'a> {
    /// The primary hit.
    pub surface: &'a SpatialSurface,
    /// One reservoir per light sample of the estimate.
    pub reservoirs: &'a [SpatialReservoir],
}

/// A reservoir's sample as seen from another shading point.
struct Shifted {
    ls: LightSample,
    /// f·|cos θ| there.
    f: Spectrum,
    /// p̂ in the reuse measure.
    target: f32,
    /// J: the reuse measure per unit solid angle.
    jacobian: f32,
}

/// J of a light sample: |cos θ_y| / d² on a surface, 1 at infinity and on point lights.
fn jacobian(ls: &LightSample) -> f32 {
    if ls.delta || ls.distance.is_infinite() {
        1.0
    } else {
        ls.normal.dot(ls.w_in).abs() / (ls.distance * ls.distance)
    }
}

/// Where a light sample is on its light.
fn on_light(ls: &LightSample) -> OnLight {
    if ls.delta {
        OnLight::Delta
    } else if ls.distance.is_infinite() {
        OnLight::Direction(ls.w_in)
    } else {
        OnLight::Surface {
            p: ls.point,
            n: ls.normal,
        }
    }
}

/// The sample `y` on light `light` seen from the context's shading point; `None` where
/// the target is zero (below a horizon, behind a one-sided emitter, no reflection).
#[inline]
fn shift(ctx: &Context<'_>, light: u32, y: OnLight) -> Option<Shifted> {
    let at = ctx.at;
    let l = &ctx.scene.lights[light as usize];
    let ls = match y {
        OnLight::Surface { p, n } => {
            let d = p - at.p;
            let distance = d.length();
            let w_in = d / distance;
            LightSample {
                w_in,
                distance,
                radiance: l.emitted(p, n, -w_in),
                pdf: 0.0,
                delta: false,
                point: p,
                normal: n,
            }
        }
        OnLight::Delta => l.sample(at, Vec2::ZERO, ctx.lights)?,
        OnLight::Direction(w_in) => LightSample {
            w_in,
            distance: f32::INFINITY,
            radiance: l.infinite_radiance(w_in),
            pdf: 0.0,
            delta: false,
            point: at.p + w_in,
            normal: -w_in,
        },
    };
    if !above_horizons(at, ls.w_in) {
        return None;
    }
    let jacobian = jacobian(&ls);
    let f = f_cos(ctx.material, ctx.hit.frame.to_local(ls.w_in), ctx.w_out);
    let target = luminance(f * ls.radiance) * jacobian;
    (target > 0.0 && target.is_finite()).then_some(Shifted {
        ls,
        f,
        target,
        jacobian,
    })
}

/// A reservoir filled by RIS from `candidates` candidates at the context's point (the
/// first pass).
fn fill(ctx: &Context<'_>, src: &mut impl Uniform, candidates: u32) -> SpatialReservoir {
    let kept = resample(ctx, src, candidates, true).and_then(|r| {
        let j = jacobian(&r.ls);
        let w = r.weight / j;
        (w > 0.0 && w.is_finite()).then_some(Kept {
            light: r.light as u32,
            y: on_light(&r.ls),
            w,
            target: luminance(r.f * r.ls.radiance) * j,
            p_source: r.p_source,
        })
    });
    SpatialReservoir { kept }
}

/// The context of a neighbour's surface.
fn context_of<'a>(
    estimator: &'a Estimator,
    scene: &'a Scene,
    s: &'a SpatialSurface,
) -> Context<'a> {
    estimator.context(scene, &s.at, &s.hit, &s.material, s.w_out)
}

/// The combination of reservoir `j` of the pixel and of its K neighbours, with pairwise
/// MIS weights (see the module notes): the kept sample seen from the pixel, its light,
/// where it lies, its contribution weight W (reuse measure), and its source density at the
/// pixel when it is the pixel's own sample.
fn combine(
    estimator: &Estimator,
    ctx: &Context<'_>,
    own: &SpatialReservoir,
    neighbours: &[Reuse<'_>],
    j: usize,
    u: f32,
) -> Option<(Shifted, Kept, f32, Option<f32>)> {
    let share = 1.0 / neighbours.len().max(1) as f64;
    let mut reservoir = Reservoir::new(u);
    let mut kept: Option<(Shifted, Kept, bool)> = None;
    let mut offer = |s: Shifted, k: Kept, w: f64, is_own: bool| {
        if w > 0.0 && w.is_finite() && reservoir.offer(w) {
            kept = Some((s, k, is_own));
        }
    };
    if let Some(c) = own.kept
        && let Some(s) = shift(ctx, c.light, c.y)
    {
        // m_c(y_c) = (1/K) Σ_i (p̂_q/K) / (p̂_i + p̂_q/K), or 1 without neighbours.
        let pq = s.target as f64;
        let m_c = if neighbours.is_empty() {
            1.0
        } else {
            let mut sum = 0.0;
            for n in neighbours {
                let nctx = context_of(estimator, ctx.scene, n.surface);
                let pi = shift(&nctx, c.light, c.y).map_or(0.0, |t| t.target as f64);
                sum += pq * share / (pi + pq * share);
            }
            share * sum
        };
        offer(s, c, m_c * pq * c.w as f64, true);
    }
    for n in neighbours {
        let Some(k) = n.reservoirs[j].kept else {
            continue;
        };
        let Some(s) = shift(ctx, k.light, k.y) else {
            continue;
        };
        // m_i(y_i) = (1/K) p̂_i / (p̂_i + p̂_q/K).
        let (pq, pi) = (s.target as f64, k.target as f64);
        let m_i = share * pi / (pi + pq * share);
        offer(s, k, m_i * pq * k.w as f64, false);
    }
    let (s, k, is_own) = kept?;
    let w = (reservoir.w_sum / s.target as f64) as f32;
    (w > 0.0 && w.is_finite()).then_some((s, k, w, is_own.then_some(k.p_source)))
}

/// Light samples combined from the pixel's reservoirs and its neighbours'.
struct Reused<'r> {
    estimator: &'r Estimator,
    own: &'r [SpatialReservoir],
    neighbours: &'r [Reuse<'r>],
    /// The next reservoir to combine.
    next: usize,
    /// MIS weights apply (false for the light estimator, whose weight is one).
    weighted: bool,
}

impl LightTechnique for Reused<'_> {
    fn sample(
        &mut self,
        ctx: &Context<'_>,
        src: &mut impl Uniform,
        scale: impl Fn(f32, f32) -> f32,
        delta_scale: f32,
    ) -> Spectrum {
        let j = self.next;
        self.next += 1;
        let u = src.next_1d();
        let Some(own) = self.own.get(j) else {
            return Spectrum::ZERO;
        };
        let Some((s, k, w, own_p)) = combine(self.estimator, ctx, own, self.neighbours, j, u)
        else {
            return Spectrum::ZERO;
        };
        if ctx.occluded(&s.ls) {
            return Spectrum::ZERO;
        }
        let weight = if s.ls.delta {
            delta_scale
        } else if !self.weighted {
            1.0
        } else {
            let p = own_p.unwrap_or_else(|| source_pdf(ctx, k.light, k.y));
            let p_bsdf = ctx
                .material
                .pdf(ctx.hit.frame.to_local(s.ls.w_in), ctx.w_out);
            if p > 0.0 { scale(p, p_bsdf) * p } else { 0.0 }
        };
        s.f * s.ls.radiance * (s.jacobian * w * weight)
    }
}

/// The density per steradian at the context's point with which the pixel's own
/// candidates draw `y` on `light` (selection pmf × the light's density).
fn source_pdf(ctx: &Context<'_>, light: u32, y: OnLight) -> f32 {
    let l = &ctx.scene.lights[light as usize];
    let pdf = match y {
        OnLight::Surface { p, n } => l.pdf(ctx.at, p, n, ctx.lights),
        OnLight::Direction(w) => l.infinite_pdf(w, ctx.lights),
        OnLight::Delta => return 0.0,
    };
    ctx.selector.pmf(ctx.at, light as usize) * pdf
}

impl Estimator {
    /// Reservoirs per pixel under spatial reuse: one per light sample of an estimate.
    pub fn spatial_reservoirs(&self) -> usize {
        match self.kind {
            EstimatorKind::Mis if self.mis.heuristic != MisHeuristic::OneSample => {
                self.mis.light_samples as usize
            }
            _ => 1,
        }
    }

    /// The first pass of spatial reuse for a camera ray: the radiance seen directly
    /// (emission or background), and when the ray meets a surface that reflects towards
    /// the camera, that surface with `reservoirs` filled by RIS.
    pub fn spatial_primary(
        &self,
        scene: &Scene,
        ray: &Ray,
        src: &mut impl Uniform,
        reservoirs: &mut [SpatialReservoir],
    ) -> (Spectrum, Option<SpatialSurface>) {
        reservoirs.fill(SpatialReservoir::default());
        let Some(hit) = scene.geometry.intersect(ray, f32::INFINITY) else {
            return (scene.escaped(ray.d.normalize()), None);
        };
        let w_out = -ray.d.normalize();
        let emitted = emitted_at(scene, &hit, w_out);
        // As `Estimator::direct_probed` shades a hit, with the material and hit kept.
        let Some(sh) = Shading::at(scene, &hit, w_out) else {
            return (emitted, None);
        };
        let surface = SpatialSurface {
            at: sh.at,
            hit: sh.hit,
            material: sh.material.into_owned(),
            w_out: sh.w_out,
        };
        let ctx = context_of(self, scene, &surface);
        let m = self.ris.unwrap_or(1);
        for r in reservoirs.iter_mut() {
            *r = fill(&ctx, src, m);
        }
        (emitted, Some(surface))
    }

    /// The second pass: one estimate of direct light at `own`'s surface whose light
    /// samples combine its reservoirs with those of `neighbours`.
    pub fn spatial_direct(
        &self,
        scene: &Scene,
        own: Reuse<'_>,
        neighbours: &[Reuse<'_>],
        src: &mut impl Uniform,
    ) -> Spectrum {
        let ctx = context_of(self, scene, own.surface);
        let mut reused = Reused {
            estimator: self,
            own: own.reservoirs,
            neighbours,
            next: 0,
            weighted: self.kind == EstimatorKind::Mis,
        };
        match self.kind {
            EstimatorKind::Mis => estimate_with(&ctx, self.mis, src, &mut reused),
            _ => reused.sample(&ctx, src, |_, _| 1.0, 1.0),
        }
    }
}
