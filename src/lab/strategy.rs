//! A strategy in a comparison: a label and a string of render flags, parsed at run time
//! by the same parser as `lightlab render`, so every flag another module adds to
//! [`StrategyArgs`] works here without a second list.
//!
//! A strategy is written `label:flags` (`"light:--estimator light --light-sampling area"`),
//! or as a preset: any estimator name (`cosine` means `--estimator cosine`), any sampler
//! name (`sobol` means `--sampler sobol`), or `default` (the scene's defaults).

use std::fmt;

use clap::Parser;
use clap::error::{ContextKind, ContextValue, ErrorKind};

use crate::cli::StrategyArgs;
use crate::integrator::EstimatorKind;
use crate::render::RenderSettings;
use crate::sampling::SamplerKind;
use crate::scene::Scene;

/// A labelled set of render flags.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Strategy {
    /// Name shown in tables, plots and file names.
    pub label: String,
    /// Flags as on the `render` command line, e.g. `--estimator light`.
    pub flags: String,
}

/// Why a strategy (or the scene of an experiment) cannot be used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StrategyError {
    /// A flag value this build does not know: (flag, value, parser message).
    UnknownValue(String, String, String),
    /// A flag this build does not have.
    UnknownFlag(String),
    /// Anything else the parser rejected (message).
    Invalid(String),
}

impl StrategyError {
    /// What is missing, in a few words: "estimator `mis`", "flag `--light-samples`".
    pub fn missing(&self) -> String {
        match self {
            StrategyError::UnknownValue(flag, value, _) => {
                format!(
                    "{} `{value}`",
                    flag.trim_start_matches('-').replace('-', " ")
                )
            }
            StrategyError::UnknownFlag(flag) => format!("flag `{flag}`"),
            StrategyError::Invalid(m) => m.clone(),
        }
    }
}

impl fmt::Display for StrategyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StrategyError::UnknownValue(_, _, message) => f.write_str(message),
            StrategyError::UnknownFlag(flag) => write!(f, "this build has no flag `{flag}`"),
            StrategyError::Invalid(m) => f.write_str(m),
        }
    }
}

/// The render flags parser: `StrategyArgs` alone, a later flag overriding an earlier one.
#[derive(Parser, Debug)]
#[command(no_binary_name = true, args_override_self = true)]
struct FlagParser {
    #[command(flatten)]
    strategy: StrategyArgs,
}

impl Strategy {
    /// A strategy from `label` and `flags`.
    pub fn new(label: impl Into<String>, flags: impl Into<String>) -> Strategy {
        Strategy {
            label: label.into(),
            flags: flags.into(),
        }
    }

    /// Parses `label:flags` or a preset name (an estimator or sampler name, or `default`).
    pub fn parse(text: &str) -> Result<Strategy, String> {
        let text = text.trim();
        if let Some((label, flags)) = text.split_once(':') {
            let label = label.trim();
            if label.is_empty() {
                return Err(format!("strategy \"{text}\" has an empty label"));
            }
            return Ok(Strategy::new(label, flags.trim()));
        }
        if text == "default" {
            return Ok(Strategy::new("default", ""));
        }
        if let Ok(kind) = text.parse::<SamplerKind>() {
            return Ok(Strategy::new(text, format!("--sampler {kind}")));
        }
        match text.parse::<EstimatorKind>() {
            Ok(kind) => Ok(Strategy::new(text, format!("--estimator {kind}"))),
            Err(e) => Err(format!(
                "strategy \"{text}\" is neither LABEL:FLAGS nor a preset (default, a sampler name, or an {e})"
            )),
        }
    }

    /// Parses a comma-separated list (`light,bsdf,"mis:--estimator mis"`); labels must
    /// be distinct.
    pub fn parse_list(text: &str) -> Result<Vec<Strategy>, String> {
        let list: Vec<Strategy> = text
            .split(',')
            .filter(|s| !s.trim().is_empty())
            .map(Strategy::parse)
            .collect::<Result<_, _>>()?;
        if list.is_empty() {
            return Err("no strategies given".into());
        }
        for (i, s) in list.iter().enumerate() {
            if list[..i].iter().any(|o| o.label == s.label) {
                return Err(format!("strategy label \"{}\" is used twice", s.label));
            }
        }
        Ok(list)
    }

