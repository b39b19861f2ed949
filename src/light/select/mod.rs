//! Choosing one light among many (lecture: "we can unite all light sources to a single
//! large one"): a selector draws a light with a probability and hands back the random
//! number rescaled, so the same number can be used again.
//!
//! Four selectors: `uniform` (solution #1), `power` (solution #2), `adaptive` (solution
//! #3, O(n) per point, the reference) and `bvh` (a light tree after Conty Estevez &
//! Kulla 2018, O(log n)). Each `pmf` returns exactly the probability `select` used, so
//! MIS can weight BSDF-sampled hits with it.

mod adaptive;
mod bounds;
mod bvh;
pub mod cone;
mod estimate;
mod power;
mod prepared;
mod uniform;

pub use adaptive::{ADAPTIVE_FLOOR, AdaptiveSelector};
pub use bounds::LightBounds;
pub use bvh::BvhSelector;
pub use power::PowerSelector;
pub use prepared::PreparedBounds;
pub use uniform::UniformSelector;

use super::{Light, LightStrategy, ShadingPoint};

/// A chosen light, its probability, and `u` rescaled to [0, 1) so it can be used again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Selection {
    /// Light index.
    pub index: usize,
    /// Probability of choosing it.
    pub pmf: f32,
    /// The random number, rescaled within the chosen light's interval.
    pub u_reused: f32,
}

/// Picks lights. `select` and `pmf` must agree exactly.
pub trait LightSelector {
    /// Chooses a light for shading point `at` with uniform number `u`.
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection>;
    /// Probability that `select` chooses light `index` at `at`.
    fn pmf(&self, at: &ShadingPoint, index: usize) -> f32;
}

pub use crate::settings::LightSelect;

/// The scene's selector (closed set, one `match`).
#[derive(Clone, Debug)]
pub enum Selector {
    /// Uniform choice.
    Uniform(UniformSelector),
    /// By power.
    Power(PowerSelector),
    /// Per-point adaptive.
    Adaptive(AdaptiveSelector),
    /// Light BVH.
    Bvh(BvhSelector),
}

impl Selector {
    /// Builds the selector `kind` over the scene's `lights` (indices into that slice).
    /// With one light every strategy chooses it with probability 1 (where the bounds say
    /// it cannot contribute, its sample is zero anyway), so no per-point selection work
    /// is done: uniform choice.
    pub fn new(kind: LightSelect, lights: &[Light]) -> Selector {
        if lights.len() == 1 {
            return Selector::Uniform(UniformSelector::new(1));
        }
        match kind {
            LightSelect::Uniform => Selector::Uniform(UniformSelector::new(lights.len())),
            LightSelect::Power => {
                let powers: Vec<f32> = lights.iter().map(|l| l.power()).collect();
                Selector::Power(PowerSelector::new(&powers))
            }
            LightSelect::Adaptive => Selector::Adaptive(AdaptiveSelector::new(lights)),
            // Resampling draws its candidates from the light BVH (see `integrator::ris`).
            LightSelect::Bvh | LightSelect::Ris => Selector::Bvh(BvhSelector::new(lights)),
        }
    }

    /// [`Selector::new`] for lights sampled with `strategy`: a light that draws no
    /// samples under it ([`Light::draws_no_samples`]: a constant environment under MIS
    /// compensation) gets probability zero, so that its turns go to lights that have
    /// samples to give, unless no light has any.
    pub fn for_strategy(kind: LightSelect, lights: &[Light], strategy: LightStrategy) -> Selector {
        Selector::new(kind, lights).without_silent(lights, strategy)
    }

    /// The same selector over `lights` with the lights that draw no samples under
    /// `strategy` left out ([`silent_lights`]; unchanged when there are none).
    pub fn without_silent(self, lights: &[Light], strategy: LightStrategy) -> Selector {
        match silent_lights(lights, strategy) {
            Some(silent) => self.excluding(lights, &silent),
            None => self,
        }
    }

