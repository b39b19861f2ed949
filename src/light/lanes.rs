//! Light samples of several shading points at once, for the lights whose sampling has a
//! lanes version, with the fast paths on: rectangles under `solid-angle`
//! ([`sample_lanes`]) and spheres under `solid-angle` ([`sphere_lanes::sample_lanes`]).
//! Every sample is the one [`Light::sample`] gives at the same shading point with the
//! same numbers, bit for bit; only the work is shared.
//!
//! A renderer that has many shading points waiting for a light sample (the camera
//! packets' shading points, after [`Estimator::begin`](crate::integrator::Estimator::begin))
//! hands them over [`LANES`] at a time.

use glam::Vec2;

use super::area::sphere_lanes::{self, SphereLane};
use super::area::{AreaLight, light_sample};
use super::{Light, LightPoint, LightSample, LightSampling, LightStrategy, ShadingPoint};
use crate::geometry::Shape;
use crate::sampling::warp::{LANES, RectangleFrame, RectangleLane, sample_lanes};

/// A light's lanes version, with what it precomputes.
#[derive(Clone, Debug)]
enum Lanes {
    /// A rectangle under `solid-angle`, with its edge frame.
    Rectangle(RectangleFrame),
    /// A sphere under `solid-angle`.
    Sphere,
}

/// Which lights of a scene have a lanes version under one strategy, with what they
/// precompute for it (a rectangle's edge frame).
#[derive(Clone, Debug)]
pub struct LightLanes {
    lanes: Vec<Option<Lanes>>,
    /// Whether some light is a sphere with lanes (else every job is a rectangle's).
    spheres: bool,
}

/// Kernels of [`LightLanes`] (rectangles, spheres); see [`LightLanes::kernel`].
pub const KERNELS: usize = 2;

/// One shading point's request: the light, the shading point, the two numbers.
pub type LaneJob<'a> = (usize, &'a ShadingPoint, Vec2);

impl LightLanes {
    /// The lanes of `lights` under `strategy`, or `None` when no light has one (then
    /// there is nothing to share).
    pub fn new(lights: &[Light], strategy: LightStrategy) -> Option<LightLanes> {
        let lanes: Vec<Option<Lanes>> = lights
            .iter()
            .map(|light| match light {
                Light::Area(a)
                    if strategy.fast_paths
                        && a.strategy(strategy.sampling) == LightSampling::SolidAngle =>
                {
                    match &a.shape {
                        Shape::Rectangle(r) => {
                            RectangleFrame::new(r.ea, r.eb).map(Lanes::Rectangle)
                        }
                        Shape::Sphere(_) => Some(Lanes::Sphere),
                        _ => None,
                    }
                }
                _ => None,
            })
            .collect();
        let spheres = lanes.iter().any(|l| matches!(l, Some(Lanes::Sphere)));
        lanes
            .iter()
            .any(Option::is_some)
            .then_some(LightLanes { lanes, spheres })
    }

    /// Whether light `index` has a lanes version.
    #[inline]
    pub fn has(&self, index: usize) -> bool {
        self.kernel(index).is_some()
    }

    /// Which kernel light `index` goes through (`Some(k)`, `k` < [`KERNELS`]), if it
    /// has a lanes version: a caller that batches jobs by kernel fills every lane of
    /// each call.
    #[inline]
    pub fn kernel(&self, index: usize) -> Option<usize> {
        match self.lanes.get(index) {
            Some(Some(Lanes::Rectangle(_))) => Some(0),
            Some(Some(Lanes::Sphere)) => Some(1),
            _ => None,
        }
    }

    /// `lights[i].sample(at, u, strategy)` for each of the first `used` jobs `(i, at, u)`,
    /// handed to `put(l, sample)` with the job's lane `l` so that the caller stores it
    /// where it is wanted (returned as an array, each 60-byte sample was copied twice more
    /// on its way); the other jobs only fill the lanes (`used` ≤ [`LANES`]; none when
    /// `used` is 0). Every light `i` is one that [`LightLanes::has`]; `lights` and
    /// `strategy` must be the ones the lanes were made with. Jobs of rectangles and of
    /// spheres go through their own kernels (each kernel runs only when some job is of
    /// its kind), so a caller that batches by [`LightLanes::kernel`] fills every lane.
    #[inline(always)]
    pub fn sample(
        &self,
        lights: &[Light],
        strategy: LightStrategy,
        jobs: &[LaneJob; LANES],
        used: usize,
        mut put: impl FnMut(usize, Option<LightSample>),
    ) {
        debug_assert!(used <= LANES, "{used} jobs for {LANES} lanes");
        let used = used.min(LANES);
        if used == 0 {
            return;
        }
        let batch = Batch {
            lights,
            strategy,
            jobs,
            used,
        };
        if !self.spheres {
            return batch.rectangles(&self.lanes, &mut put, |_| true);
        }
        let is_sphere = |l: usize| matches!(self.lanes[jobs[l].0], Some(Lanes::Sphere));
        let of_spheres = (0..used).filter(|&l| is_sphere(l)).count();
        if of_spheres < used {
            batch.rectangles(&self.lanes, &mut put, |l| !is_sphere(l));
        }
        if of_spheres > 0 {
            batch.spheres(&mut put, is_sphere);
        }
    }
}

