//! Several shading points' selections walked together, level by level: the walks are
//! independent, so while one waits on its node's importances (a chain of square roots
//! and divisions, [`WideNode::importance`]) the core works on the others'. Where the
//! processor has AVX2, two walks' importances are computed in one pass over eight lanes
//! ([`importance_pair`]). Each walk takes the steps [`BvhSelector::select`] takes for
//! its point, in the same order and with the same bits, so every selection is the
//! one-at-a-time one.

#[cfg(target_arch = "x86_64")]
use super::wide::importance_pair;
use super::wide::{LANES as CHILDREN, WideNode};
use super::{BvhSelector, Search, Step, Walk, descend};
use crate::light::ShadingPoint;
use crate::light::select::{LightSelector, Selection};
use crate::sampling::warp::LANES;

/// The walks of one call still in the tree.
struct Walks<'a> {
    jobs: &'a [(&'a ShadingPoint, f32)],
    out: &'a mut [Option<Selection>],
    walks: [Walk; LANES],
    /// Indices into `jobs` of the walks still going, `count` of them.
    active: [u8; LANES],
    count: usize,
    /// How many of `active` go on to the next level (moved to its front).
    kept: usize,
    /// The probability of entering the tree ([`BvhSelector::tree_share`]).
    share: f32,
}

impl Walks<'_> {
    /// Walk `j`'s step at `node`, whose importances at its point are `importance`.
    #[inline(always)]
    fn step(&mut self, j: usize, node: &WideNode, importance: &[f32; CHILDREN]) {
        match descend(node, importance, self.walks[j], Search::Masked) {
            Step::Inner(next) => {
                self.walks[j] = next;
                self.active[self.kept] = j as u8;
                self.kept += 1;
            }
            Step::Light(mut selection) => {
                selection.pmf *= self.share;
                self.out[j] = Some(selection);
            }
            Step::Dead => self.out[j] = None,
        }
    }
}

impl BvhSelector {
    /// [`BvhSelector::select`] for each `(point, u)` of `jobs` (at most [`LANES`]),
    /// into the same place of `out`.
    pub fn select_lanes(&self, jobs: &[(&ShadingPoint, f32)], out: &mut [Option<Selection>]) {
        self.select_lanes_with(jobs, out, true);
    }