    /// The settings for `scene`: the scene's defaults, then `base` flags (the
    /// experiment's render flags, applied to every strategy), then this strategy's flags,
    /// then `extra` (the experiment's budget, e.g. `--spp 16`); later flags win.
    pub fn settings(
        &self,
        scene: &Scene,
        base: &[String],
        extra: &[String],
    ) -> Result<RenderSettings, StrategyError> {
        let tokens: Vec<String> = base
            .iter()
            .cloned()
            .chain(self.flags.split_whitespace().map(str::to_string))
            .chain(extra.iter().cloned())
            .collect();
        let parsed = FlagParser::try_parse_from(&tokens).map_err(clap_error)?;
        parsed
            .strategy
            .settings(scene)
            .map_err(|e| StrategyError::Invalid(e.message))
    }

    /// The label as a file name: lower-case letters, digits and `-`.
    pub fn slug(&self) -> String {
        slug(&self.label)
    }
}

/// `text` reduced to lower-case ASCII letters, digits and single `-`.
pub fn slug(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    let out = out.trim_matches('-').to_string();
    if out.is_empty() { "s".into() } else { out }
}

/// Names the flag and value a clap error is about.
fn clap_error(e: clap::Error) -> StrategyError {
    let context = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let flag = context(ContextKind::InvalidArg).map(|f| {
        // "--estimator <ESTIMATOR>" -> "--estimator"
        f.split_whitespace().next().unwrap_or("").to_string()
    });
    let first_line = e.to_string().lines().next().unwrap_or("").to_string();
    let message = first_line.trim_start_matches("error: ").to_string();
    match (e.kind(), flag) {
        (ErrorKind::InvalidValue | ErrorKind::ValueValidation, Some(flag)) => {
            let value = context(ContextKind::InvalidValue).unwrap_or_default();
            StrategyError::UnknownValue(flag, value, message)
        }
        (ErrorKind::UnknownArgument, Some(flag)) => StrategyError::UnknownFlag(flag),
        _ => StrategyError::Invalid(message),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    #[test]
    fn presets_labels_and_overrides() {
        let list = Strategy::parse_list("cosine, light:--estimator light --spp 3,default").unwrap();
        assert_eq!(list[0], Strategy::new("cosine", "--estimator cosine"));
        assert_eq!(list[1].label, "light");
        assert!(Strategy::parse_list("a:--spp 1,a:--spp 2").is_err());
        assert!(Strategy::parse("nonsense").is_err());
        assert_eq!(
            Strategy::parse("sobol").unwrap(),
            Strategy::new("sobol", "--sampler sobol")
        );
        let scene = scene::load("builtin:assignment").unwrap();
        let base = [
            "--seed".to_string(),
            "5".to_string(),
            "--width".into(),
            "8".into(),
        ];
        let s = list[1]
            .settings(&scene, &base, &["--spp".into(), "7".into()])
            .unwrap();
        assert_eq!((s.seed, s.spp, s.resolution.map(|r| r.0)), (5, 7, Some(8)));
        assert_eq!(s.estimator, EstimatorKind::Light);
    }

    #[test]
    fn unknown_values_and_flags_are_named() {
        let scene = scene::load("builtin:assignment").unwrap();
        let e = Strategy::new("x", "--estimator nope")
            .settings(&scene, &[], &[])
            .unwrap_err();
        assert_eq!(e.missing(), "estimator `nope`");
        let e = Strategy::new("x", "--no-such-flag 3")
            .settings(&scene, &[], &[])
            .unwrap_err();
        assert_eq!(e.missing(), "flag `--no-such-flag`");
        assert_eq!(slug("MIS (balance)"), "mis-balance");
    }
}