    /// The same selector over `lights` giving those marked in `silent` probability zero:
    /// `uniform` becomes uniform among the others (an alias table of equal weights, so
    /// the same u may name another light than ⌊u·n⌋), `power` gives them power zero,
    /// `adaptive` and `bvh` leave them out. A one-light selector is kept as it is.
    pub fn excluding(self, lights: &[Light], silent: &[bool]) -> Selector {
        let weights = |weight: &dyn Fn(&Light) -> f32| -> Vec<f32> {
            lights
                .iter()
                .zip(silent)
                .map(|(l, &s)| if s { 0.0 } else { weight(l) })
                .collect()
        };
        match self {
            Selector::Uniform(_) if lights.len() > 1 => {
                Selector::Power(PowerSelector::new(&weights(&|_| 1.0)))
            }
            Selector::Power(_) => Selector::Power(PowerSelector::new(&weights(&|l| l.power()))),
            Selector::Adaptive(a) => Selector::Adaptive(a.excluding(silent)),
            Selector::Bvh(b) => Selector::Bvh(b.excluding(silent)),
            one => one,
        }
    }
}

impl Selector {
    /// Whether [`Selector::select_lanes`] does more than choose one light after another:
    /// for a light tree of more than one light, whose walks it interleaves.
    pub fn walks_together(&self) -> bool {
        matches!(self, Selector::Bvh(b) if b.node_count() > 0)
    }

    /// [`LightSelector::select`] for each `(point, u)` of `jobs` (at most
    /// [`LANES`](crate::sampling::warp::LANES)), into the same place of `out`: the light
    /// tree's walks together ([`BvhSelector::select_lanes`]), the others' choices one by
    /// one. The same selections as one at a time, bit for bit.
    pub fn select_lanes(&self, jobs: &[(&ShadingPoint, f32)], out: &mut [Option<Selection>]) {
        match self {
            Selector::Bvh(b) => b.select_lanes(jobs, out),
            _ => {
                for (o, &(at, u)) in out.iter_mut().zip(jobs) {
                    *o = self.select(at, u);
                }
            }
        }
    }
}

/// Which of `lights` draw no samples under `strategy` ([`Light::draws_no_samples`]), or
/// `None` when none does, or when all do (they then keep their turns: their samples are
/// empty anyway, and a selector over no light would leave the light technique with no
/// density at all).
pub fn silent_lights(lights: &[Light], strategy: LightStrategy) -> Option<Vec<bool>> {
    let silent: Vec<bool> = lights
        .iter()
        .map(|l| l.draws_no_samples(strategy))
        .collect();
    (silent.contains(&true) && silent.contains(&false)).then_some(silent)
}

impl LightSelector for Selector {
    #[inline]
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection> {
        match self {
            Selector::Uniform(s) => s.select(at, u),
            Selector::Power(s) => s.select(at, u),
            Selector::Adaptive(s) => s.select(at, u),
            Selector::Bvh(s) => s.select(at, u),
        }
    }