    /// [`BvhSelector::select_lanes`], in pairs only where `pairs` and the processor
    /// has AVX2.
    fn select_lanes_with(
        &self,
        jobs: &[(&ShadingPoint, f32)],
        out: &mut [Option<Selection>],
        pairs: bool,
    ) {
        assert!(jobs.len() <= LANES && out.len() == jobs.len());
        if self.single.is_some() || self.nodes.is_empty() {
            for (o, &(at, u)) in out.iter_mut().zip(jobs) {
                *o = self.select(at, u);
            }
            return;
        }
        let mut walks = Walks {
            jobs,
            out,
            walks: [Walk::default(); LANES],
            active: [0; LANES],
            count: 0,
            kept: 0,
            share: self.tree_share(),
        };
        for (j, &(_, u)) in jobs.iter().enumerate() {
            match self.entry(u) {
                Err(infinite) => walks.out[j] = Some(infinite),
                Ok(u) => {
                    walks.walks[j] = Walk::from_root(u);
                    walks.active[walks.count] = j as u8;
                    walks.count += 1;
                }
            }
        }
        #[cfg(target_arch = "x86_64")]
        if pairs && std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2, checked just above.
            return unsafe { self.walk_pairs(&mut walks) };
        }
        // Other processors walk one at a time.
        #[cfg(not(target_arch = "x86_64"))]
        let _ = pairs;
        self.walk(&mut walks);
    }

    /// Takes every walk of `walks` to its end, level by level, one walk at a time.
    fn walk(&self, walks: &mut Walks<'_>) {
        while walks.count > 0 {
            walks.kept = 0;
            self.singles(walks, 0);
            walks.count = walks.kept;
        }
    }

    /// [`BvhSelector::walk`], two walks at a time through [`importance_pair`] (the
    /// last alone where a level has an odd number).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn walk_pairs(&self, walks: &mut Walks<'_>) {
        let nodes = &self.nodes;
        while walks.count > 0 {
            walks.kept = 0;
            let mut k = 0;
            while k + 1 < walks.count {
                let (i, j) = (walks.active[k] as usize, walks.active[k + 1] as usize);
                let a = &nodes[walks.walks[i].node as usize];
                let b = &nodes[walks.walks[j].node as usize];
                let (ia, ib) = importance_pair(a, walks.jobs[i].0, b, walks.jobs[j].0);
                walks.step(i, a, &ia);
                walks.step(j, b, &ib);
                k += 2;
            }
            self.singles(walks, k);
            walks.count = walks.kept;
        }
    }

    /// The steps of the walks `walks.active[from..walks.count]` at this level, one at a
    /// time.
    #[inline(always)]
    fn singles(&self, walks: &mut Walks<'_>, from: usize) {
        for k in from..walks.count {
            let j = walks.active[k] as usize;
            let node = &self.nodes[walks.walks[j].node as usize];
            walks.step(j, node, &node.importance(walks.jobs[j].0));
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::light::select::{LightSelect, Selector};
    use crate::light::{Environment, Light};
    use crate::math::Spectrum;
    use crate::sampling::Rng32;
    use crate::scene::load;

    /// Walked together, in pairs or not, every selection is the one-at-a-time one bit
    /// for bit (whose walk finds each child by the other search, `Search::Linear`),
    /// with 1 to 8 jobs at a time: on trees of rectangles and spheres
    /// (`shirley-100`), of 256 triangles (`mesh_ply_serialized`), of point lights
    /// (`tent_point`) and with a light at infinity beside the tree (`shirley-100` under
    /// a constant sky); from points anywhere in the scene's bounds, facing anywhere
    /// (some see no light), with numbers at 0 and just below 1.
    #[test]
    fn walks_together_choose_what_one_walk_chooses() {
        for spec in [
            "builtin:shirley-100",
            "tests/scenes/mesh_ply_serialized.xml",
            "tests/scenes/tent_point.xml",
            "builtin:shirley-100 under a sky",
        ] {
            let scene = load(spec.split(' ').next().expect("a name")).expect("scene");
            let mut lights = scene.lights.clone();
            if spec.contains("sky") {
                lights.push(Light::Environment(Environment::constant(Spectrum::ONE)));
            }
            let Selector::Bvh(bvh) = Selector::new(LightSelect::Bvh, &lights) else {
                panic!("{spec}: not a tree");
            };
            assert!(bvh.node_count() > 0, "{spec}");
            let bounds = scene.geometry.bounds();
            let mut rng = Rng32::new(0x005e_ed0f_1a11 + spec.len() as u64);
            let mut next = || rng.next_f32();
            let (mut chosen, mut none, mut infinite) = (0, 0, 0);
            for i in 0..4_000 {
                let n = 1 + i % LANES;
                let points: Vec<ShadingPoint> = (0..n)
                    .map(|_| {
                        let t = Vec3::new(next(), next(), next());
                        let p = bounds.min + t * (bounds.max - bounds.min);
                        let d = Vec3::new(next(), next(), next()) * 2.0 - 1.0;
                        let n = d.normalize_or(Vec3::Y);
                        ShadingPoint { p, ng: n, n }
                    })
                    .collect();
                let jobs: Vec<(&ShadingPoint, f32)> = points
                    .iter()
                    .enumerate()
                    .map(|(k, at)| {
                        let u = match (i + k) % 13 {
                            0 => 0.0,
                            1 => 1.0 - f32::EPSILON / 2.0,
                            _ => next(),
                        };
                        (at, u)
                    })
                    .collect();
                for pairs in [true, false] {
                    let mut out = vec![None; n];
                    bvh.select_lanes_with(&jobs, &mut out, pairs);
                    for (k, (&(at, u), got)) in jobs.iter().zip(&out).enumerate() {
                        let one = bvh.select(at, u);
                        assert_eq!(
                            got.map(|s| (s.index, s.pmf.to_bits(), s.u_reused.to_bits())),
                            one.map(|s| (s.index, s.pmf.to_bits(), s.u_reused.to_bits())),
                            "{spec}: call {i}, job {k}, pairs {pairs}"
                        );
                        if pairs {
                            match one {
                                None => none += 1,
                                Some(s) if lights[s.index].is_infinite() => infinite += 1,
                                Some(_) => chosen += 1,
                            }
                        }
                    }
                }
            }
            // Lights chosen and points that see none; the sky where there is one.
            assert!(
                chosen > 5_000 && none > 100,
                "{spec}: {chosen} chosen, {none} none"
            );
            assert_eq!(infinite > 1_000, spec.contains("sky"), "{spec}: {infinite}");
        }
    }
}