/// The jobs of one [`LightLanes::sample`] call, the first `used` of them real.
struct Batch<'a, 'j> {
    lights: &'a [Light],
    strategy: LightStrategy,
    jobs: &'a [LaneJob<'j>; LANES],
    used: usize,
}

impl Batch<'_, '_> {
    /// The samples of the jobs `l < used` that `mine(l)` (all rectangles, with their
    /// `lanes`; the kernel's other lanes repeat the first of them).
    #[inline(always)]
    fn rectangles(
        &self,
        lanes: &[Option<Lanes>],
        put: &mut impl FnMut(usize, Option<LightSample>),
        mine: impl Fn(usize) -> bool,
    ) {
        let rectangle = |i: usize| match &self.area(i).shape {
            Shape::Rectangle(r) => r,
            _ => unreachable!("light {i} has no rectangle lanes"),
        };
        let pick = self.filled(&mine);
        let lane: [RectangleLane; LANES] = std::array::from_fn(|l| {
            let (i, at, u) = self.jobs[pick(l)];
            let Some(Lanes::Rectangle(frame)) = &lanes[i] else {
                unreachable!("light {i} has no rectangle lanes")
            };
            RectangleLane {
                frame,
                corner: rectangle(i).o,
                p: at.p,
                u,
            }
        });
        // As rectangle::sample's fast path: the point p + offset, the plane's normal.
        let drawn = sample_lanes(&lane);
        let point = |l: usize, i: usize, at: &ShadingPoint| {
            drawn[l].map(|(offset, pdf)| LightPoint {
                y: at.p + offset,
                ny: rectangle(i).normal,
                pdf,
            })
        };
        self.put_samples(put, &mine, point);
    }

    /// The samples of the jobs `l < used` that `mine(l)` (all spheres; the kernel's
    /// other lanes repeat the first of them).
    #[inline(always)]
    fn spheres(
        &self,
        put: &mut impl FnMut(usize, Option<LightSample>),
        mine: impl Fn(usize) -> bool,
    ) {
        let pick = self.filled(&mine);
        let lane: [SphereLane; LANES] = std::array::from_fn(|l| {
            let (i, at, u) = self.jobs[pick(l)];
            let Shape::Sphere(sphere) = self.area(i).shape else {
                unreachable!("light {i} has no sphere lanes")
            };
            SphereLane { sphere, p: at.p, u }
        });
        let points = sphere_lanes::sample_lanes(&lane);
        self.put_samples(put, &mine, |l, _, _| points[l]);
    }

    /// The area light `lights[i]` (one with lanes).
    #[inline(always)]
    fn area(&self, i: usize) -> &AreaLight {
        match &self.lights[i] {
            Light::Area(a) => a,
            _ => unreachable!("light {i} has no lanes version"),
        }
    }

