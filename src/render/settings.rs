//! Everything that describes a render besides the scene: strategies, sampler, sample
//! budget, seed, resolution and pass. Every strategy is a value with one CLI name.

use std::fmt;
use std::str::FromStr;

use crate::image::Filter;
use crate::integrator::{EstimatorKind, MisSettings};
use crate::light::LightSampling;
use crate::light::select::LightSelect;
use crate::render::camera::Camera;
use crate::sampling::SamplerKind;
use crate::scene::Scene;

/// The share of the samples a render computes: pass `index` of `count` (1-based in the
/// CLI as `I/N`, stored 0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pass {
    /// 0-based pass index.
    pub index: u32,
    /// Number of passes.
    pub count: u32,
}

impl Pass {
    /// The whole render.
    pub const WHOLE: Pass = Pass { index: 0, count: 1 };

    /// Sample indices [first, last) of this pass out of `spp`: the same indices (and so
    /// the same random streams) a single render would use for them.
    pub fn sample_range(&self, spp: u32) -> (u32, u32) {
        let split = |i: u32| ((spp as u64 * i as u64) / self.count as u64) as u32;
        (split(self.index), split(self.index + 1))
    }
}

impl fmt::Display for Pass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index + 1, self.count)
    }
}

impl FromStr for Pass {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let err = || format!("bad pass \"{s}\": expected I/N with 1 ≤ I ≤ N, e.g. 2/8");
        let (i, n) = s.split_once('/').ok_or_else(err)?;
        let (i, n): (u32, u32) = (
            i.trim().parse().map_err(|_| err())?,
            n.trim().parse().map_err(|_| err())?,
        );
        if i == 0 || n == 0 || i > n {
            return Err(err());
        }
        Ok(Pass {
            index: i - 1,
            count: n,
        })
    }
}

/// A complete description of how to render a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Direct-lighting estimator.
    pub estimator: EstimatorKind,
    /// Heuristic and sample counts of the `mis` estimator.
    pub mis: MisSettings,
    /// Sampling strategy of area lights.
    pub light_sampling: LightSampling,
    /// Light selection.
    pub light_select: LightSelect,
    /// Random number source.
    pub sampler: SamplerKind,
    /// Samples per pixel (of the whole render, over all passes).
    pub spp: u32,
    /// Seed of every random stream.
    pub seed: u64,
    /// Image size override.
    pub resolution: Option<(u32, u32)>,
    /// Which share of the samples to render.
    pub pass: Pass,
    /// Pixel reconstruction filter (the one-pixel box unless a scene file asks).
    pub filter: Filter,
    /// MIS compensation of environment-map sampling (Karlík et al. 2019); applied only
    /// with the `mis` estimator, where it stays unbiased.
    pub envmap_compensation: bool,
}

impl RenderSettings {
    /// The defaults for `scene`: MIS (one light and one BSDF sample, power heuristic) with
    /// the best light sampling per shape, light-BVH selection and the Sobol sampler at the
    /// scene's spp, and the one-pixel box filter; a scene file's requests (filter, sampler,
    /// seed, MIS sample counts) replace these.
    pub fn for_scene(scene: &Scene) -> RenderSettings {
        let asked = &scene.requested;
        RenderSettings {
            estimator: EstimatorKind::Mis,
            mis: asked.mis.unwrap_or_default(),
            light_sampling: LightSampling::Best,
            light_select: LightSelect::Bvh,
            sampler: asked.sampler.unwrap_or(SamplerKind::Sobol),
            spp: scene.spp,
            seed: asked.seed.unwrap_or(0),
            resolution: None,
            pass: Pass::WHOLE,
            filter: asked.filter,
            envmap_compensation: false,
        }
    }

    /// The camera with the resolution override applied.
    pub fn camera(&self, scene: &Scene) -> Camera {
        match self.resolution {
            Some((w, h)) => scene.camera.with_resolution(w, h),
            None => scene.camera.clone(),
        }
    }

    /// The strategy flags that reproduce these settings on the command line.
    pub fn flags(&self) -> String {
        let compensation = if self.envmap_compensation {
            " --envmap-compensation"
        } else {
            ""
        };
        format!(
            "--estimator {} --mis {} --light-samples {} --bsdf-samples {} --light-sampling {} \
             --light-select {} --sampler {} --spp {} --seed {}{}",
            self.estimator,
            self.mis.heuristic,
            self.mis.light_samples,
            self.mis.bsdf_samples,
            self.light_sampling,
            self.light_select,
            self.sampler,
            self.spp,
            self.seed,
            compensation
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_partition_the_samples() {
        let spp = 37;
        let mut next = 0;
        for i in 0..5 {
            let (a, b) = Pass { index: i, count: 5 }.sample_range(spp);
            assert_eq!(a, next);
            next = b;
        }
        assert_eq!(next, spp);
        assert_eq!("2/8".parse::<Pass>().unwrap(), Pass { index: 1, count: 8 });
        for bad in ["0/3", "4/3", "x", "1/0"] {
            assert!(bad.parse::<Pass>().is_err());
        }
    }
}
