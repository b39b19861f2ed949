//! Flags shared by every subcommand that renders: the strategies, sampler and budget.

use clap::Args;

use super::CliError;
use crate::integrator::{EstimatorKind, MisHeuristic};
use crate::light::LightSampling;
use crate::light::select::LightSelect;
use crate::render::{Pass, RenderSettings};
use crate::sampling::SamplerKind;
use crate::scene::Scene;

/// Strategy, sampler and budget flags.
#[derive(Args, Debug, Clone, Default)]
pub struct StrategyArgs {
    /// Direct-lighting estimator: hemisphere, hemisphere-rejection, cosine, bsdf, light, mis.
    #[arg(long)]
    pub estimator: Option<EstimatorKind>,
    /// MIS weighting: balance, power (β = 2), one-sample (balance, one strategy per sample).
    #[arg(long)]
    pub mis: Option<MisHeuristic>,
    /// Light samples per estimate of the `mis` estimator.
    #[arg(long)]
    pub light_samples: Option<u32>,
    /// BSDF samples per estimate of the `mis` estimator.
    #[arg(long)]
    pub bsdf_samples: Option<u32>,
    /// Area-light sampling strategy: area, visible-area, solid-angle, geometric, best (default;
    /// per shape). A shape without the chosen strategy uses area.
    #[arg(long)]
    pub light_sampling: Option<LightSampling>,
    /// MIS compensation of environment-map sampling (Karlík et al. 2019): sample
    /// ∝ max(0, L − mean L). Unbiased only with `--estimator mis`, so required with it.
    #[arg(long)]
    pub envmap_compensation: bool,
    /// Light selection among many lights: uniform, power, adaptive, bvh (default).
    #[arg(long)]
    pub light_select: Option<LightSelect>,
    /// Sampler: independent, stratified, sobol.
    #[arg(long)]
    pub sampler: Option<SamplerKind>,
    /// Samples per pixel (default: the scene's).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Seed of every random stream.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Image width (overrides the scene's; height follows the aspect unless given).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height.
    #[arg(long)]
    pub height: Option<u32>,
    /// Render only pass I of N (sample indices split evenly): `--pass 2/8`.
    #[arg(long)]
    pub pass: Option<Pass>,
}

impl StrategyArgs {
    /// The settings for `scene` with these flags applied over its defaults.
    pub fn settings(&self, scene: &Scene) -> Result<RenderSettings, CliError> {
        let mut s = RenderSettings::for_scene(scene);
        if let Some(v) = self.estimator {
            s.estimator = v;
        }
        if let Some(v) = self.mis {
            s.mis.heuristic = v;
        }
        for (flag, given, count) in [
            (
                "--light-samples",
                self.light_samples,
                &mut s.mis.light_samples,
            ),
            ("--bsdf-samples", self.bsdf_samples, &mut s.mis.bsdf_samples),
        ] {
            if let Some(v) = given {
                if !(1..=1024).contains(&v) {
                    return Err(CliError::input(format!(
                        "{flag} must be in 1..=1024, not {v}"
                    )));
                }
                *count = v;
            }
        }
        if self.envmap_compensation {
            if s.estimator != EstimatorKind::Mis {
                return Err(CliError::input(format!(
                    "--envmap-compensation is unbiased only with --estimator mis, not {}",
                    s.estimator
                )));
            }
            s.envmap_compensation = true;
        }
        if let Some(v) = self.light_sampling {
            s.light_sampling = v;
        }
        if let Some(v) = self.light_select {
            s.light_select = v;
        }
        if let Some(v) = self.sampler {
            s.sampler = v;
        }
        if let Some(v) = self.spp {
            if v == 0 {
                return Err(CliError::input("--spp must be at least 1"));
            }
            s.spp = v;
        }
        if let Some(v) = self.seed {
            s.seed = v;
        }
        if let Some(v) = self.pass {
            s.pass = v;
        }
        let (cw, ch) = (scene.camera.width, scene.camera.height);
        s.resolution = match (self.width, self.height) {
            (None, None) => None,
            (Some(w), None) => Some((w, ((w as u64 * ch as u64) / cw as u64).max(1) as u32)),
            (None, Some(h)) => Some((((h as u64 * cw as u64) / ch as u64).max(1) as u32, h)),
            (Some(w), Some(h)) => Some((w, h)),
        };
        if let Some((w, h)) = s.resolution
            && (w == 0 || h == 0 || w > 32768 || h > 32768)
        {
            return Err(CliError::input(format!(
                "image size {w}x{h} is out of range (1..=32768)"
            )));
        }
        Ok(s)
    }
}

/// Parses `-D NAME=VALUE`.
pub fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((n, v)) if !n.trim().is_empty() => Ok((n.trim().to_owned(), v.to_owned())),
        _ => Err(format!("expected NAME=VALUE, not \"{s}\"")),
    }
}
