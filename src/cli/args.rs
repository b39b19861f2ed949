//! The render flags on the command line: clap reads them straight into a settings
//! [`RenderPatch`], from the patch's own table of flags (`RenderPatch::VALUE_FLAGS`), so
//! no second list of flags is kept here.

use clap::error::ErrorKind;
use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches};

use super::CliError;
use crate::names::flag;
use crate::render::RenderSettings;
use crate::scene::Scene;
use crate::settings::RenderPatch;

/// Every render flag (strategies, sampler, budget, image size, pass).
#[derive(Debug, Clone, Default)]
pub struct StrategyArgs(pub RenderPatch);

/// The render flags a lab experiment applies to all of its strategies.
#[derive(Debug, Clone, Default)]
pub struct LabPatchArgs(pub RenderPatch);

/// The flags of [`LabPatchArgs`].
const LAB_FLAGS: [&str; 4] = [flag::WIDTH, flag::HEIGHT, flag::SEED, flag::SAMPLER];

/// The render flags `export` writes into the file: film size, samples, sampler, seed.
#[derive(Debug, Clone, Default)]
pub struct ExportPatchArgs(pub RenderPatch);

/// The flags of [`ExportPatchArgs`].
const EXPORT_FLAGS: [&str; 5] = [
    flag::WIDTH,
    flag::HEIGHT,
    flag::SPP,
    flag::SAMPLER,
    flag::SEED,
];

/// Adds the value flags `names` (and the compensation switch if `switch`) to `cmd`.
fn augment(cmd: Command, names: &[&'static str], switch: bool) -> Command {
    let mut cmd = cmd;
    for (name, help) in RenderPatch::VALUE_FLAGS {
        if names.contains(name) {
            cmd = cmd.arg(
                Arg::new(*name)
                    .long(*name)
                    .help(*help)
                    .value_name(name.to_uppercase().replace('-', "_"))
                    .action(ArgAction::Set)
                    // `--spp -1` is a bad value of --spp, not an unknown flag `-1`.
                    .allow_hyphen_values(true),
            );
        }
    }
    if switch {
        cmd = cmd.arg(
            Arg::new(flag::ENVMAP_COMPENSATION)
                .long(flag::ENVMAP_COMPENSATION)
                .help(
                    "MIS compensation of environment-map sampling (Karlík et al. 2019): sample \
                     ∝ max(0, L − mean L), and a constant environment not at all (the BSDF \
                     samples light it). The default with --estimator mis; an error with the \
                     other estimators, for which it would be biased.",
                )
                .action(ArgAction::SetTrue)
                .overrides_with(flag::NO_ENVMAP_COMPENSATION),
        );
        cmd = cmd.arg(
            Arg::new(flag::NO_ENVMAP_COMPENSATION)
                .long(flag::NO_ENVMAP_COMPENSATION)
                .help(
                    "Environment maps sampled ∝ L under --estimator mis too (Mitsuba 3's \
                     choice; pbrt-v4's path integrator compensates), instead of the \
                     compensated distribution.",
                )
                .action(ArgAction::SetTrue)
                .overrides_with(flag::ENVMAP_COMPENSATION),
        );
    }
    cmd
}

/// Reads the flags `names` (and the switch if `switch`) into a patch.
fn read(m: &ArgMatches, names: &[&str], switch: bool) -> Result<RenderPatch, clap::Error> {
    let mut patch = RenderPatch::default();
    for name in names {
        if let Some(value) = m.get_one::<String>(name) {
            patch
                .set(name, value)
                .map_err(|e| clap::Error::raw(ErrorKind::ValueValidation, format!("{e}\n")))?;
        }
    }
    if switch && m.get_flag(flag::ENVMAP_COMPENSATION) {
        patch.envmap_compensation = Some(true);
    }
    if switch && m.get_flag(flag::NO_ENVMAP_COMPENSATION) {
        patch.envmap_compensation = Some(false);
    }
    Ok(patch)
}

/// Implements clap's `Args` for a newtype over [`RenderPatch`] with the flags `$names`.
macro_rules! patch_args {
    ($ty:ident, $names:expr, $switch:expr) => {
        impl Args for $ty {
            fn augment_args(cmd: Command) -> Command {
                augment(cmd, &$names, $switch)
            }
            fn augment_args_for_update(cmd: Command) -> Command {
                augment(cmd, &$names, $switch)
            }
        }

        impl FromArgMatches for $ty {
            fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
                read(m, &$names, $switch).map($ty)
            }
            fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
                self.0 = self.0.then(&read(m, &$names, $switch)?);
                Ok(())
            }
        }
    };
}

/// Every value flag's name.
fn all_flags() -> Vec<&'static str> {
    RenderPatch::VALUE_FLAGS.iter().map(|(f, _)| *f).collect()
}

patch_args!(StrategyArgs, all_flags(), true);
patch_args!(LabPatchArgs, LAB_FLAGS, false);
patch_args!(ExportPatchArgs, EXPORT_FLAGS, false);

impl StrategyArgs {
    /// The settings for `scene` with these flags laid over its defaults.
    pub fn settings(&self, scene: &Scene) -> Result<RenderSettings, CliError> {
        RenderSettings::build(scene, &[&self.0]).map_err(CliError::input)
    }
}

/// How a scene file is read: `-D` definitions and `--lenient`.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct SceneFileArgs {
    /// Set a scene file parameter: `-D spp=64` replaces `<default name="spp" .../>`.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// Accept unused and duplicated properties in the scene file with a warning (Mitsuba 3
    /// refuses them; older files may have them).
    #[arg(long)]
    pub lenient: bool,
}

impl SceneFileArgs {
    /// Loads `spec` (a file or `builtin:NAME`) with these options; a bad scene is exit 2.
    pub fn load(&self, spec: &str) -> Result<crate::scene::Scene, CliError> {
        let options = crate::scene::xml::LoadOptions {
            lenient: self.lenient,
        };
        crate::scene::load_with_options(spec, &self.define, options).map_err(CliError::input)
    }
}

/// Parses `-D NAME=VALUE`.
pub fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((n, v)) if !n.trim().is_empty() => Ok((n.trim().to_owned(), v.to_owned())),
        _ => Err(format!("expected NAME=VALUE, not \"{s}\"")),
    }
}

/// A pool of `threads` workers (all cores when `None` or 0).
pub fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(CliError::failure)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    #[command(no_binary_name = true)]
    struct Both {
        #[command(flatten)]
        all: StrategyArgs,
    }

    #[test]
    fn the_command_line_and_the_patch_parser_agree() {
        for text in [
            "--estimator light --light-sampling area --spp 16",
            "--mis balance --light-samples 2 --bsdf-samples 3 --envmap-compensation",
            "--sampler stratified --seed 9 --width 64 --height 32 --pass 2/8 --light-select power",
            "--estimator mis --no-envmap-compensation",
            // The later of the two switches wins, as with the patch parser.
            "--no-envmap-compensation --envmap-compensation",
            "--envmap-compensation --no-envmap-compensation",
        ] {
            let words: Vec<&str> = text.split_whitespace().collect();
            let cli = Both::try_parse_from(&words).unwrap().all.0;
            assert_eq!(cli, text.parse::<RenderPatch>().unwrap(), "{text}");
            assert_eq!(cli.to_string().parse::<RenderPatch>().unwrap(), cli);
        }
        let e = Both::try_parse_from(["--spp", "-1"])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("--spp -1"), "{e}");
    }
}
