//! A strategy in a comparison: a label and a settings patch.
//!
//! A strategy is written `label:flags` (`"light:--estimator light --light-sampling area"`),
//! or as a preset: any estimator name (`cosine` means `--estimator cosine`), any sampler
//! name (`sobol` means `--sampler sobol`), or `default` (the scene's defaults). The flags
//! are read once, here, into a [`RenderPatch`]; experiments lay patches, never strings.

use crate::settings::{EstimatorKind, RenderPatch, SamplerKind};

/// A labelled settings patch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Strategy {
    /// Name shown in tables, plots and file names.
    pub label: String,
    /// What the strategy changes over the scene's defaults and the experiment's flags.
    pub patch: RenderPatch,
}

impl Strategy {
    /// A strategy from `label` and `patch`.
    pub fn new(label: impl Into<String>, patch: RenderPatch) -> Strategy {
        Strategy {
            label: label.into(),
            patch,
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
            let patch = flags
                .parse::<RenderPatch>()
                .map_err(|e| format!("strategy \"{label}\" (`{}`): {e}", flags.trim()))?;
            return Ok(Strategy::new(label, patch));
        }
        if text == "default" {
            return Ok(Strategy::new("default", RenderPatch::default()));
        }
        if let Ok(kind) = text.parse::<SamplerKind>() {
            let patch = RenderPatch {
                sampler: Some(kind),
                ..Default::default()
            };
            return Ok(Strategy::new(text, patch));
        }
        match text.parse::<EstimatorKind>() {
            Ok(kind) => Ok(Strategy::new(
                text,
                RenderPatch {
                    estimator: Some(kind),
                    ..Default::default()
                },
            )),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_labels_and_flags() {
        let list = Strategy::parse_list("cosine, light:--estimator light --spp 3,default").unwrap();
        assert_eq!(list[0].patch.to_string(), "--estimator cosine");
        assert_eq!(list[1].label, "light");
        assert_eq!(list[1].patch.to_string(), "--estimator light --spp 3");
        assert!(list[2].patch.is_empty());
        assert!(Strategy::parse_list("a:--spp 1,a:--spp 2").is_err());
        assert!(Strategy::parse("nonsense").is_err());
        assert_eq!(
            Strategy::parse("sobol").unwrap().patch.to_string(),
            "--sampler sobol"
        );
    }

    #[test]
    fn unknown_values_and_flags_are_named() {
        let e = Strategy::parse("x:--estimator nope").unwrap_err();
        assert!(e.contains("strategy \"x\"") && e.contains("nope"), "{e}");
        let e = Strategy::parse("x:--no-such-flag 3").unwrap_err();
        assert!(e.contains("--no-such-flag"), "{e}");
        assert_eq!(slug("MIS (balance)"), "mis-balance");
    }
}
