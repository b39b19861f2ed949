//! Render flags shared by the lab's subcommands (`reference`, `compare`, `converge`,
//! `figure`): they apply to every strategy, as a patch laid under each strategy's own.

use clap::Args;

use super::args::{LabPatchArgs, thread_pool};
use crate::settings::RenderPatch;

/// Flags applied to every render of an experiment.
#[derive(Args, Debug, Clone, Default)]
pub struct LabRenderArgs {
    /// Image size, seed and sampler of every render.
    #[command(flatten)]
    pub patch: LabPatchArgs,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
}

impl LabRenderArgs {
    /// The flags as a settings patch.
    pub fn base(&self) -> RenderPatch {
        self.patch.0.clone()
    }

    /// Runs `work` on a pool of `--threads` workers.
    pub fn install<T: Send>(&self, work: impl FnOnce() -> T + Send) -> Result<T, super::CliError> {
        Ok(thread_pool(self.threads)?.install(work))
    }
}