    /// The lane whose job lane `l` takes: its own when it is one of the first `used`
    /// and `mine`, else the first such (a kernel's other lanes only fill it).
    #[inline(always)]
    fn filled<'m>(&self, mine: &'m impl Fn(usize) -> bool) -> impl Fn(usize) -> usize + 'm {
        let used = self.used;
        let first = (0..used).find(|&l| mine(l)).expect("a job for the kernel");
        move |l| if l < used && mine(l) { l } else { first }
    }

    /// Hands on the samples of the jobs `l < used` that `mine(l)`, from the kernel's
    /// `point(l, i, at)` of lane `l` (light `i`, shading point `at`): each as
    /// `AreaLight::sample_with` makes it from its shape's point, and where the kernel
    /// has none (a spherical rectangle too small or seen edge-on, a shading point inside
    /// a sphere) the scalar sample, which takes the area there. (The points are made one
    /// at a time, as they are handed on: gathered in an array first, they cost the
    /// rectangles' stage 8 % more instructions.)
    #[inline(always)]
    fn put_samples(
        &self,
        put: &mut impl FnMut(usize, Option<LightSample>),
        mine: &impl Fn(usize) -> bool,
        point: impl Fn(usize, usize, &ShadingPoint) -> Option<LightPoint>,
    ) {
        for (l, &(i, at, u)) in self.jobs.iter().enumerate().take(self.used) {
            if !mine(l) {
                continue;
            }
            match point(l, i, at) {
                Some(point) => {
                    let (light, y) = (self.area(i), point.y);
                    let emitted = |ny, w| light.emitted(y, ny, w);
                    let reject = self.strategy.horizon_rejection;
                    put(l, light_sample(at, point, reject, emitted));
                }
                None => put(l, self.lights[i].sample(at, u, self.strategy)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::sampling::{Rng32, Uniform};
    use crate::scene::load;

    /// The bits of a sample, to compare them exactly.
    type Bits = ([u32; 3], [u32; 3], [u32; 3], u32, u32);

    fn bits(s: &Option<LightSample>) -> Option<Bits> {
        s.map(|s| {
            (
                s.point.to_array().map(f32::to_bits),
                s.w_in.to_array().map(f32::to_bits),
                s.radiance.to_array().map(f32::to_bits),
                s.pdf.to_bits(),
                s.distance.to_bits(),
            )
        })
    }

    /// On scenes with rectangle lights (`assignment`), sphere lights and a rectangle
    /// together (`sphere-near-plane`, so batches mix the two kernels) and a hundred
    /// spheres and quads (`shirley-100`), the lanes give every job the scalar sample bit
    /// for bit, at points all around the lights (near, grazing, behind, and inside the
    /// spheres, where the scalar path samples the area), with every lane used and with
    /// two.
    #[test]
    fn lanes_are_the_scalar_samples() {
        for (spec, size) in [
            ("builtin:assignment", 8.0),
            ("builtin:sphere-near-plane", 3.0),
            ("builtin:shirley-100", 12.0),
        ] {
            let scene = load(spec).expect("scene");
            let strategy = LightStrategy::default();
            let lanes = LightLanes::new(&scene.lights, strategy).expect("lights with lanes");
            let with: Vec<usize> = (0..scene.lights.len()).filter(|&i| lanes.has(i)).collect();
            let sphere = |i: usize| match &scene.lights[i] {
                Light::Area(a) => match &a.shape {
                    Shape::Sphere(s) => Some(*s),
                    _ => None,
                },
                _ => None,
            };
            // Off: no fast paths, no lanes.
            let slow = LightStrategy {
                fast_paths: false,
                ..strategy
            };
            assert!(LightLanes::new(&scene.lights, slow).is_none());
            let mut rng = Rng32::new(3);
            // Samples compared of rectangles and of spheres, and jobs from inside one.
            let (mut rectangles, mut spheres, mut inside) = (0, 0, 0);
            for k in 0..4000 {
                let jobs_lights: [usize; LANES] = std::array::from_fn(|_| {
                    with[(rng.next_1d() * with.len() as f32) as usize % with.len()]
                });
                let points: [ShadingPoint; LANES] = std::array::from_fn(|l| {
                    let mut p =
                        (Vec3::new(rng.next_1d(), rng.next_1d(), rng.next_1d()) - 0.5) * size;
                    if let Some(s) = sphere(jobs_lights[l]).filter(|_| k % 7 == l) {
                        // Near the sphere: inside it, or just outside.
                        let d = Vec3::new(rng.next_1d(), rng.next_1d(), rng.next_1d()) - 0.5;
                        p = s.center + d.normalize_or_zero() * s.radius * 2.0 * rng.next_1d();
                    }
                    let n = Vec3::new(rng.next_1d() - 0.5, rng.next_1d(), rng.next_1d() - 0.5)
                        .normalize();
                    ShadingPoint { p, ng: n, n }
                });
                let jobs: [LaneJob; LANES] =
                    std::array::from_fn(|l| (jobs_lights[l], &points[l], rng.next_2d()));
                let drawn = |used: usize| {
                    let mut out = [None; LANES];
                    let mut calls = 0;
                    lanes.sample(&scene.lights, strategy, &jobs, used, |l, ls| {
                        out[l] = ls;
                        calls += 1;
                    });
                    assert_eq!(calls, used, "one sample per job");
                    out
                };
                let wide = drawn(LANES);
                // Fewer jobs than lanes: only the first are handed on, the same.
                let some = drawn(2);
                drawn(0); // no job: no call
                for (l, got) in wide.iter().enumerate() {
                    let (i, at, u) = jobs[l];
                    let scalar = scene.lights[i].sample(at, u, strategy);
                    assert_eq!(bits(got), bits(&scalar), "{spec}: light {i} at {}", at.p);
                    if l < 2 {
                        assert_eq!(bits(&some[l]), bits(&scalar), "{spec}: light {i}");
                    }
                    match sphere(i) {
                        Some(s) if (at.p - s.center).length() <= s.radius => inside += 1,
                        Some(_) => spheres += got.is_some() as u32,
                        None => rectangles += got.is_some() as u32,
                    }
                }
            }
            let has_spheres = with.iter().any(|&i| sphere(i).is_some());
            let has_rectangles = with.iter().any(|&i| sphere(i).is_none());
            assert_eq!(
                has_rectangles,
                rectangles > 2000,
                "{spec}: {rectangles} samples"
            );
            assert_eq!(has_spheres, spheres > 1000, "{spec}: {spheres} samples");
            assert_eq!(has_spheres, inside > 100, "{spec}: {inside} jobs inside");
        }
    }
}
