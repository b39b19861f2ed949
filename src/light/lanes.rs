//! Light samples of several shading points at once, for the lights whose sampling has a
//! lanes version: rectangles under `solid-angle` with the fast paths on
//! ([`sample_lanes`]). Every sample is the one [`Light::sample`] gives at the same
//! shading point with the same numbers, bit for bit; only the work is shared.
//!
//! A renderer that has many shading points waiting for a light sample (the camera
//! packets' shading points, after [`Estimator::begin`](crate::integrator::Estimator::begin))
//! hands them over [`LANES`] at a time.

use glam::Vec2;

use super::area::light_sample;
use super::{Light, LightPoint, LightSample, LightSampling, LightStrategy, ShadingPoint};
use crate::geometry::Shape;
use crate::sampling::warp::{LANES, RectangleFrame, RectangleLane, sample_lanes};

/// Which lights of a scene have a lanes version under one strategy, with what they
/// precompute for it (a rectangle's edge frame).
#[derive(Clone, Debug)]
pub struct LightLanes {
    frames: Vec<Option<RectangleFrame>>,
}

/// One shading point's request: the light, the shading point, the two numbers.
pub type LaneJob<'a> = (usize, &'a ShadingPoint, Vec2);

impl LightLanes {
    /// The lanes of `lights` under `strategy`, or `None` when no light has one (then
    /// there is nothing to share).
    pub fn new(lights: &[Light], strategy: LightStrategy) -> Option<LightLanes> {
        let frames: Vec<Option<RectangleFrame>> = lights
            .iter()
            .map(|light| match light {
                Light::Area(a) if strategy.fast_paths => match &a.shape {
                    Shape::Rectangle(r)
                        if a.strategy(strategy.sampling) == LightSampling::SolidAngle =>
                    {
                        RectangleFrame::new(r.ea, r.eb)
                    }
                    _ => None,
                },
                _ => None,
            })
            .collect();
        frames
            .iter()
            .any(Option::is_some)
            .then_some(LightLanes { frames })
    }

    /// Whether light `index` has a lanes version.
    #[inline]
    pub fn has(&self, index: usize) -> bool {
        matches!(self.frames.get(index), Some(Some(_)))
    }

    /// `lights[i].sample(at, u, strategy)` for each of the first `used` jobs `(i, at, u)`,
    /// handed to `put(l, sample)` with the job's lane `l` so that the caller stores it
    /// where it is wanted (returned as an array, each 60-byte sample was copied twice more
    /// on its way); the other jobs only fill the lanes. Every light `i` is one that
    /// [`LightLanes::has`]; `lights` and `strategy` must be the ones the lanes were made
    /// with.
    #[inline(always)]
    pub fn sample(
        &self,
        lights: &[Light],
        strategy: LightStrategy,
        jobs: &[LaneJob; LANES],
        used: usize,
        mut put: impl FnMut(usize, Option<LightSample>),
    ) {
        let rectangle = |i: usize| match &lights[i] {
            Light::Area(a) => match &a.shape {
                Shape::Rectangle(r) => (a, r),
                _ => unreachable!("light {i} has no lanes version"),
            },
            _ => unreachable!("light {i} has no lanes version"),
        };
        let lane: [RectangleLane; LANES] = std::array::from_fn(|l| {
            let (i, at, u) = jobs[l];
            RectangleLane {
                frame: self.frames[i].as_ref().expect("a light with lanes"),
                corner: rectangle(i).1.o,
                p: at.p,
                u,
            }
        });
        let drawn = sample_lanes(&lane);
        for (l, &(i, at, u)) in jobs.iter().enumerate().take(used) {
            let (light, r) = rectangle(i);
            match drawn[l] {
                // As rectangle::sample's fast path, then AreaLight::sample_with.
                Some((offset, pdf)) => {
                    let y = at.p + offset;
                    let point = LightPoint {
                        y,
                        ny: r.normal,
                        pdf,
                    };
                    put(
                        l,
                        light_sample(at, point, strategy.horizon_rejection, |ny, w| {
                            light.emitted(y, ny, w)
                        }),
                    );
                }
                // The spherical rectangle is too small or seen edge-on: the scalar path
                // falls back to area sampling there.
                None => put(l, lights[i].sample(at, u, strategy)),
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

    /// On a scene with rectangle and other lights, the lanes give every job the scalar
    /// sample bit for bit, at points all around the rectangles (near, grazing, behind).
    #[test]
    fn lanes_are_the_scalar_samples() {
        let scene = load("builtin:assignment").expect("scene");
        let strategy = LightStrategy::default();
        let lanes = LightLanes::new(&scene.lights, strategy).expect("a rectangle light");
        let with: Vec<usize> = (0..scene.lights.len()).filter(|&i| lanes.has(i)).collect();
        assert!(!with.is_empty());
        // Off: no fast paths, no lanes.
        let slow = LightStrategy {
            fast_paths: false,
            ..strategy
        };
        assert!(LightLanes::new(&scene.lights, slow).is_none());
        let mut rng = Rng32::new(3);
        let mut compared = 0;
        for k in 0..5000 {
            let points: [ShadingPoint; LANES] = std::array::from_fn(|_| {
                let p = (Vec3::new(rng.next_1d(), rng.next_1d(), rng.next_1d()) - 0.5) * 8.0;
                let n =
                    Vec3::new(rng.next_1d() - 0.5, rng.next_1d(), rng.next_1d() - 0.5).normalize();
                ShadingPoint { p, ng: n, n }
            });
            let jobs: [LaneJob; LANES] =
                std::array::from_fn(|l| (with[(k + l) % with.len()], &points[l], rng.next_2d()));
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
            let bits = |s: &Option<LightSample>| {
                s.map(|s| {
                    (
                        s.point.to_array().map(f32::to_bits),
                        s.w_in.to_array().map(f32::to_bits),
                        s.radiance.to_array().map(f32::to_bits),
                        s.pdf.to_bits(),
                        s.distance.to_bits(),
                    )
                })
            };
            for (l, got) in wide.iter().enumerate() {
                let (i, at, u) = jobs[l];
                let scalar = scene.lights[i].sample(at, u, strategy);
                assert_eq!(bits(got), bits(&scalar), "light {i} at {}", at.p);
                if l < 2 {
                    assert_eq!(bits(&some[l]), bits(&scalar));
                }
                compared += got.is_some() as u32;
            }
        }
        assert!(compared > 2000, "only {compared} samples");
    }
}