    #[inline]
    fn pmf(&self, at: &ShadingPoint, index: usize) -> f32 {
        match self {
            Selector::Uniform(s) => s.pmf(at, index),
            Selector::Power(s) => s.pmf(at, index),
            Selector::Adaptive(s) => s.pmf(at, index),
            Selector::Bvh(s) => s.pmf(at, index),
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::geometry::Shape;
    use crate::geometry::shape::Sphere;
    use crate::light::AreaLight;
    use crate::math::Spectrum;

    fn sphere(x: f32, radiance: f32) -> Light {
        Light::Area(AreaLight {
            shape: Shape::Sphere(Sphere::new(Vec3::new(x, 2.0, 0.0), 0.3)),
            radiance: Spectrum::splat(radiance),
            two_sided: false,
            texture: None,
        })
    }

    const AT: ShadingPoint = ShadingPoint {
        p: Vec3::ZERO,
        ng: Vec3::Y,
        n: Vec3::Y,
    };

    #[test]
    fn no_lights_select_nothing() {
        for kind in LightSelect::ALL {
            let s = Selector::new(kind, &[]);
            assert!(s.select(&AT, 0.5).is_none(), "{kind}");
            assert_eq!(s.pmf(&AT, 0), 0.0, "{kind}");
        }
    }

    #[test]
    fn one_light_is_chosen_with_probability_one() {
        let lights = [sphere(0.0, 1.0)];
        for kind in LightSelect::ALL {
            let s = Selector::new(kind, &lights);
            for u in [0.0, 0.5, 0.999_999_9] {
                let sel = s.select(&AT, u).expect("a light");
                assert_eq!((sel.index, sel.pmf), (0, 1.0), "{kind}");
                assert!((0.0..1.0).contains(&sel.u_reused), "{kind}");
            }
            assert_eq!(s.pmf(&AT, 1), 0.0, "{kind}: out of range");
        }
    }

    #[test]
    fn dark_lights_are_never_chosen_by_informed_selectors() {
        let lights: Vec<Light> = (0..7)
            .map(|i| sphere(i as f32 - 3.0, if i == 2 { 0.0 } else { 1.0 + i as f32 }))
            .collect();
        for kind in [LightSelect::Power, LightSelect::Adaptive, LightSelect::Bvh] {
            let s = Selector::new(kind, &lights);
            assert_eq!(s.pmf(&AT, 2), 0.0, "{kind}");
            for k in 0..1000 {
                let sel = s.select(&AT, k as f32 / 1000.0).expect("a light");
                assert_ne!(sel.index, 2, "{kind}");
            }
        }
        let bvh = BvhSelector::new(&lights);
        // Six lights: a root of four lanes, two of them clusters of two (or one of three).
        assert!((2..=3).contains(&bvh.node_count()), "{}", bvh.node_count());
    }

    /// Under MIS compensation a constant environment draws no samples: every selector
    /// gives it probability zero and the others' probabilities still sum to one; without
    /// compensation, or when it is the only kind of light there is, it keeps its share.
    #[test]
    fn lights_that_draw_nothing_get_no_turns() {
        use crate::light::Environment;
        let sky = || Light::Environment(Environment::constant(Spectrum::ONE));
        let lights = [sphere(-1.0, 2.0), sky(), sphere(1.0, 3.0), sphere(0.0, 1.0)];
        let compensated = LightStrategy {
            env_compensation: true,
            ..LightStrategy::default()
        };
        for kind in LightSelect::ALL {
            let plain = Selector::for_strategy(kind, &lights, LightStrategy::default());
            assert!(plain.pmf(&AT, 1) > 0.0, "{kind}");
            let s = Selector::for_strategy(kind, &lights, compensated);
            assert_eq!(s.pmf(&AT, 1), 0.0, "{kind}");
            let sum: f32 = (0..lights.len()).map(|i| s.pmf(&AT, i)).sum();
            assert!((sum - 1.0).abs() < 1e-5, "{kind}: Σ pmf = {sum}");
            for k in 0..1000 {
                let sel = s.select(&AT, k as f32 / 1000.0).expect("a light");
                assert_ne!(sel.index, 1, "{kind}");
                assert_eq!(sel.pmf, s.pmf(&AT, sel.index), "{kind}");
            }
            if kind == LightSelect::Uniform {
                for i in [0, 2, 3] {
                    assert!((s.pmf(&AT, i) - 1.0 / 3.0).abs() < 1e-6, "uniform: {i}");
                }
            }
            // Nothing but skies: they keep their turns (their samples are empty anyway).
            let skies = Selector::for_strategy(kind, &[sky(), sky()], compensated);
            assert!(skies.pmf(&AT, 0) > 0.0 && skies.pmf(&AT, 1) > 0.0, "{kind}");
        }
    }
}
