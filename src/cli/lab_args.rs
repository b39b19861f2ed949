//! Render flags shared by the lab's subcommands (`reference`, `compare`, `converge`,
//! `figure`): they apply to every strategy, as flags placed before the strategy's own.

use clap::Args;

use crate::sampling::SamplerKind;

/// Flags applied to every render of an experiment.
#[derive(Args, Debug, Clone, Default)]
pub struct LabRenderArgs {
    /// Image width (height follows the scene's aspect unless given).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height.
    #[arg(long)]
    pub height: Option<u32>,
    /// Seed of every random stream.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Sampler: independent, stratified, sobol.
    #[arg(long)]
    pub sampler: Option<SamplerKind>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
}

impl LabRenderArgs {
    /// The flags as render-flag tokens (`--width 64 --seed 3`).
    pub fn base_flags(&self) -> Vec<String> {
        let mut out = Vec::new();
        let mut push = |flag: &str, value: Option<String>| {
            if let Some(v) = value {
                out.push(flag.to_string());
                out.push(v);
            }
        };
        push("--width", self.width.map(|v| v.to_string()));
        push("--height", self.height.map(|v| v.to_string()));
        push("--seed", self.seed.map(|v| v.to_string()));
        push("--sampler", self.sampler.map(|v| v.to_string()));
        out
    }

    /// Runs `work` on a pool of `--threads` workers.
    pub fn install<T: Send>(&self, work: impl FnOnce() -> T + Send) -> Result<T, super::CliError> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0))
            .build()
            .map_err(super::CliError::failure)?;
        Ok(pool.install(work))
    }
}
